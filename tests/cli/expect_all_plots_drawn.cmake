# Two pantographs on the S55 section draw 17 curves in the time-series plots
# (2 contact forces, 9 droppers, 6 pantograph coordinates), more than a
# gnuplot `using` spec takes (14 columns): every plot must still be drawn, as
# a real PNG file, and none reported missing.
#   -DEXE=... -DPRM=... -DOUTDIR=dir
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
file(REMOVE_RECURSE ${OUTDIR})
run_or_fail("run" out COMMAND ${EXE} ${PRM} -o ${OUTDIR}
            --set "Pantograph/Final position=202"
            --set "Statistics/Window spans=")
find_program(GNUPLOT gnuplot)
if(NOT GNUPLOT)
  return()
endif()
if(out MATCHES "some plots were not drawn")
  message(FATAL_ERROR "plots missing:\n${out}")
endif()
foreach(f contact_force.png dropper_forces.png pantograph.png contact_force_statistics.png
          contact_force_over_x_pantograph_1.png contact_force_over_x_pantograph_2.png)
  if(NOT EXISTS ${OUTDIR}/${f})
    message(FATAL_ERROR "missing plot ${f}:\n${out}")
  endif()
  file(READ ${OUTDIR}/${f} magic LIMIT 4 HEX)
  if(NOT magic STREQUAL "89504e47")
    message(FATAL_ERROR "${f} is not a PNG image (starts ${magic})")
  endif()
endforeach()
file(READ ${OUTDIR}/time_series.gp script)
string(REGEX MATCHALL "\\$c[0-9]+ << EOD" curves "${script}")
list(LENGTH curves n)
if(NOT n EQUAL 17)
  message(FATAL_ERROR "time_series.gp holds ${n} curves, expected 17")
endif()
