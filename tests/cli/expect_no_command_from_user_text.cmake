# No value of a prm file or the command line runs a command through gnuplot
# (doc/input-errors.md, "Names, links and files that are not what they say").
# Every user text that becomes a file name (Sweep/Output name, Study/Output
# name) with a value of the injection list (quotes with gnuplot's system(),
# back quotes, $(...), a macro, a newline, a path, a 300-character name), in
# each study and sweep mode with Output/Plots = true, by --set and in a prm
# file (Monte Carlo): each is refused with exit 2 and one line naming the
# parameter, before anything is written. An output directory holding the same text (which is no file name
# in a script: gnuplot runs inside it) runs and draws its plots. Nothing the
# values ask for ever runs: no file PWNED* appears anywhere under WORKDIR.
#   -DEXE=... -DSTUDIES=tests/studies -DWORKDIR=dir
cmake_minimum_required(VERSION 3.13)
string(ASCII 10 newline)
string(ASCII 59 semicolon)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
set(out ${WORKDIR}/out)

# SEMI stands for ';', which would split a CMake list.
set(injections
    "x'SEMI system(\"touch PWNED1\")SEMI print '"
    "x\"SEMI system(\"touch PWNED2\")SEMI print \""
    "a`touch PWNED3`"
    "$(touch PWNED4)"
    "@macro"
    "../PWNED5"
    ".hidden"
    "-x")
string(REPEAT "n" 300 long)
list(APPEND injections "${long}")

function(expect_no_marker what)
  file(GLOB_RECURSE markers ${WORKDIR}/*PWNED*)
  if(markers)
    message(FATAL_ERROR "${what} ran a command: ${markers}")
  endif()
endfunction()

# Runs EXE on PRM with "--set PARAMETER=VALUE" (none if SET is false);
# expects exit 2, one line naming PARAMETER, no output directory.
function(expect_refused prm parameter value set)
  string(REPLACE "SEMI" "${semicolon}" value "${value}")
  if(set)
    execute_process(COMMAND ${EXE} ${prm} -o ${out} --set Output/Plots=true
                            --set "${parameter}=${value}"
                    WORKING_DIRECTORY ${WORKDIR}
                    RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE stderr)
  else()
    execute_process(COMMAND ${EXE} ${prm} -o ${out} WORKING_DIRECTORY ${WORKDIR}
                    RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE stderr)
  endif()
  string(REGEX REPLACE "\n$" "" line "${stderr}")
  if(NOT status EQUAL 2 OR line MATCHES "\n" OR
     NOT line MATCHES "^pantocat-fem: error: ${parameter} = .*: a file base name of 1 to 64 characters")
    message(FATAL_ERROR "${parameter} = '${value}': exit ${status}, expected one refusal line:\n${stderr}")
  endif()
  if(EXISTS ${out})
    message(FATAL_ERROR "${parameter} = '${value}': the refusal left ${out}")
  endif()
  expect_no_marker("${parameter} = '${value}'")
endfunction()

# Each route once end to end (the whole list through every mode's parsing:
# FileSafety.EveryOutputNameInEveryModeRefusesTheInjectionList).
set(cases "small-speed-sweep.prm:Sweep:0" "small-parameter-sweep.prm:Sweep:1"
          "small-monte-carlo.prm:Sweep:2" "small-convergence.prm:Study:3"
          "small-work-precision.prm:Study:4" "small-contact.prm:Study:8")
set(n 0)
foreach(case ${cases})
  string(REPLACE ":" ";" parts "${case}")
  list(GET parts 0 prm)
  list(GET parts 1 subsection)
  list(GET parts 2 index)
  list(GET injections ${index} value)
  expect_refused(${STUDIES}/${prm} "${subsection}/Output name" "${value}" TRUE)
  math(EXPR n "${n} + 1")
endforeach()

# In a prm file (a shared Monte Carlo case).
foreach(index 0 5)
  list(GET injections ${index} value)
  string(REPLACE "SEMI" "${semicolon}" text "${value}")
  file(WRITE ${WORKDIR}/case.prm
       "include ${STUDIES}/small-monte-carlo.prm\nsubsection Output\n  set Plots = true\nend\n"
       "subsection Sweep\n  set Output name = ${text}\nend\n")
  expect_refused(case.prm "Sweep/Output name" "${value}" FALSE)
  math(EXPR n "${n} + 1")
endforeach()

# A newline cannot be in a prm value; by --set it is refused as a control character.
execute_process(COMMAND ${EXE} ${STUDIES}/small-speed-sweep.prm -o ${out}
                        --set "Sweep/Output name=a${newline}system(\"touch PWNED6\")"
                WORKING_DIRECTORY ${WORKDIR} RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "^pantocat-fem: error: --set Sweep/Output name=a.x0a.*control character")
  message(FATAL_ERROR "a newline in Sweep/Output name: exit ${status}:\n${stderr}")
endif()
expect_no_marker("a newline in Sweep/Output name")

# The injected text as the output directory: the sweep runs and draws its plot there.
set(dir "x'${semicolon} system(\"touch PWNED7\")${semicolon} print '`touch PWNED8`")
execute_process(COMMAND ${EXE} ${STUDIES}/small-speed-sweep.prm -o "${dir}"
                        --set Output/Plots=true --set "Sweep/Speeds=115.2"
                WORKING_DIRECTORY ${WORKDIR} RESULT_VARIABLE status OUTPUT_VARIABLE stdout
                ERROR_VARIABLE stderr)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "a sweep into '${dir}': exit ${status}\n${stderr}")
endif()
expect_no_marker("a sweep into '${dir}'")
if(GNUPLOT AND NOT EXISTS "${WORKDIR}/${dir}/speed_sweep.png")
  message(FATAL_ERROR "gnuplot drew no speed_sweep.png in '${dir}':\n${stdout}")
endif()
message(STATUS "${n} injected names refused with one line; nothing ran; plots drawn: ${GNUPLOT}")
