# The progress line appears only on a terminal: a run that lasts over a second
# (FEM + BDF-2, 125000 steps: about 2.5 s in session 22; 50000 steps
# took 1.0 s once the steps got faster) with stderr to a file leaves
# nothing there but optional warnings; the same run on a pseudo-terminal
# (util-linux `script`, when installed) shows the line, so the first check
# is not vacuous. Verbosity = detailed adds the timer table to the statistics;
# Verbosity = quiet prints nothing on stdout.
#   -DEXE=... -DPRM=... -DOUTDIR=dir
set(case ${PRM} --set "Discretisation/Method=fem" --set "Time integration/Integrator=bdf2"
         --set "Time integration/Time step=4e-6" --set "Output/Plots=false"
         --set "Output/Time series interval=20" --set "Output/Verbosity=detailed")
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${case} -o ${OUTDIR}/file
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_FILE ${OUTDIR}.stderr)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run failed (${status})")
endif()
file(STRINGS ${OUTDIR}.stderr lines)
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^pantocat-fem: warning: ")
    message(FATAL_ERROR "stderr to a file holds more than warnings: '${line}'")
  endif()
endforeach()
if(NOT out MATCHES "time loop" OR NOT out MATCHES "contact-force statistics")
  message(FATAL_ERROR "stdout lacks the statistics or the timer table:\n${out}")
endif()

find_program(SCRIPT script)
if(SCRIPT)
  set(command "'${EXE}' '${PRM}' -o '${OUTDIR}/tty'")
  foreach(arg "Discretisation/Method=fem" "Time integration/Integrator=bdf2"
              "Time integration/Time step=4e-6" "Output/Plots=false"
              "Output/Time series interval=20")
    string(APPEND command " --set '${arg}'")
  endforeach()
  execute_process(COMMAND ${SCRIPT} -qec "${command}" /dev/null
                  RESULT_VARIABLE status OUTPUT_VARIABLE tty)
  if(NOT status EQUAL 0 OR NOT tty MATCHES "\r +[0-9.]+ %  t = [0-9.]+ s of 0.5000 s  [0-9]+ steps/s")
    message(FATAL_ERROR "no progress line on a terminal (${status}):\n${tty}")
  endif()
endif()

execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR}/quiet --set "Pantograph/Final position=2.32"
                        --set "Output/Verbosity=quiet"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT out STREQUAL "" OR NOT err STREQUAL "")
  message(FATAL_ERROR "Verbosity = quiet printed (${status}):\n${out}\n${err}")
endif()
