# A run that leaves a bound of subsection Guards (or goes non-finite) stops
# with exit 1 and "simulation failed: unstable: <EXPECT> at t = T s (step n)"
# on stderr; summary.json says "failed" with the same reason; time_series.csv
# is kept up to the failure: its last row is the time point T that failed;
# results of an earlier run in the directory are gone.
#   -DEXE=... -DARGS="a;b;c" -DEXPECT=regex -DOUTDIR=dir
# Results of an earlier run in the same directory must go (not look like this run's).
file(REMOVE_RECURSE ${OUTDIR})
file(WRITE ${OUTDIR}/contact_force.csv "stale\n")
file(WRITE ${OUTDIR}/contact_force.png "stale\n")
execute_process(COMMAND ${EXE} ${ARGS} --set Output/Plots=false -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "expected exit status 1, got '${status}'\nstderr: ${err}")
endif()
if(NOT err MATCHES "simulation failed: (unstable: ${EXPECT} at t = ([0-9.e-]+) s \\(step [0-9]+\\))")
  message(FATAL_ERROR "stderr does not say 'simulation failed: unstable: ${EXPECT} at t = ...':\n${err}")
endif()
set(reason "${CMAKE_MATCH_1}")
set(t_failed "${CMAKE_MATCH_2}")
file(READ ${OUTDIR}/summary.json summary)
string(FIND "${summary}" "\"reason\": \"${reason}\"" found)
if(NOT summary MATCHES "\"status\": \"failed\"" OR found EQUAL -1)
  message(FATAL_ERROR "summary.json is not marked failed with the reason '${reason}':\n${summary}")
endif()
file(STRINGS ${OUTDIR}/time_series.csv rows)
list(LENGTH rows n_rows)
list(GET rows -1 last)
string(REGEX REPLACE ",.*" "" t_last "${last}")
if(n_rows LESS 3 OR NOT t_last STREQUAL t_failed)
  message(FATAL_ERROR "time_series.csv (${n_rows} rows) does not end at t = ${t_failed}: ${last}")
endif()
if(EXISTS ${OUTDIR}/contact_force.csv OR EXISTS ${OUTDIR}/contact_force.png)
  message(FATAL_ERROR "the results of an earlier run were left next to the failed one")
endif()
message(STATUS "stopped at t = ${t_failed} s; time_series.csv kept with ${n_rows} rows")
