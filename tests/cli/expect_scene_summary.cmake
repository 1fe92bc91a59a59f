# A shipped scene runs through the program and its summary.json holds the
# known answer: the number at JSON path KEY (a ;-list, e.g. energy;max_relative_variation)
# must be below BOUND, and the detailed screen must list the scene's effects.
#   -DEXE=... -DPRM=... -DOUTDIR=dir -DKEY=a;b;c -DBOUND=x [-DVTU=1]
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
file(REMOVE_RECURSE ${OUTDIR})
set(extra)
if(VTU)
  set(extra --set "Output/VTU interval=0.05")
endif()
run_or_fail("run" out COMMAND ${EXE} ${PRM} -o ${OUTDIR} ${extra}
            --set "Output/Verbosity=detailed")
if(NOT out MATCHES "scene: [0-9]+ effects" OR NOT out MATCHES "problem size: [0-9]+ unknowns")
  message(FATAL_ERROR "the screen does not list the scene and its size:\n${out}")
endif()
file(READ ${OUTDIR}/summary.json summary)
string(JSON value GET "${summary}" ${KEY})
if(NOT value LESS BOUND)
  message(FATAL_ERROR "summary.json ${KEY} = ${value}, expected below ${BOUND}")
endif()
message(STATUS "${KEY} = ${value} (bound ${BOUND})")
