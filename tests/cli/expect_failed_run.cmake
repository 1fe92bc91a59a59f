# Runs pantocat-fem on a case that must fail during the simulation and checks
# that it says so (exit status 1, "simulation failed: " with EXPECT on stderr)
# and that its outputs are marked: summary.json has "status": "failed".
#   -DEXE=... -DARGS="a;b;c" -DEXPECT=regex -DOUTDIR=dir
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${ARGS} -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "expected exit status 1, got '${status}'\nstderr: ${err}")
endif()
if(NOT err MATCHES "simulation failed: ${EXPECT}")
  message(FATAL_ERROR "stderr does not say 'simulation failed: ${EXPECT}':\n${err}")
endif()
file(READ ${OUTDIR}/summary.json summary)
if(NOT summary MATCHES "\"status\": \"failed\"")
  message(FATAL_ERROR "summary.json is not marked failed:\n${summary}")
endif()
