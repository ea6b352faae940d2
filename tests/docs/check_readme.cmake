# Checks the README against the code it quotes:
#   - the ```cpp block that follows the line `<!-- examples/quickstart.cpp -->` in README.md is
#     exactly the text of examples/quickstart.cpp, and the ```python block that follows the line
#     `<!-- examples/python/quickstart.py -->` exactly the text of examples/python/quickstart.py
#     (a trailing newline aside); both programs run as tests (example_quickstart, python_tests);
#   - README.md has at most 150 lines (a front page; the reference is in docs/).
# Run: cmake -DSOURCE_DIR=<project> [-DREADME=<file>] [-DQUICKSTART=<file>] [-DPYTHON_QUICKSTART=<file>]
#      -P check_readme.cmake
# (fails with the reason and the first line that differs).
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "check_readme: set -DSOURCE_DIR")
endif()
if(NOT README)
  set(README "${SOURCE_DIR}/README.md")
endif()
if(NOT QUICKSTART)
  set(QUICKSTART "${SOURCE_DIR}/examples/quickstart.cpp")
endif()
if(NOT PYTHON_QUICKSTART)
  set(PYTHON_QUICKSTART "${SOURCE_DIR}/examples/python/quickstart.py")
endif()
set(max_lines 150)

foreach(f IN ITEMS "${README}" "${QUICKSTART}" "${PYTHON_QUICKSTART}")
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "check_readme: ${f} does not exist")
  endif()
endforeach()
file(READ "${README}" readme)

# Length: the number of lines, counting a last line without its newline.
string(REGEX MATCHALL "\n" newlines "${readme}")
list(LENGTH newlines lines)
if(NOT readme MATCHES "\n$" AND NOT readme STREQUAL "")
  math(EXPR lines "${lines} + 1")
endif()
if(lines GREATER max_lines)
  message(FATAL_ERROR "check_readme: ${README} has ${lines} lines, more than ${max_lines}: "
                      "move reference material to docs/")
endif()

# check_block(MARKER LANGUAGE FILE): the block after the line MARKER, then (blank lines aside) a
# line ```LANGUAGE, up to the next line ```, is the text of FILE.
function(check_block marker language source)
  file(READ "${source}" expected)
  string(FIND "${readme}" "${marker}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "check_readme: ${README} has no line '${marker}'")
  endif()
  string(LENGTH "${marker}" marker_length)
  math(EXPR after "${at} + ${marker_length}")
  string(SUBSTRING "${readme}" ${after} -1 rest)
  if(NOT rest MATCHES "^[ \t]*\n[ \t\n]*```${language}[ \t]*\n")
    message(FATAL_ERROR "check_readme: the line after '${marker}' in ${README} is not a ```${language} block")
  endif()
  string(LENGTH "${CMAKE_MATCH_0}" opening)
  string(SUBSTRING "${rest}" ${opening} -1 rest)
  if(rest MATCHES "^```")
    set(block "")
  else()
    string(FIND "${rest}" "\n```" close)
    if(close EQUAL -1)
      message(FATAL_ERROR "check_readme: the ```${language} block after '${marker}' in ${README} is not closed")
    endif()
    string(SUBSTRING "${rest}" 0 ${close} block)
  endif()

  # Compare, a trailing newline aside.
  string(REGEX REPLACE "\n$" "" expected "${expected}")
  if(NOT block STREQUAL expected)
    # Name the first line that differs (lines compared as substrings, so ';' in the code is harmless).
    set(line 1)
    set(a "${block}\n")
    set(b "${expected}\n")
    while(TRUE)
      string(FIND "${a}" "\n" ea)
      string(FIND "${b}" "\n" eb)
      if(ea EQUAL -1 OR eb EQUAL -1)
        break()
      endif()
      string(SUBSTRING "${a}" 0 ${ea} la)
      string(SUBSTRING "${b}" 0 ${eb} lb)
      if(NOT la STREQUAL lb)
        break()
      endif()
      math(EXPR ea "${ea} + 1")
      math(EXPR eb "${eb} + 1")
      string(SUBSTRING "${a}" ${ea} -1 a)
      string(SUBSTRING "${b}" ${eb} -1 b)
      math(EXPR line "${line} + 1")
    endwhile()
    if(ea EQUAL -1)
      set(la "(end of the block)")
    endif()
    if(eb EQUAL -1)
      set(lb "(end of the file)")
    endif()
    message(FATAL_ERROR "check_readme: the ```${language} block after '${marker}' in ${README} differs from "
                        "${source} at line ${line} of the file:\n  README: ${la}\n  file:   ${lb}")
  endif()
endfunction()

check_block("<!-- examples/quickstart.cpp -->" cpp "${QUICKSTART}")
check_block("<!-- examples/python/quickstart.py -->" python "${PYTHON_QUICKSTART}")
message(STATUS "check_readme: ${README}: ${lines} lines; its quickstart blocks match ${QUICKSTART} "
               "and ${PYTHON_QUICKSTART}")
