# The parameter reference doc/parameters.prm must equal what the program
# prints now; regenerate it with scripts/update-parameter-reference.sh.
#   -DEXE=... -DREFERENCE=...
execute_process(COMMAND ${EXE} --print-parameters prm RESULT_VARIABLE status
                OUTPUT_VARIABLE printed ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "--print-parameters failed: ${err}")
endif()
file(READ ${REFERENCE} stored)
if(NOT printed STREQUAL stored)
  message(FATAL_ERROR "doc/parameters.prm is stale: run scripts/update-parameter-reference.sh")
endif()
