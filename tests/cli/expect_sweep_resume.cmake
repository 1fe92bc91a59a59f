# A sweep stopped after KEEP runs (Sweep/Stop after runs, as if killed) whose
# last run's append was cut by the kill (its end line gone, its last row cut
# short: with two pantographs the first row stays whole), resumed with
# Sweep/Resume = true, runs only the runs its <name>.csv.partial does not
# hold completely and ends with the CSV of the uninterrupted sweep, byte for
# byte. The resume sets Checkpoint/Interval, which the runs of a sweep do not
# read: the partial file is still accepted. The stop's summary.json (failed)
# is gone after the resume.
#   -DEXE=... -DPRM=... [-DARGS="--set;A=b"] -DOUTDIR=dir -DTABLE=speed_sweep.csv
#   -DRUNS=n -DKEEP=k
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR}-full ${OUTDIR}-resumed)
execute_process(COMMAND ${EXE} ${PRM} ${ARGS} -o ${OUTDIR}-full RESULT_VARIABLE status
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "sweep failed (${status}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${EXE} ${PRM} ${ARGS} -o ${OUTDIR}-resumed
                        --set "Sweep/Stop after runs=${KEEP}"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 1 OR NOT err MATCHES "stopped after ${KEEP} runs as asked")
  message(FATAL_ERROR "the stopped sweep: exit ${status}\n${out}\n${err}")
endif()
set(partial ${OUTDIR}-resumed/${TABLE}.partial)
if(EXISTS ${OUTDIR}-resumed/${TABLE} OR NOT EXISTS ${partial})
  message(FATAL_ERROR "the stopped sweep left ${TABLE} or no partial file")
endif()
# The kill: the last run's end line removed and its last row cut short.
file(READ ${partial} text)
string(FIND "${text}" "# end of run:" last_end REVERSE)
string(SUBSTRING "${text}" 0 ${last_end} text)
string(LENGTH "${text}" n)
math(EXPR n "${n} - 40")
string(SUBSTRING "${text}" 0 ${n} text)
file(WRITE ${partial} "${text}")
execute_process(COMMAND ${EXE} ${PRM} ${ARGS} -o ${OUTDIR}-resumed --set "Sweep/Resume=true"
                        --set "Checkpoint/Interval=100"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "resumed sweep failed (${status}):\n${out}\n${err}")
endif()
math(EXPR before "${KEEP} - 1")
if(NOT out MATCHES "${before} finished before [(]Resume = true; [0-9]+ lines of a run cut short dropped[)]")
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
if(EXISTS ${partial} OR EXISTS ${OUTDIR}-resumed/summary.json)
  message(FATAL_ERROR "${TABLE}.partial or the stop's summary.json left behind")
endif()
message(STATUS "resumed after ${before} whole runs and a cut one: the same ${TABLE}")
