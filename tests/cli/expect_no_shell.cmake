# External programs run without a shell: output directories whose names hold
# shell syntax (a quote, a semicolon, $(...)) reach gnuplot as a plain working
# directory. Expected for each: exit status 0, no file created by the injected
# command anywhere under WORKDIR, and (with gnuplot installed) the PNG plots
# drawn in that directory.
#   -DEXE=... -DPRM=... -DWORKDIR=dir [-DGNUPLOT=path]
string(ASCII 59 semicolon)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
foreach(index 0 1)
  if(index EQUAL 0)
    set(dir "q'${semicolon} touch PWNED${semicolon} echo '")
  else()
    set(dir "q'$(touch PWNED_TOO)'")
  endif()
  execute_process(COMMAND ${EXE} ${PRM} --set "Pantograph/Final position=2.5" -o "${dir}"
                  WORKING_DIRECTORY ${WORKDIR}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "exit status ${status} for -o \"${dir}\":\n${out}\n${err}")
  endif()
  file(GLOB_RECURSE injected ${WORKDIR}/PWNED* ${WORKDIR}/*/PWNED*)
  if(injected)
    message(FATAL_ERROR "-o \"${dir}\" ran a shell command: ${injected}")
  endif()
  if(GNUPLOT)
    foreach(png contact_force.png dropper_forces.png pantograph.png
                contact_force_statistics.png contact_force_over_x.png)
      if(NOT EXISTS "${WORKDIR}/${dir}/${png}")
        message(FATAL_ERROR "gnuplot did not draw ${png} in \"${dir}\":\n${out}")
      endif()
    endforeach()
  endif()
endforeach()
message(STATUS "no shell ran; plots drawn: ${GNUPLOT}")
