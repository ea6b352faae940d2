# A rank that fails ends the whole run: its message on stderr (prefixed with the rank), a non-zero
# exit status, and no rank left waiting in a collective for it (each run under a timeout).
#  - bad input seen by one rank: rank 1 is given a scene file that does not exist, while the
#    others read a good one and go on to the solve;
#  - out of memory on one rank: rank 1 runs with its address space limited (ulimit -v 400000,
#    400 MB), so the memory plan refuses level 6 there (the plan: about 700 MB) before any large
#    allocation, while the others go on with the setup.
# Run: cmake -DMPIEXEC=mpirun -DPANELRAD=<program> -DSOURCE_DIR=<project> -DWORK_DIR=<dir> -P cli_rank_failure.cmake
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(scene "${SOURCE_DIR}/examples/scenes/cornell_box.obj")

function(expect_failure name expected script)
  execute_process(COMMAND "${MPIEXEC}" -np 3 --oversubscribe sh -c "${script}" sh "${PANELRAD}" "${scene}"
                  WORKING_DIRECTORY "${WORK_DIR}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 240)
  if(status EQUAL 0 OR status MATCHES "timeout")
    message(FATAL_ERROR "${name}: exit status '${status}', expected a failure\n${out}\n${err}")
  endif()
  if(NOT err MATCHES "${expected}")
    message(FATAL_ERROR "${name}: stderr does not say '${expected}':\n${err}")
  endif()
  if(EXISTS "${WORK_DIR}/out.csv")
    message(FATAL_ERROR "${name}: an output was written")
  endif()
  message(STATUS "${name}: status ${status}, message found")
endfunction()

# $1: the program, $2: the scene. OMPI_COMM_WORLD_RANK: the rank Open MPI gives each process.
expect_failure("bad input on rank 1" "rank 1: panelrad solve: error: .*missing_scene.obj"
  [=[if [ "$OMPI_COMM_WORLD_RANK" = 1 ]; then s=missing_scene.obj; else s="$2"; fi
     exec "$1" solve "$s" --levels 3 --method fast --formats csv --out out --quiet]=])
expect_failure("out of memory on rank 1" "rank 1: panelrad solve: error: .*more than the .* available"
  [=[if [ "$OMPI_COMM_WORLD_RANK" = 1 ]; then ulimit -v 400000; fi
     exec "$1" solve "$2" --levels 6 --method fast --formats csv --out out --quiet]=])
