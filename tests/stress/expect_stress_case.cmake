# One case of the stress suite (doc/stability.md): runs pantocat-fem and checks
# the stated outcome.
#   OUTCOME = completed: exit 0, summary.json "completed", and every CHECK;
#   OUTCOME = refused:   exit 2 before the run, one line matching MESSAGE;
#   OUTCOME = stopped:   exit 1, "simulation failed: " MESSAGE, summary.json
#                        "failed" and time_series.csv kept.
# A CHECK is "key<=value" or "key>=value"; key is a path into summary.json
# with dots (guards.max_drift, contact_loss_intervals.0.1) or #path for the
# length of an array (#contact_loss_intervals).
#   -DEXE=... -DARGS="a;b" -DOUTDIR=dir -DOUTCOME=... [-DMESSAGE=regex] [-DCHECKS="k<=v;..."]
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${ARGS} --set Output/Plots=false --set Output/Verbosity=quiet
                        -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(OUTCOME STREQUAL "refused")
  if(NOT status EQUAL 2 OR err MATCHES "\n" OR NOT err MATCHES "${MESSAGE}")
    message(FATAL_ERROR "expected a refusal (exit 2, one line matching '${MESSAGE}'), got "
                        "exit ${status}:\n${err}")
  endif()
  message(STATUS "refused: ${err}")
  return()
endif()
if(OUTCOME STREQUAL "stopped")
  if(NOT status EQUAL 1 OR NOT err MATCHES "simulation failed: ${MESSAGE}")
    message(FATAL_ERROR "expected a stop (exit 1, 'simulation failed: ${MESSAGE}'), got "
                        "exit ${status}:\n${err}")
  endif()
  file(READ ${OUTDIR}/summary.json summary)
  file(STRINGS ${OUTDIR}/time_series.csv rows)
  list(LENGTH rows n_rows)
  if(NOT summary MATCHES "\"status\": \"failed\"" OR n_rows LESS 3)
    message(FATAL_ERROR "a stopped run must leave summary.json failed and its time series "
                        "(${n_rows} rows):\n${summary}")
  endif()
  message(STATUS "stopped: ${err}; time_series.csv kept with ${n_rows} rows")
  return()
endif()
if(NOT status EQUAL 0)
  message(FATAL_ERROR "expected the run to complete, got exit ${status}:\n${err}")
endif()
file(READ ${OUTDIR}/summary.json summary)
foreach(check ${CHECKS})
  if(NOT check MATCHES "^(#?)([^<>=]+)(<=|>=)(.+)$")
    message(FATAL_ERROR "bad check '${check}'")
  endif()
  set(length "${CMAKE_MATCH_1}")
  string(REPLACE "." ";" path "${CMAKE_MATCH_2}")
  set(op "${CMAKE_MATCH_3}")
  set(bound "${CMAKE_MATCH_4}")
  if(length)
    string(JSON value LENGTH "${summary}" ${path})
  else()
    string(JSON value GET "${summary}" ${path})
  endif()
  if((op STREQUAL "<=" AND value GREATER bound) OR (op STREQUAL ">=" AND value LESS bound))
    message(FATAL_ERROR "${check} does not hold: ${value}")
  endif()
endforeach()
string(JSON force GET "${summary}" guards max_multiplier)
string(JSON drift GET "${summary}" guards max_drift)
string(JSON energy GET "${summary}" guards max_energy_increase)
string(JSON losses LENGTH "${summary}" contact_loss_intervals)
string(JSON slack GET "${summary}" max_droppers_slack_at_once)
string(JSON lmin GET "${summary}" contact_force min)
string(JSON seconds GET "${summary}" time_loop_seconds)
message(STATUS "completed: max |lambda| ${force} N, min lambda_p ${lmin} N, drift ${drift} m, "
               "max E(t)-E(0) ${energy} J, ${losses} contact losses, up to ${slack} "
               "droppers slack at once, time loop ${seconds} s")
