# A parameter sweep's plots give the swept entry's unit on their x axis, as
# the entry's documentation states it ("Tensile force T [N], > 0.").
#   -DEXE=... -DPRM=... -DOUTDIR=dir
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
file(REMOVE_RECURSE ${OUTDIR})
run_or_fail("sweep" out COMMAND ${EXE} ${PRM} -o ${OUTDIR} --set "Output/Plots=true"
            --set "Sweep/Parameter=Catenary/Contact wire/Tension"
            --set "Sweep/Values=15000, 16000" --set "Sweep/Second parameter="
            --set "Sweep/Second values=")
file(READ ${OUTDIR}/parameter_sweep_std.gp script)
if(NOT script MATCHES "set xlabel 'Catenary/Contact wire/Tension \\[N\\]'"
   OR NOT script MATCHES "set ylabel 'contact force: std \\[N\\]'")
  message(FATAL_ERROR "parameter_sweep_std.gp lacks the axes with their units:\n${script}")
endif()
