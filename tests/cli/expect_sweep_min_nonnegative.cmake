# A speed sweep's rows are all completed and their raw "min" column, the
# smallest contact force of each run, is >= 0 (a unilateral contact only
# pushes; its written text never starts with '-'). The filtered minimum may
# lie below zero (a low pass of a force that drops to 0 undershoots) and is
# not checked.
#   -DEXE=... "-DARGS=case.prm;--set;..." -DOUTDIR=dir -DROWS=n
cmake_minimum_required(VERSION 3.19) # empty CSV fields kept in lists (CMP0007)
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
file(REMOVE_RECURSE ${OUTDIR})
run_or_fail("sweep" out COMMAND ${EXE} ${ARGS} -o ${OUTDIR})
file(STRINGS ${OUTDIR}/speed_sweep.csv lines)
list(POP_FRONT lines header)
string(REPLACE "," ";" columns "${header}")
list(FIND columns min index)
if(index LESS 0)
  message(FATAL_ERROR "speed_sweep.csv has no column min: ${header}")
endif()
list(LENGTH lines rows)
if(NOT rows EQUAL ROWS)
  message(FATAL_ERROR "speed_sweep.csv has ${rows} rows, expected ${ROWS}")
endif()
foreach(line IN LISTS lines)
  string(REPLACE "," ";" fields "${line}")
  list(GET fields ${index} min)
  if(NOT line MATCHES ",completed,")
    message(FATAL_ERROR "a run of the sweep did not complete: ${line}")
  endif()
  if(NOT min MATCHES "^[0-9]")
    message(FATAL_ERROR "a negative contact force in speed_sweep.csv: min = ${min} in ${line}")
  endif()
endforeach()
message(STATUS "${rows} rows completed, every raw min >= 0")
