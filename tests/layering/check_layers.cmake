# Checks that every #include <panelrad/...> points down the layers, never up:
#   support -> geometry -> quadrature -> lib: scene -> operator -> distributed -> solve -> viewfactors -> thermal -> io
#   (and mpi, beside solve, on distributed) -> paper -> cli,
#   examples, bench, python (on io); and that nothing outside the tests includes the test-only oracles.
# Run: cmake -DSOURCE_DIR=<project> -P check_layers.cmake (fails with the offending file and line).
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "check_layers: set -DSOURCE_DIR")
endif()

# folder (relative to SOURCE_DIR) -> header folders under <panelrad/...> it may include
set(layer_folders
  support/include support/src geometry/include geometry/src geometry/oracles quadrature
  lib/include/panelrad/scene lib/src/scene
  lib/include/panelrad/operator lib/src/operator lib/include/panelrad/distributed lib/src/distributed
  lib/include/panelrad/mpi lib/src/mpi lib/include/panelrad/solve lib/src/solve
  lib/include/panelrad/viewfactors lib/src/viewfactors lib/include/panelrad/thermal lib/src/thermal
  lib/include/panelrad/io lib/src/io paper cli examples bench python/src)
set(allowed_support/include support)
set(allowed_support/src support)
set(allowed_geometry/include support geometry)
set(allowed_geometry/src support geometry)
set(allowed_geometry/oracles support geometry geometry/oracles)
set(allowed_quadrature support geometry quadrature)
set(allowed_lib/include/panelrad/scene ${allowed_quadrature} scene)
set(allowed_lib/src/scene ${allowed_lib/include/panelrad/scene})
set(allowed_lib/include/panelrad/operator ${allowed_lib/src/scene} operator)
set(allowed_lib/src/operator ${allowed_lib/include/panelrad/operator})
set(allowed_lib/include/panelrad/distributed ${allowed_lib/src/operator} distributed)
set(allowed_lib/src/distributed ${allowed_lib/include/panelrad/distributed})
set(allowed_lib/include/panelrad/mpi ${allowed_lib/src/distributed} mpi)
set(allowed_lib/src/mpi ${allowed_lib/include/panelrad/mpi})
set(allowed_lib/include/panelrad/solve ${allowed_lib/src/distributed} solve)
set(allowed_lib/src/solve ${allowed_lib/include/panelrad/solve})
set(allowed_lib/include/panelrad/viewfactors ${allowed_lib/src/solve} viewfactors)
set(allowed_lib/src/viewfactors ${allowed_lib/include/panelrad/viewfactors})
set(allowed_lib/include/panelrad/thermal ${allowed_lib/src/viewfactors} thermal)
set(allowed_lib/src/thermal ${allowed_lib/include/panelrad/thermal})
set(allowed_lib/include/panelrad/io ${allowed_lib/src/thermal} io)
set(allowed_lib/src/io ${allowed_lib/include/panelrad/io})
set(allowed_paper ${allowed_lib/src/io} paper)
set(allowed_cli ${allowed_paper} mpi)
set(allowed_examples ${allowed_lib/src/io})
set(allowed_bench ${allowed_paper})
set(allowed_python/src ${allowed_lib/src/io})

set(failures "")
set(checked 0)
foreach(folder IN LISTS layer_folders)
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.hpp")
  foreach(src IN LISTS sources)
    math(EXPR checked "${checked} + 1")
    file(STRINGS "${src}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*<panelrad/")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*<panelrad/([^>]*)>.*$" "\\1" target "${line}")
      # the umbrella header <panelrad/panelrad.hpp> sits at the top of lib: only for users above lib
      if(target STREQUAL "panelrad.hpp")
        set(target_folder "io")
      else()
        string(REGEX REPLACE "/[^/]*$" "" target_folder "${target}")
      endif()
      if(target MATCHES "^geometry/oracles/")
        set(target_folder "geometry/oracles")
      endif()
      if(NOT target_folder IN_LIST allowed_${folder})
        file(RELATIVE_PATH rel "${SOURCE_DIR}" "${src}")
        string(APPEND failures "  ${rel}: #include <panelrad/${target}> reaches up (allowed from ${folder}: ${allowed_${folder}})\n")
      endif()
    endforeach()
  endforeach()
endforeach()
if(checked LESS 50)
  message(FATAL_ERROR "check_layers: only ${checked} files found under ${SOURCE_DIR}: wrong SOURCE_DIR?")
endif()
if(failures)
  message(FATAL_ERROR "check_layers: includes against the layers:\n${failures}")
endif()
message(STATUS "check_layers: ${checked} files, every include points down the layers")
