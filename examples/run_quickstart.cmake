# Runs examples/quickstart in DIR and checks what it promises: a converged solve of the Cornell
# box at level 3 (n = 64 n0), its summary line, and the files cornell.csv and cornell.png.
# Run: cmake -DPROGRAM=<quickstart> -DDIR=<dir with examples/ linked> -P run_quickstart.cmake
file(REMOVE ${DIR}/cornell.csv ${DIR}/cornell.png)
execute_process(COMMAND ${PROGRAM} WORKING_DIRECTORY ${DIR} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "quickstart exited with ${status}:\n${out}${err}")
endif()
if(NOT out MATCHES "^n = [0-9]+, ")
  message(FATAL_ERROR "quickstart printed no summary line:\n${out}")
endif()
foreach(f cornell.csv cornell.png)
  if(NOT EXISTS ${DIR}/${f})
    message(FATAL_ERROR "quickstart did not write ${f}")
  endif()
endforeach()
file(STRINGS ${DIR}/cornell.csv rows)
list(LENGTH rows count)
string(REGEX REPLACE "^n = ([0-9]+),.*$" "\\1" n "${out}")
math(EXPR expected "${n} + 1")  # a header line, then one row per element
if(NOT count EQUAL expected)
  message(FATAL_ERROR "cornell.csv has ${count} lines, expected ${expected} (n = ${n})")
endif()
message(STATUS "quickstart: ${out}")
