# A run stopped after STOP steps with checkpoints and VTU frames, whose vtu/
# is then removed: the resume is refused with one line naming the missing
# frame and what to do (exit 2), and the stopped run's summary.json stays as
# it was (a refused resume leaves the directory as it was).
#   -DEXE=... -DPRM=prm/benchmark-32.prm -DWORKDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${WORKDIR})
set(out ${WORKDIR}/out)
set(args ${PRM} -o ${out} --set "Pantograph/Final position=2.5" --set Output/Plots=false
         --set Checkpoint/Interval=100 --set "Output/VTU interval=0.002")
execute_process(COMMAND ${EXE} ${args} --set "Checkpoint/Stop after steps=250"
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE stderr)
if(NOT status EQUAL 1 OR NOT stderr MATCHES "stopped after step 250 ")
  message(FATAL_ERROR "the stopped run: exit ${status}\n${stderr}")
endif()
file(SHA256 ${out}/summary.json summary_before)
file(SHA256 ${out}/time_series.csv series_before)
file(REMOVE_RECURSE ${out}/vtu)
execute_process(COMMAND ${EXE} ${args} --set "Checkpoint/Resume from checkpoint=true"
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE stderr)
string(REGEX REPLACE "\n$" "" line "${stderr}")
if(NOT status EQUAL 2 OR line MATCHES "\n" OR NOT line MATCHES
   "^pantocat-fem: error: Checkpoint/Resume from checkpoint = true: the checkpoint .*/out/checkpoint.bin cannot be resumed: its frame .*/out/vtu/wires-00000.vtu is missing [(].*/out/vtu was removed or changed[)][;] start afresh [(]Resume from checkpoint = false[)]$")
  message(FATAL_ERROR "the resume without vtu/: exit ${status}, expected one line:\n${stderr}")
endif()
file(SHA256 ${out}/summary.json summary_after)
file(SHA256 ${out}/time_series.csv series_after)
if(NOT summary_before STREQUAL summary_after OR NOT series_before STREQUAL series_after)
  message(FATAL_ERROR "the refused resume changed the stopped run's summary.json or time series")
endif()
message(STATUS "${line}")
