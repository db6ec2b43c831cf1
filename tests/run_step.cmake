# run(COMMAND ARGS...) for the CMake scripts that install or package raps and use it as a
# consumer would: a step that fails stops the test with its command and output; a step that
# succeeds leaves its standard output in last_output and its standard error in last_error.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
  set(last_error "${err}" PARENT_SCOPE)
endfunction()
