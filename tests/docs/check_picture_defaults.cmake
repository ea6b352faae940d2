# Checks that the docs describe the picture's default camera as lib/src/io/picture_camera.cpp
# chooses it when --view / --up (write_outputs' view / up) are not given: the viewpoint from the
# scene (a room in perspective from its open side or through a wall, bodies along the brightest
# diagonal) and the up direction from the lights (y or z, never a fixed 0,0,1).
#   - docs/cli.md: the row of `--view X,Y,Z`, `--up X,Y,Z` in the options of `panelrad solve`;
#   - docs/file-formats.md: the paragraph that starts with **The picture**.
# Each must name the parts below and none of the stale defaults.
# Run: cmake -DSOURCE_DIR=<project> -P check_picture_defaults.cmake
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "check_picture_defaults: set -DSOURCE_DIR")
endif()

# The text of FILE from the first line that starts with START up to the next blank line (a table
# row, START "|...": to the end of that line).
function(paragraph file start out)
  file(READ "${SOURCE_DIR}/${file}" text)
  string(FIND "${text}" "\n${start}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "check_picture_defaults: ${file} has no line starting with '${start}'")
  endif()
  math(EXPR at "${at} + 1")
  string(SUBSTRING "${text}" ${at} -1 rest)
  if(start MATCHES "^[|]")
    string(FIND "${rest}" "\n" end)
  else()
    string(FIND "${rest}" "\n\n" end)
  endif()
  if(NOT end EQUAL -1)
    string(SUBSTRING "${rest}" 0 ${end} rest)
  endif()
  string(REPLACE "\n" " " rest "${rest}")
  set(${out} "${rest}" PARENT_SCOPE)
endfunction()

# FILE's paragraph START names each of NEEDED and none of STALE (lists of words).
function(expect file start)
  cmake_parse_arguments(ARG "" "" "NEEDED;STALE" ${ARGN})
  paragraph("${file}" "${start}" text)
  foreach(word IN LISTS ARG_NEEDED)
    string(FIND "${text}" "${word}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "check_picture_defaults: ${file}, '${start}...' does not say '${word}':\n${text}")
    endif()
  endforeach()
  foreach(word IN LISTS ARG_STALE)
    string(FIND "${text}" "${word}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "check_picture_defaults: ${file}, '${start}...' still says '${word}':\n${text}")
    endif()
  endforeach()
endfunction()

# The parts of the choice (picture_camera.cpp): rooms from the open side or through a wall, in
# perspective; bodies orthographically along the brightest of the diagonals; up from the lights.
set(choice "open side" "through" "perspective" "brightest" "diagonal" "lights")
expect(docs/cli.md "| `--view X,Y,Z`" NEEDED ${choice} "chosen from the scene" STALE "0,0,1")
expect(docs/file-formats.md "**The picture**" NEEDED ${choice} "up" STALE "0,0,1")
message(STATUS "check_picture_defaults: docs/cli.md and docs/file-formats.md describe the default camera")
