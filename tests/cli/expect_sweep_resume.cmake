# A killed sweep resumed with Sweep/Resume = true runs only the runs its
# <name>.csv.partial does not hold and ends with the CSV of the uninterrupted
# sweep, byte for byte. The partial file is made from the uninterrupted
# sweep's first KEEP runs plus a line cut short (the kill hit a write): that
# run runs again.
#   -DEXE=... -DPRM=... -DOUTDIR=dir -DTABLE=speed_sweep.csv -DRUNS=n -DKEEP=k
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR}-full ${OUTDIR}-resumed)
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR}-full RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "sweep failed (${status}):\n${out}\n${err}")
endif()
file(STRINGS ${OUTDIR}-full/${TABLE} lines)
list(SUBLIST lines 0 ${KEEP} kept) # the header and KEEP - 1 rows
list(GET lines ${KEEP} cut)
string(SUBSTRING "${cut}" 0 12 cut)
string(REPLACE ";" "\n" partial "${kept}")
file(MAKE_DIRECTORY ${OUTDIR}-resumed)
file(WRITE ${OUTDIR}-resumed/${TABLE}.partial "${partial}\n${cut}")
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR}-resumed --set "Sweep/Resume=true"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "resumed sweep failed (${status}):\n${out}\n${err}")
endif()
math(EXPR before "${KEEP} - 1")
if(NOT out MATCHES "${before} finished before")
  message(FATAL_ERROR "the resumed sweep did not keep ${before} runs:\n${out}")
endif()
string(REPLACE ".csv" "_runs.csv" runs_table ${TABLE})
file(STRINGS ${OUTDIR}-resumed/${runs_table} ran)
list(LENGTH ran n)
math(EXPR expected "${RUNS} - ${before} + 1")
if(NOT n EQUAL expected)
  message(FATAL_ERROR "the resumed sweep ran ${n} - 1 runs, expected ${RUNS} - ${before}")
endif()
file(READ ${OUTDIR}-full/${TABLE} full)
file(READ ${OUTDIR}-resumed/${TABLE} resumed)
if(NOT full STREQUAL resumed)
  message(FATAL_ERROR "resumed CSV differs:\n${full}\n---\n${resumed}")
endif()
if(EXISTS ${OUTDIR}-resumed/${TABLE}.partial)
  message(FATAL_ERROR "${TABLE}.partial left behind")
endif()
message(STATUS "resumed after ${before} runs: the same ${TABLE}")
