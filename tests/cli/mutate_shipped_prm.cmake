# Mutation test of the shipped prm files (issue 6, "Bad input"): every file of
# prm/ with each of the mutations below must end with exit status 2, exactly
# one line on stderr that matches the expected message (parameter, value, what
# is allowed), and no output directory left behind. Mutations are appended
# to the file (a later entry overrides an earlier one) or cut it short.
#   -DEXE=... -DPRM_DIR=... -DWORKDIR=...
cmake_minimum_required(VERSION 3.13) # quoted if() arguments are not variables (CMP0054)
set(names wrong_type out_of_range_span negative_dropper_length dropper_outside_span
          epsilon_wider_than_span speed_not_positive grid_too_coarse unknown_subsection
          misspelled_entry rho_infinity_above_one tolerance_not_positive inconsistent_scene
          guard_bound_not_positive truncated_file)
set(wrong_type "subsection Discretisation\n  set Number of intervals = abc\nend\n")
set(wrong_type_expect "abc for the entry named Number of intervals does not match")
set(out_of_range_span "subsection Catenary\n  set Span = -3\nend\n")
set(out_of_range_span_expect "-3 for the entry named Span does not match")
set(negative_dropper_length
    "subsection Catenary\n  subsection Droppers\n    set Lengths = -0.95, 0.95\n  end\nend\n")
set(negative_dropper_length_expect "-0.95, 0.95 for the entry named Lengths does not match")
set(dropper_outside_span
    "subsection Catenary\n  subsection Droppers\n    set Positions = 5.5, 25\n  end\nend\n")
set(dropper_outside_span_expect "Positions = 25: positions are measured from the span's first support and must lie inside span 1")
set(epsilon_wider_than_span "subsection Discretisation\n  set Load half-width = 30\nend\n")
set(epsilon_wider_than_span_expect "Load half-width = 30: must lie in")
set(speed_not_positive "subsection Pantograph\n  set Speed = -5\nend\n")
set(speed_not_positive_expect "Speed = -5: must be > 0")
set(grid_too_coarse
    "subsection Discretisation\n  set Method = fdm\n  set Number of intervals = 2\nend\n")
set(grid_too_coarse_expect "Number of intervals = 2: grid too coarse")
# Studies take N+1 from their own list (checked before any run starts); the
# eigenfrequency mode has no droppers, so any N+1 >= 2 is allowed there.
set(grid_too_coarse_in_study "subsection Study\n  set Number of intervals = 2\nend\n")
set(grid_too_coarse_in_study_expect "Study.*Number of intervals = 2: ")
set(unknown_subsection "subsection Foo\nend\n")
set(unknown_subsection_expect "no such subsection.*Foo")
set(misspelled_entry "subsection Catenary\n  set Lenght = 20\nend\n")
set(misspelled_entry_expect "No entry with name <Lenght>")
set(rho_infinity_above_one "subsection Time integration\n  set Spectral radius at infinity = 2\nend\n")
set(rho_infinity_above_one_expect "2 for the entry named Spectral radius at infinity does not match")
set(tolerance_not_positive "subsection Time integration\n  set IDA relative tolerance = 0\nend\n")
set(tolerance_not_positive_expect "IDA relative tolerance = 0: must be > 0")
set(inconsistent_scene
    "subsection Scene\n  set Contact wire = rigid\n  set Pantograph = moving force\nend\n")
set(inconsistent_scene_expect "Scene/Pantograph = moving force: a prescribed force on a rigid")
set(guard_bound_not_positive "subsection Guards\n  set Multiplier bound = 0\nend\n")
set(guard_bound_not_positive_expect "Guards/Multiplier bound = 0: must be > 0")
set(truncated_file_expect "unequal numbers of 'subsection' and 'end'")

file(GLOB cases ${PRM_DIR}/*.prm ${PRM_DIR}/scenes/*.prm)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
set(count 0)
set(failures "")
foreach(prm ${cases})
  get_filename_component(stem ${prm} NAME_WE)
  get_filename_component(folder ${prm} DIRECTORY)
  if(folder MATCHES "scenes$")
    set(stem "scene-${stem}")
  endif()
  file(READ ${prm} text)
  foreach(name ${names})
    # Without droppers (the eigenfrequency mode, scenes with Droppers = absent) any
    # N+1 >= 2 is allowed.
    if(name STREQUAL "grid_too_coarse" AND text MATCHES "Mode = eigenfrequencies|Droppers = absent")
      continue()
    endif()
    # A point load has no width.
    if(name STREQUAL "epsilon_wider_than_span" AND text MATCHES "Load shape = point")
      continue()
    endif()
    set(expect "${${name}_expect}")
    if(name STREQUAL "grid_too_coarse" AND text MATCHES "Mode = (convergence study|work precision)")
      set(mutated "${text}\n${grid_too_coarse_in_study}")
      set(expect "${grid_too_coarse_in_study_expect}")
    elseif(name STREQUAL "truncated_file")
      # Cut the file right after its first 'subsection' line.
      string(FIND "${text}" "\nsubsection " at)
      math(EXPR at "${at} + 1")
      string(SUBSTRING "${text}" ${at} -1 rest)
      string(FIND "${rest}" "\n" eol)
      math(EXPR keep "${at} + ${eol} + 1")
      string(SUBSTRING "${text}" 0 ${keep} mutated)
    else()
      set(mutated "${text}\n${${name}}")
    endif()
    set(file ${WORKDIR}/${stem}-${name}.prm)
    set(out ${WORKDIR}/${stem}-${name}-output)
    file(WRITE ${file} "${mutated}")
    execute_process(COMMAND ${EXE} ${file} -o ${out} RESULT_VARIABLE status
                    OUTPUT_VARIABLE stdout ERROR_VARIABLE err TIMEOUT 60)
    string(STRIP "${err}" line)
    string(FIND "${line}" "\n" newline)
    math(EXPR count "${count} + 1")
    if(NOT status EQUAL 2)
      list(APPEND failures "${stem} + ${name}: exit status ${status}, stderr: ${err}")
    elseif(NOT newline EQUAL -1)
      list(APPEND failures "${stem} + ${name}: more than one line on stderr: ${err}")
    elseif(NOT line MATCHES "${expect}")
      list(APPEND failures "${stem} + ${name}: '${line}' does not match '${expect}'")
    elseif(EXISTS ${out})
      list(APPEND failures "${stem} + ${name}: output directory left behind")
    endif()
  endforeach()
endforeach()
list(LENGTH failures n_failed)
message(STATUS "${count} mutation cases of the shipped prm files, ${n_failed} failed")
if(n_failed GREATER 0)
  string(REPLACE ";" "\n" failures "${failures}")
  message(FATAL_ERROR "${failures}")
endif()
