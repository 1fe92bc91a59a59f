# A sweep that starts afresh (Resume = false) removes what an earlier sweep
# completed in its output directory before it runs anything: a sweep stopped
# after its first run (Sweep/Stop after runs = 1, as if killed) leaves its
# partial file and its parameters.prm, but neither the earlier sweep's
# tables and plots nor the default-named results of another sweep; a file of
# another name stays.
#   -DEXE=... -DPRM=... -DOUTDIR=dir -DTABLE=speed_sweep.csv
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR} RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REPLACE ".csv" "" name ${TABLE})
if(NOT status EQUAL 0 OR NOT EXISTS ${OUTDIR}/${TABLE} OR NOT EXISTS ${OUTDIR}/${name}_runs.csv)
  message(FATAL_ERROR "the first sweep: exit ${status}\n${out}\n${err}")
endif()
# Results as an earlier sweep with plots, or of another mode, leaves them.
set(earlier ${TABLE} ${name}_runs.csv ${name}.png ${name}.gp ${name}_pantograph_2.png
    ${name}_std.png monte_carlo.csv monte_carlo_distribution.csv
    parameter_sweep_max_pantograph_1.gp summary.json)
foreach(file ${name}.png ${name}.gp ${name}_pantograph_2.png ${name}_std.png
        monte_carlo.csv monte_carlo_distribution.csv parameter_sweep_max_pantograph_1.gp
        summary.json ${name}_notes.txt ${name}_stdev.png)
  file(WRITE ${OUTDIR}/${file} "earlier\n")
endforeach()
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR} --set "Catenary/Contact wire/Tension=22000"
                        --set "Sweep/Stop after runs=1"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 1 OR NOT err MATCHES "stopped after 1 runs as asked")
  message(FATAL_ERROR "the stopped sweep: exit ${status}\n${out}\n${err}")
endif()
foreach(file ${earlier})
  if(EXISTS ${OUTDIR}/${file} AND NOT file STREQUAL "summary.json")
    message(FATAL_ERROR "the new sweep left the earlier ${file}")
  endif()
endforeach()
# The stop writes its own summary.json (failed); the earlier one is gone.
file(READ ${OUTDIR}/summary.json summary)
if(NOT summary MATCHES "\"status\": \"failed\"")
  message(FATAL_ERROR "summary.json is not the stop's:\n${summary}")
endif()
foreach(file ${name}_notes.txt ${name}_stdev.png)
  if(NOT EXISTS ${OUTDIR}/${file})
    message(FATAL_ERROR "the new sweep removed ${file}, which no sweep writes")
  endif()
endforeach()
file(READ ${OUTDIR}/${TABLE}.partial partial)
file(READ ${OUTDIR}/parameters.prm parameters)
if(NOT partial MATCHES "\n# set Catenary/Contact wire/Tension = 22000\n"
   OR NOT parameters MATCHES "set Tension += 22000")
  message(FATAL_ERROR "the partial file or parameters.prm is not the new sweep's")
endif()
message(STATUS "the stopped fresh sweep left only its own partial file and parameters")
