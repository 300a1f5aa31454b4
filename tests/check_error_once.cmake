# Under mpirun an error of the input is printed once, by rank 0, not once per rank (issue 24):
# an empty input run on two ranks says "is empty" once and exits non-zero.
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
