# Runs pantocat-fem on bad input and checks the promise of the README: exit
# status 2, exactly one line on stderr that matches EXPECT (names the
# parameter, the value and what is allowed), and no output directory left.
#   -DEXE=... -DARGS="a;b;c" -DEXPECT=regex -DOUTDIR=dir [-DPRM_TEXT=...]
if(DEFINED PRM_TEXT)
  file(WRITE ${OUTDIR}.prm "${PRM_TEXT}")
endif()
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${ARGS} -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 2)
  message(FATAL_ERROR "expected exit status 2, got '${status}'\nstderr: ${err}")
endif()
string(STRIP "${err}" err_stripped)
string(FIND "${err_stripped}" "\n" newline)
if(NOT newline EQUAL -1)
  message(FATAL_ERROR "expected one line on stderr, got:\n${err}")
endif()
if(NOT err_stripped MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
if(EXISTS ${OUTDIR})
  message(FATAL_ERROR "bad input left an output directory behind: ${OUTDIR}")
endif()
