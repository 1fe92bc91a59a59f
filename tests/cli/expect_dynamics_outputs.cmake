# A short coupled run must leave the outputs the README promises: the resolved
# parameters, time_series.csv with its header and one row per step,
# summary.json with the documented keys (and the statistics), the three PNG
# plots, the ParaView frames, and the statistics (and with Verbosity =
# detailed the timer table) on screen.
#   -DEXE=... -DPRM=... -DOUTDIR=dir
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
file(REMOVE_RECURSE ${OUTDIR})
run_or_fail("run" out COMMAND ${EXE} ${PRM} -o ${OUTDIR}
            --set "Pantograph/Final position=2.32"
            --set "Output/VTU interval=0.005" --set "Output/Verbosity=detailed")
foreach(f parameters.prm time_series.csv summary.json report.html contact_force.png dropper_forces.png
          pantograph.png time_series.gp solution.pvd vtu/wires-00002.vtu
          contact_force.csv contact_force_statistics.png contact_force_statistics.gp
          contact_force_over_x.png contact_force_over_x.gp
          vtu/pantograph-droppers-00002.vtu)
  if(NOT EXISTS ${OUTDIR}/${f})
    message(FATAL_ERROR "missing output ${f}")
  endif()
endforeach()
# The plots (gnuplot is installed by scripts/install-dependencies.sh): real PNG files.
find_program(GNUPLOT gnuplot)
if(GNUPLOT)
  foreach(f contact_force.png dropper_forces.png pantograph.png contact_force_statistics.png
            contact_force_over_x.png)
    file(SIZE ${OUTDIR}/${f} size)
    file(READ ${OUTDIR}/${f} magic LIMIT 4 HEX)
    if(size LESS 1000 OR NOT magic STREQUAL "89504e47")
      message(FATAL_ERROR "${f} is not a PNG image (${size} bytes, starts ${magic})")
    endif()
  endforeach()
endif()
# VTU frames at t = 0, 5 and 10 ms: three, listed in solution.pvd with their times.
file(GLOB frames ${OUTDIR}/vtu/wires-*.vtu)
list(LENGTH frames n_frames)
file(READ ${OUTDIR}/solution.pvd pvd)
if(NOT n_frames EQUAL 3 OR NOT pvd MATCHES "timestep=\"0.005\" group=\"\" part=\"0\" file=\"vtu/wires-00001.vtu\"")
  message(FATAL_ERROR "expected 3 frames listed in solution.pvd, got ${n_frames}:\n${pvd}")
endif()
if(NOT out MATCHES "contact-force statistics" OR NOT out MATCHES "[|] time loop")
  message(FATAL_ERROR "screen output lacks the statistics or the timer table:\n${out}")
endif()
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
            position velocity time_loop_seconds statistics window raw filtered
            mean_plus_3std mean_minus_3std contact_loss_percent max_steady_arm_uplift_m
            steady_arms max_uplift_at_droppers dropper_slack_events
            dropper_slack_events_in_window)
  if(NOT summary MATCHES "\"${key}\":")
    message(FATAL_ERROR "summary.json lacks \"${key}\":\n${summary}")
  endif()
endforeach()
# One name per thing: the names before issue 15 are gone.
foreach(old mean_minus_3_sigma mean_plus_3_sigma percent_without_contact filter_cutoff_hz)
  if(summary MATCHES "\"${old}\":")
    message(FATAL_ERROR "summary.json still has the old key \"${old}\":\n${summary}")
  endif()
endforeach()
if(NOT summary MATCHES "\"status\": \"completed\"" OR NOT summary MATCHES "\"steps\": 200")
  message(FATAL_ERROR "summary.json: expected status completed and 200 steps:\n${summary}")
endif()
