# A checkpoint made with other critical parameters is refused: the run is
# stopped after STOP steps with checkpoints every INTERVAL steps, then resumed
# with CHANGE (one --set override). Expected: exit 2, one line on stderr that
# matches EXPECT (the parameter, the checkpoint's value and this run's value),
# and the stopped run's time series and checkpoint left as they were.
#   -DEXE=... -DARGS="a;b" -DINTERVAL=k -DSTOP=n -DCHANGE="Sub/Entry=value"
#   -DEXPECT=regex -DOUTDIR=dir
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${ARGS} --set Output/Plots=false
                        --set Checkpoint/Interval=${INTERVAL}
                        --set "Checkpoint/Stop after steps=${STOP}" -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_QUIET)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "the stopped run: exit ${status}")
endif()
file(SHA256 ${OUTDIR}/time_series.csv series_before)
file(SHA256 ${OUTDIR}/checkpoint.bin checkpoint_before)
execute_process(COMMAND ${EXE} ${ARGS} --set Output/Plots=false --set "${CHANGE}"
                        --set "Checkpoint/Resume from checkpoint=true" -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT status EQUAL 2)
  message(FATAL_ERROR "expected exit status 2, got '${status}'\nstderr: ${err}")
endif()
string(STRIP "${err}" err)
if(err MATCHES "\n" OR NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "expected one line matching '${EXPECT}', got:\n${err}")
endif()
file(SHA256 ${OUTDIR}/time_series.csv series_after)
file(SHA256 ${OUTDIR}/checkpoint.bin checkpoint_after)
if(NOT series_before STREQUAL series_after OR NOT checkpoint_before STREQUAL checkpoint_after)
  message(FATAL_ERROR "the refused resume changed time_series.csv or checkpoint.bin")
endif()
