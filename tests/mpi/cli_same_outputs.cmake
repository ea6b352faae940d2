# mpirun -np K panelrad solve / cube (K = 1, 2, 3, oversubscribed) against the program run alone:
# the solve's CSV (every value in 17 significant digits, so equal files are equal bits) byte for
# byte, on the Cornell box (occluded: V computed, each rank classifying the pairs of its rows) at
# n = 3072; the cube's CSV without its times (the error (51) in 7 digits, products, ratio (36):
# its bits are compared by test_mpi_solves); only rank 0 writes (one 'wrote' line).
# Run: cmake -DMPIEXEC=mpirun -DPANELRAD=<program> -DSOURCE_DIR=<project> -DWORK_DIR=<dir> -P cli_same_outputs.cmake
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(scene "${SOURCE_DIR}/examples/scenes/cornell_box.obj")
set(solve_args solve "${scene}" --levels 3 --method fast --formats csv --quiet)
set(cube_args cube --accuracy manual --method fast --eta 0.4 --degree 4 --min-level 3 --levels 4)

function(run_checked name)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK_DIR}" RESULT_VARIABLE status
                  OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${name}: exit status ${status}\n${out}\n${err}")
  endif()
  set(${name}_out "${out}" PARENT_SCOPE)
  set(${name}_err "${err}" PARENT_SCOPE)
endfunction()

# The cube's CSV without its times and memory: method, near, eta, mu, degree, n, max_error (51),
# iterations, conv_ratio (36) of each level.
function(cube_numbers csv result)
  file(STRINGS "${csv}" lines)
  set(kept "")
  foreach(line IN LISTS lines)
    string(REPLACE "," ";" fields "${line}")
    foreach(k 0 1 2 3 4 5 6 9 10)
      list(GET fields ${k} field)
      string(APPEND kept "${field} ")
    endforeach()
    string(APPEND kept "\n")
  endforeach()
  set(${result} "${kept}" PARENT_SCOPE)
endfunction()

run_checked(alone "${PANELRAD}" ${solve_args} --out alone)
run_checked(cube_alone "${PANELRAD}" ${cube_args} --csv cube_alone.csv)
cube_numbers("${WORK_DIR}/cube_alone.csv" cube_alone)
foreach(ranks 1 2 3)
  run_checked(shared "${MPIEXEC}" -np ${ranks} --oversubscribe "${PANELRAD}" ${solve_args} --out np${ranks})
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK_DIR}/alone.csv" "${WORK_DIR}/np${ranks}.csv"
                  RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "solve on ${ranks} ranks: np${ranks}.csv differs from alone.csv")
  endif()
  string(REGEX MATCHALL "wrote " wrote "${shared_out}")
  list(LENGTH wrote writes)
  if(NOT writes EQUAL 1)
    message(FATAL_ERROR "solve on ${ranks} ranks: ${writes} 'wrote' lines (only rank 0 writes):\n${shared_out}")
  endif()
  run_checked(cube_shared "${MPIEXEC}" -np ${ranks} --oversubscribe "${PANELRAD}" ${cube_args} --csv cube_np${ranks}.csv)
  cube_numbers("${WORK_DIR}/cube_np${ranks}.csv" cube_ranks)
  if(NOT cube_ranks STREQUAL cube_alone)
    message(FATAL_ERROR "cube on ${ranks} ranks:\n${cube_ranks}\nalone:\n${cube_alone}")
  endif()
  message(STATUS "${ranks} ranks: the solve's CSV and the cube's table as one process's")
endforeach()
