# A parameter sweep over an entry the runs read but this case does not use
# (an IDA tolerance with the half-explicit integrator) completes and ends
# with one warning naming it: every value gave the same rows. The other
# entry of the grid (the contact wire's tension) changes the rows: no
# warning for it.
#   -DEXE=... -DPRM=small-parameter-sweep.prm -DOUTDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR}
                        --set "Sweep/Parameter=Catenary/Contact wire/Tension"
                        --set "Sweep/Values=15000, 16000"
                        --set "Sweep/Second parameter=Time integration/IDA relative tolerance"
                        --set "Sweep/Second values=1e-6, 1e-5"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the sweep failed (${status}):\n${out}\n${err}")
endif()
string(STRIP "${err}" err)
set(expect "^pantocat-fem: warning: Sweep/Second parameter = Time integration/IDA relative tolerance: every value gave the same figures [(]every completed row equal to all its digits[)]: the runs may not use this entry in this case$")
if(NOT err MATCHES "${expect}")
  message(FATAL_ERROR "expected exactly the warning about the IDA tolerance, got:\n${err}")
endif()
message(STATUS "${err}")
