# A run that completes (exit 0) and warns: its standard error holds a line
# matching EXPECT.
#   -DEXE=... -DARGS=a;b;... -DOUTDIR=dir -DEXPECT=regex
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${ARGS} -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the run failed (${status}):\n${out}\n${err}")
endif()
if(NOT err MATCHES "(^|\n)pantocat-fem: warning: ${EXPECT}")
  message(FATAL_ERROR "expected a warning matching\n  ${EXPECT}\ngot:\n${err}")
endif()
message(STATUS "${err}")
