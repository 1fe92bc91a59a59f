# Runs a Monte Carlo study on 2 MPI ranks and checks: every sample completed
# (SAMPLES rows), no negative raw contact force in any row (a unilateral
# contact never pulls), the median of the filtered sigma over the samples
# inside [P50_MIN, P50_MAX] N (the band around the measured value, doc/studies.md),
# and the distribution table and the histogram plot written.
#   -DEXE=... -DMPIEXEC=... -DPRM=... -DOUTDIR=... -DSAMPLES=n -DP50_MIN=... -DP50_MAX=...
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${MPIEXEC} --oversubscribe -np 2 ${EXE} ${PRM} -o ${OUTDIR}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${PRM} failed (${status}):\n${out}\n${err}")
endif()
file(STRINGS ${OUTDIR}/monte_carlo.csv rows)
list(POP_FRONT rows header)
string(REPLACE "," ";" columns "${header}")
list(FIND columns min min_index)
set(completed 0)
foreach(row IN LISTS rows)
  string(REPLACE "," ";" fields "${row}")
  if(row MATCHES ",completed,")
    math(EXPR completed "${completed} + 1")
  endif()
  list(GET fields ${min_index} min)
  if(min LESS 0)
    message(FATAL_ERROR "a negative contact force ${min} N in: ${row}")
  endif()
endforeach()
if(NOT completed EQUAL SAMPLES)
  message(FATAL_ERROR "${completed} of ${SAMPLES} samples completed:\n${out}")
endif()
file(STRINGS ${OUTDIR}/monte_carlo_distribution.csv lines REGEX "^filtered_std,1,")
string(REPLACE "," ";" fields "${lines}")
list(GET fields 7 p50) # statistic,pantograph,n,mean,std,min,p5,p50
message(STATUS "${completed} samples; filtered sigma median ${p50} N")
if(p50 LESS ${P50_MIN} OR p50 GREATER ${P50_MAX})
  message(FATAL_ERROR "median filtered sigma ${p50} N outside [${P50_MIN}, ${P50_MAX}] N")
endif()
if(NOT EXISTS ${OUTDIR}/monte_carlo.png AND out MATCHES "monte_carlo.png")
  message(FATAL_ERROR "monte_carlo.png announced but not written")
endif()
