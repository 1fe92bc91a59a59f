# A write that fails (here a file-size limit: write() fails with EFBIG as on a
# full disk with ENOSPC) ends the run with one line naming the file actually
# being written and the reason of the failing call (exit 1), and summary.json
# says failed with that line.
#   -DEXE=... -DPRM=prm/benchmark-32.prm -DWORKDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
# 200 blocks of 512 bytes: parameters.prm and summary.json fit, the time
# series of 2000 steps (about 1 MB) does not. SIGXFSZ is ignored, so that
# write() returns the error instead of the signal ending the process.
execute_process(COMMAND sh -c "trap '' XFSZ; ulimit -f 200; exec \"$0\" \"$@\"" ${EXE}
                        ${PRM} -o out --set "Pantograph/Final position=5.2"
                        --set Output/Plots=false
                WORKING_DIRECTORY ${WORKDIR} RESULT_VARIABLE status OUTPUT_QUIET
                ERROR_VARIABLE stderr)
string(REGEX REPLACE "\n$" "" line "${stderr}")
if(NOT status EQUAL 1 OR line MATCHES "\n" OR NOT line MATCHES
   "^pantocat-fem: simulation failed: cannot write out/time_series.csv: File too large$")
  message(FATAL_ERROR "exit ${status}, expected one line naming time_series.csv:\n${stderr}")
endif()
file(READ ${WORKDIR}/out/summary.json summary)
if(NOT summary MATCHES "\"status\": \"failed\"" OR
   NOT summary MATCHES "cannot write out/time_series.csv: File too large")
  message(FATAL_ERROR "summary.json does not say why:\n${summary}")
endif()
message(STATUS "${line}")
