# A short coupled run must leave the outputs the README promises: the resolved
# parameters, time_series.csv with its header and one row per step,
# summary.json with the documented keys, and the three PNG plots.
#   -DEXE=... -DPRM=... -DOUTDIR=dir
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR} --set "Pantograph/Final position=2.32"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run failed (${status}):\n${out}\n${err}")
endif()
foreach(f parameters.prm time_series.csv summary.json contact_force.png dropper_forces.png
          pantograph.png time_series.gp)
  if(NOT EXISTS ${OUTDIR}/${f})
    message(FATAL_ERROR "missing output ${f}")
  endif()
endforeach()
file(STRINGS ${OUTDIR}/time_series.csv lines)
list(GET lines 0 header)
set(expected_header "t,x_p,lambda_p,lambda_d1,lambda_d2,w_p1,w_p2,gap_p,gap_d1,gap_d2,active_p,active_d1,active_d2,residual_position,residual_velocity")
if(NOT header STREQUAL expected_header)
  message(FATAL_ERROR "time_series.csv header is\n${header}\nexpected\n${expected_header}")
endif()
# x_p from 2 to 2.32 m at 32 m/s with dt = 5e-5 s: 200 steps, 201 time points.
list(LENGTH lines n)
if(NOT n EQUAL 202)
  message(FATAL_ERROR "time_series.csv has ${n} lines, expected 202 (header + 201 time points)")
endif()
file(READ ${OUTDIR}/summary.json summary)
foreach(key status contact_force max min mean std dropper_slack_intervals events event_resolution
            contact_loss_intervals steps active_set_changes max_constraint_residual
            position velocity time_loop_seconds)
  if(NOT summary MATCHES "\"${key}\":")
    message(FATAL_ERROR "summary.json lacks \"${key}\":\n${summary}")
  endif()
endforeach()
if(NOT summary MATCHES "\"status\": \"completed\"" OR NOT summary MATCHES "\"steps\": 200")
  message(FATAL_ERROR "summary.json: expected status completed and 200 steps:\n${summary}")
endif()
