# A failed run (a guard) and a refused run (a step above the stability
# limit) are rows with their reason, not the end of the study: exit 0, one
# row per run, the other runs complete with their figures.
#   -DEXE=... -DPRM=small-parameter-sweep.prm -DOUTDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR} RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the sweep should complete (${status}):\n${out}\n${err}")
endif()
file(READ ${OUTDIR}/parameter_sweep.csv csv)
foreach(expect
    "\n100,1e-4,1,[0-9.]+,[0-9.]+,[^\n]*,completed,\"\"\n"
    "\n1.1,1e-4,1,,,,,,,,,,,,,,,,failed,\"unstable: force [|]lambda[|] = [0-9.e+]+ N of [a-z0-9 ]+ exceeds Guards/Multiplier bound = 1.1 x F_ref"
    "\n100,1e-3,1,,[^\n]*,refused,\"Time integration/Time step = 0.001: above the stability limit"
    "\n1.1,1e-3,1,,[^\n]*,refused,")
  if(NOT csv MATCHES "${expect}")
    message(FATAL_ERROR "parameter_sweep.csv has no row matching '${expect}':\n${csv}")
  endif()
endforeach()
string(REGEX MATCHALL "\n" newlines "${csv}")
list(LENGTH newlines n)
if(NOT n EQUAL 5)
  message(FATAL_ERROR "expected the header and 4 rows, got ${n} lines:\n${csv}")
endif()
message(STATUS "a failed and two refused runs are rows with their reasons")
