# A run that fails after an earlier run completed in the same directory must
# not leave that run's results next to its own parameters (issue: stale
# results): first a completed run, then a failing one (ARGS_FAIL); afterwards
# summary.json says "failed" in PHASE, and none of the earlier run's result
# files (GONE) is left.
#   -DEXE=... -DARGS_OK="a;b" -DARGS_FAIL="a;b" -DPHASE=setup -DGONE="f1;f2" -DOUTDIR=dir
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${ARGS_OK} -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the first run should complete, got '${status}'\nstderr: ${err}")
endif()
foreach(file ${GONE})
  if(NOT EXISTS ${OUTDIR}/${file})
    message(FATAL_ERROR "the first run did not write ${file}")
  endif()
endforeach()
execute_process(COMMAND ${EXE} ${ARGS_FAIL} -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "the second run should fail (exit 1), got '${status}'\nstderr: ${err}")
endif()
file(READ ${OUTDIR}/summary.json summary)
if(NOT summary MATCHES "\"status\": \"failed\"" OR
   NOT summary MATCHES "\"phase\": \"${PHASE}\"" OR NOT summary MATCHES "\"reason\": \"[^\"]")
  message(FATAL_ERROR "summary.json does not say failed in phase ${PHASE} with a reason:\n${summary}")
endif()
foreach(file ${GONE})
  if(NOT file STREQUAL "summary.json" AND EXISTS ${OUTDIR}/${file})
    message(FATAL_ERROR "the earlier run's ${file} is still there after the failure")
  endif()
endforeach()
