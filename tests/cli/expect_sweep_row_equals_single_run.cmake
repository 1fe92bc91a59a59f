# A speed sweep's row equals the single dynamic run of that speed to the
# printed digit (7 significant digits: |a - b| <= 5e-7 |a|, or 1e-9 N near
# zero): the sweep runs the same case through the same runner and statistics.
#   -DEXE=... -DPRM=small-speed-sweep.prm -DOUTDIR=dir -DSPEED_KMH=115.2
#   -DSPEED_MS=32 (the speed of the single run)
cmake_minimum_required(VERSION 3.19) # string(JSON)
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
find_program(AWK NAMES awk mawk gawk REQUIRED)
file(REMOVE_RECURSE ${OUTDIR}-sweep ${OUTDIR}-single)
run_or_fail("sweep" out COMMAND ${EXE} ${PRM} -o ${OUTDIR}-sweep)
run_or_fail("single run" out COMMAND ${EXE} ${PRM} -o ${OUTDIR}-single
            --set "Run/Mode=dynamics"
            --set "Pantograph/Speed=${SPEED_MS}")
file(READ ${OUTDIR}-single/summary.json summary)
file(STRINGS ${OUTDIR}-sweep/speed_sweep.csv lines)
list(GET lines 0 header)
string(REPLACE "," ";" columns "${header}")
set(row "")
foreach(line IN LISTS lines)
  if(line MATCHES "^${SPEED_KMH},1,")
    set(row "${line}")
  endif()
endforeach()
if(row STREQUAL "")
  message(FATAL_ERROR "no row of ${SPEED_KMH} km/h in speed_sweep.csv")
endif()
string(REPLACE "," ";" fields "${row}")
set(pairs "")
foreach(name mean std max min mean_plus_3std mean_minus_3std contact_loss_percent)
  foreach(set raw filtered)
    set(column ${name})
    if(set STREQUAL "filtered")
      set(column filtered_${name})
    endif()
    list(FIND columns ${column} index)
    list(GET fields ${index} sweep_value)
    string(JSON single_value GET "${summary}" statistics ${set} ${name})
    string(APPEND pairs "${column} ${single_value} ${sweep_value}\n")
  endforeach()
endforeach()
file(WRITE ${OUTDIR}-pairs.txt "${pairs}")
execute_process(COMMAND ${AWK} "{ d = $2 - $3; if (d < 0) d = -d; a = $2 < 0 ? -$2 : $2;
  if (d > 5e-7 * a + 1e-9) { print $1 \": single run \" $2 \", sweep \" $3; bad = 1 } }
  END { exit bad }" ${OUTDIR}-pairs.txt
  RESULT_VARIABLE status OUTPUT_VARIABLE bad)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the sweep's row differs from the single run:\n${bad}")
endif()
message(STATUS "14 figures of ${SPEED_KMH} km/h equal the single run to 7 digits")
