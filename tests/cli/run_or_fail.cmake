# run_or_fail(<what> <output variable> COMMAND ...): runs the command (the
# arguments of execute_process) and stops the test, naming <what>, its exit
# status, its output and its errors, if it fails; otherwise its standard
# output goes to <output variable>.
function(run_or_fail what out)
  execute_process(${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE stdout
                  ERROR_VARIABLE stderr)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${stdout}\n${stderr}")
  endif()
  set(${out} "${stdout}" PARENT_SCOPE)
endfunction()
