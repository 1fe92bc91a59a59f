# A file read back that is no regular file is refused at once, without
# reading it (doc/input-errors.md, "Names, links and files that are not what
# they say"): a checkpoint or a sweep's partial file that is a FIFO (which
# blocked the run) or a link to /dev/zero (4 GB of zeros read in 8 s), and a
# FIFO as the parameter file. Each: exit 2, one line naming the file and what
# it is, in no more than a second beyond a plain refusal (a resume without a
# checkpoint; the program's start dominates both).
#   -DEXE=... -DPRM=prm/benchmark-32.prm -DSWEEP=tests/studies/small-speed-sweep.prm
#   -DWORKDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})

# Runs EXE with ARGN (timed); expects exit 2 and one line matching EXPECT,
# within BASELINE (the time of a plain refusal, the start of the program
# included) plus a second.
function(expect_refused_at_once what expect)
  execute_process(COMMAND date +%s%N OUTPUT_VARIABLE t0 OUTPUT_STRIP_TRAILING_WHITESPACE)
  execute_process(COMMAND ${EXE} ${ARGN} WORKING_DIRECTORY ${WORKDIR} TIMEOUT 20
                  RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE stderr)
  execute_process(COMMAND date +%s%N OUTPUT_VARIABLE t1 OUTPUT_STRIP_TRAILING_WHITESPACE)
  math(EXPR ms "(${t1} - ${t0}) / 1000000")
  string(REGEX REPLACE "\n$" "" line "${stderr}")
  if(NOT status EQUAL 2 OR line MATCHES "\n" OR NOT line MATCHES "${expect}")
    message(FATAL_ERROR "${what}: exit ${status}, expected one line matching '${expect}':\n${stderr}")
  endif()
  if(DEFINED baseline)
    math(EXPR limit "${baseline} + 1000")
  else()
    set(limit 100000)
  endif()
  if(ms GREATER limit)
    message(FATAL_ERROR "${what}: refused after ${ms} ms (a plain refusal: ${baseline} ms)")
  endif()
  message(STATUS "${what}: ${ms} ms: ${line}")
  set(ms ${ms} PARENT_SCOPE)
endfunction()

set(short --set "Pantograph/Final position=2.5" --set Output/Plots=false)
set(resume --set "Checkpoint/Resume from checkpoint=true")
file(MAKE_DIRECTORY ${WORKDIR}/fifo ${WORKDIR}/zero)
execute_process(COMMAND mkfifo ${WORKDIR}/fifo/checkpoint.bin
                               ${WORKDIR}/fifo/speed_sweep.csv.partial ${WORKDIR}/case.prm)
file(CREATE_LINK /dev/zero ${WORKDIR}/zero/checkpoint.bin SYMBOLIC)
file(CREATE_LINK /dev/zero ${WORKDIR}/zero/speed_sweep.csv.partial SYMBOLIC)

# The baseline: a resume without any checkpoint.
expect_refused_at_once("no checkpoint"
  "Checkpoint/Resume from checkpoint = true: there is no checkpoint none/checkpoint.bin"
  ${PRM} ${short} ${resume} -o none)
set(baseline ${ms})
expect_refused_at_once("a FIFO as checkpoint"
  "Checkpoint/Resume from checkpoint = true: the checkpoint fifo/checkpoint.bin is a FIFO, not a regular file[;] start afresh"
  ${PRM} ${short} ${resume} -o fifo)
expect_refused_at_once("/dev/zero as checkpoint"
  "Checkpoint/Resume from checkpoint = true: the checkpoint zero/checkpoint.bin is a symbolic link, not a regular file[;] start afresh"
  ${PRM} ${short} ${resume} -o zero)
expect_refused_at_once("a FIFO as partial file"
  "Sweep/Resume = true: fifo/speed_sweep.csv.partial is a FIFO, not a regular file[;] allowed: Resume = false"
  ${SWEEP} --set Sweep/Resume=true -o fifo)
expect_refused_at_once("/dev/zero as partial file"
  "Sweep/Resume = true: zero/speed_sweep.csv.partial is a symbolic link, not a regular file[;] allowed: Resume = false"
  ${SWEEP} --set Sweep/Resume=true -o zero)
expect_refused_at_once("a FIFO as parameter file"
  "cannot read parameter file 'case.prm': not a regular file that can be read"
  case.prm -o out)
