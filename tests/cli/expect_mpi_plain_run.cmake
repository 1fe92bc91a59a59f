# A run that is not a study, started by mpirun on 2 ranks, runs once, on rank
# 0: exit 0, one "Dynamic run" in the output, nothing on stderr, and the same
# time series as the serial run bit for bit. Bad input under mpirun: its error
# line printed once (by rank 0), exit status 2, nothing left behind.
#   -DEXE=... -DMPIEXEC=... -DPRM=... -DOUTDIR=dir
set(short --set "Pantograph/Final position=2.5" --set Output/Plots=false)
set(mpi ${MPIEXEC} --allow-run-as-root --oversubscribe -np 2)
file(REMOVE_RECURSE ${OUTDIR}-serial ${OUTDIR}-mpi ${OUTDIR}-refused)
execute_process(COMMAND ${EXE} ${PRM} ${short} -o ${OUTDIR}-serial
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "serial run failed (${status}):\n${err}")
endif()
execute_process(COMMAND ${mpi} ${EXE} ${PRM} ${short} -o ${OUTDIR}-mpi
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT err STREQUAL "")
  message(FATAL_ERROR "2-rank run: exit ${status}, stderr:\n${err}")
endif()
string(REGEX MATCHALL "Dynamic run:" runs "${out}")
list(LENGTH runs n_runs)
if(NOT n_runs EQUAL 1)
  message(FATAL_ERROR "2-rank run: the run was made ${n_runs} times:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUTDIR}-serial/time_series.csv
                        ${OUTDIR}-mpi/time_series.csv RESULT_VARIABLE differ)
if(differ)
  message(FATAL_ERROR "time_series.csv of the 2-rank run differs from the serial run")
endif()
execute_process(COMMAND ${mpi} ${EXE} ${PRM} --set "Pantograph/Speed=-5" -o ${OUTDIR}-refused
                RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
string(REGEX MATCHALL "pantocat-fem: [^\n]*" lines "${err}")
list(LENGTH lines n_lines)
if(status EQUAL 0 OR NOT n_lines EQUAL 1 OR NOT lines MATCHES "Pantograph/Speed = -5: must be > 0"
   OR EXISTS ${OUTDIR}-refused)
  message(FATAL_ERROR "bad input on 2 ranks: exit ${status}, ${n_lines} lines of ours:\n${err}")
endif()
message(STATUS "one run on rank 0, the same series as serial; one error line for bad input")
