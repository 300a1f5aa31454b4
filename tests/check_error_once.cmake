# Under mpirun an error of the input is printed once, by rank 0, not once per rank (issue 24).
# An empty input run on two ranks says "is empty" once and exits non-zero.
# cmake -DMPIEXEC=... -DFLAGS=... -DGEOHYBRID=... -DWORK=DIR -P check_error_once.cmake
file(WRITE ${WORK}/error_once_empty.prm "")
execute_process(COMMAND ${MPIEXEC} -np 2 ${FLAGS} ${GEOHYBRID} pullout ${WORK}/error_once_empty.prm
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE status)
string(REGEX MATCHALL "error:" errors "${out}${err}")
list(LENGTH errors n)
if(NOT n EQUAL 1 OR NOT "${out}${err}" MATCHES "error_once_empty.prm' is empty")
  message(FATAL_ERROR "expected one error naming the empty input, got ${n}:\n${out}${err}")
endif()
if(status EQUAL 0)
  message(FATAL_ERROR "exit status 0 for an empty input:\n${out}${err}")
endif()
message(STATUS "one error on two ranks, status ${status}")

# A --seeds ensemble on two ranks into another run's directory: rank 0 refuses it, and every rank
# stops (none waits for rank 0 at a barrier), with the one message.
set(seeds_out ${WORK}/error_once_seeds)
file(REMOVE_RECURSE ${seeds_out})
file(WRITE ${seeds_out}/summary.json "{}\n")
file(WRITE ${WORK}/error_once_seeds.prm "set output directory = ${seeds_out}\n")
execute_process(COMMAND ${MPIEXEC} -np 2 ${FLAGS} ${GEOHYBRID} pullout ${WORK}/error_once_seeds.prm --seeds 2
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE status TIMEOUT 60)
string(REGEX MATCHALL "error:" errors "${out}${err}")
list(LENGTH errors n)
if(NOT n EQUAL 1 OR NOT "${out}${err}" MATCHES "holds the files of another run \\(summary.json\\)")
  message(FATAL_ERROR "expected one refusal of ${seeds_out}, got ${n} (status ${status}):\n${out}${err}")
endif()
if(status EQUAL 0 OR NOT status MATCHES "^[0-9]+$") # a rank left waiting ends in the timeout
  message(FATAL_ERROR "exit status '${status}' for a refused directory:\n${out}${err}")
endif()
message(STATUS "one refusal of the ensemble's directory on two ranks, status ${status}")
