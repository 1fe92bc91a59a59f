# A Monte Carlo sample whose deviations install a dropper of length <= 0 is
# refused by the check a prm file's catenary goes through, not run: its row
# says refused with the reason, it is not in the distribution (n counts the
# completed samples only), and the summary on screen names it. With seed
# 1082 and a normal dropper length tolerance of 0.9 m on the paper's 0.95 m
# droppers, sample 1 (std::mt19937_64(1083)) draws -1.0487 m for dropper 2:
# an installed length of -0.0987228 m.
#   -DEXE=... -DPRM=small-monte-carlo.prm -DOUTDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${OUTDIR})
execute_process(COMMAND ${EXE} ${PRM} -o ${OUTDIR} --set "Sweep/Samples=4"
                        --set "Sweep/Seed=1082" --set "Sweep/Dropper length tolerance=0.9"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the study failed (${status}):\n${out}\n${err}")
endif()
set(reason "the catenary as installed [(]with its installation deviations[)] is refused: Catenary/Droppers/Lengths = -0.0987228: must be > 0")
string(REPEAT "," 16 empty) # the 15 figures of a run without figures
file(STRINGS ${OUTDIR}/monte_carlo.csv rows)
set(completed 0)
foreach(row ${rows})
  if(row MATCHES "^1,1${empty}refused,\"${reason}\"$")
    set(refused_row TRUE)
  elseif(row MATCHES ",completed,\"\"$")
    math(EXPR completed "${completed} + 1")
  elseif(row MATCHES "^1,")
    message(FATAL_ERROR "sample 1 is not refused with its reason: ${row}")
  endif()
endforeach()
if(NOT refused_row)
  message(FATAL_ERROR "no refused row of sample 1 in monte_carlo.csv:\n${rows}")
endif()
file(STRINGS ${OUTDIR}/monte_carlo_distribution.csv distribution REGEX "^std,1,")
if(NOT distribution MATCHES "^std,1,${completed},")
  message(FATAL_ERROR "the distribution of std is not over the ${completed} completed "
                      "samples: ${distribution}")
endif()
if(NOT out MATCHES "sample 1 refused: ${reason}")
  message(FATAL_ERROR "the summary does not name the refused sample:\n${out}")
endif()
message(STATUS "sample 1 refused; the distribution over ${completed} completed samples")
