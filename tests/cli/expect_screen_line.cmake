# A run that completes (exit 0) and prints a line matching EXPECT on its
# screen (standard output).
#   -DEXE=... -DARGS=a;b;... -DOUTDIR=dir -DEXPECT=regex
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
file(REMOVE_RECURSE ${OUTDIR})
run_or_fail("run" out COMMAND ${EXE} ${ARGS} -o ${OUTDIR} --set Output/Plots=false)
if(NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "expected a line matching\n  ${EXPECT}\ngot:\n${out}")
endif()
