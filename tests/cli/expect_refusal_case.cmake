# One bad-input case of the command line and the prm reader (doc/input-errors.md,
# "Refusals of the command line"): exit status 2, exactly one line on stderr
# matching the expected message, no output directory left, and nothing the
# user had lost or changed (an input parameters.prm, an earlier run's files).
#   -DEXE=... -DCASE=name -DWORKDIR=dir -DPRM=prm/benchmark-32.prm
cmake_minimum_required(VERSION 3.13)
string(ASCII 10 newline)
string(ASCII 1 control)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
set(out ${WORKDIR}/out)
set(short "Pantograph/Final position=2.2")

# Runs EXE with ARGN in WORKDIR; expects exit 2 and one line matching EXPECT.
function(expect_refusal expect)
  execute_process(COMMAND ${EXE} ${ARGN} WORKING_DIRECTORY ${WORKDIR}
                  RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  if(NOT status EQUAL 2)
    message(FATAL_ERROR "${CASE}: expected exit status 2, got '${status}'\n${stderr}")
  endif()
  string(REGEX REPLACE "\n$" "" line "${stderr}")
  if(line MATCHES "\n" OR NOT line MATCHES "${expect}")
    message(FATAL_ERROR "${CASE}: expected one line matching '${expect}', got:\n${stderr}")
  endif()
  message(STATUS "${CASE}: ${line}")
endfunction()

function(expect_no_output_directory)
  if(EXISTS ${out})
    message(FATAL_ERROR "${CASE}: bad input left ${out} behind")
  endif()
endfunction()

if(CASE STREQUAL "set_with_newline")
  # The newline would inject "end / subsection Output / set Plots = false".
  expect_refusal("--set Pantograph/Final position=2.2.x0aend.x0asubsection Output.x0aset Plots = false: contains the control character .x0a"
                 ${PRM} -o ${out}
                 --set "${short}${newline}end${newline}subsection Output${newline}set Plots = false")
  expect_no_output_directory()
elseif(CASE STREQUAL "set_with_control_character")
  expect_refusal("--set Catenary/Span=20.x01: contains the control character .x01"
                 ${PRM} -o ${out} --set "Catenary/Span=20${control}")
  expect_no_output_directory()
elseif(CASE STREQUAL "output_directory_with_newline")
  # It would go into parameters.prm there, a line of its own when read again.
  expect_refusal("-o out.x0asubsection Foo: a directory name with a control character"
                 ${PRM} -o "out${newline}subsection Foo")
  expect_no_output_directory()
elseif(CASE STREQUAL "print_parameters_unknown_format")
  expect_refusal("^pantocat-fem: error: --print-parameters xml: unknown format[;] allowed: prm [|] json$"
                 --print-parameters xml)
elseif(CASE STREQUAL "empty_output_directory")
  # (Written out: an empty word would not survive ARGN.)
  execute_process(COMMAND ${EXE} ${PRM} -o "" WORKING_DIRECTORY ${WORKDIR}
                  RESULT_VARIABLE status ERROR_VARIABLE stderr)
  string(STRIP "${stderr}" line)
  if(NOT status EQUAL 2 OR line MATCHES "\n" OR
     NOT line MATCHES "Output/Output directory = '': must name a directory")
    message(FATAL_ERROR "${CASE}: exit ${status}, expected one line:\n${stderr}")
  endif()
  if(EXISTS ${WORKDIR}/parameters.prm)
    message(FATAL_ERROR "${CASE}: -o '' wrote ./parameters.prm")
  endif()
elseif(CASE STREQUAL "directory_as_parameter_file")
  file(MAKE_DIRECTORY ${WORKDIR}/case.prm)
  expect_refusal("cannot read parameter file '.*case.prm': this is a directory" ${WORKDIR}/case.prm -o ${out})
  expect_no_output_directory()
elseif(CASE STREQUAL "include_of_a_directory")
  file(MAKE_DIRECTORY ${WORKDIR}/more)
  file(WRITE ${WORKDIR}/case.prm "subsection Catenary\n  include more # a directory\nend\n")
  expect_refusal("Line <2> of file <case.prm>: include more: this is a directory" case.prm -o ${out})
  expect_no_output_directory()
elseif(CASE STREQUAL "include_of_a_device")
  file(WRITE ${WORKDIR}/case.prm "include /dev/zero\n")
  expect_refusal("include /dev/zero: not a regular file" case.prm -o ${out})
  expect_no_output_directory()
elseif(CASE STREQUAL "file_includes_itself")
  file(WRITE ${WORKDIR}/case.prm "subsection Catenary\nend\ninclude case.prm\n")
  expect_refusal("Line <3> of file <case.prm>: include case.prm: include cycle .*case.prm -> .*case.prm" case.prm -o ${out})
  expect_no_output_directory()
elseif(CASE STREQUAL "include_cycle")
  file(WRITE ${WORKDIR}/a.prm "include b.prm\n")
  file(WRITE ${WORKDIR}/b.prm "include \\\n  c.prm\n")
  file(WRITE ${WORKDIR}/c.prm "INCLUDE\ta.prm\n")
  expect_refusal("Line <1> of file <c.prm>: include a.prm: include cycle .*a.prm -> .*b.prm -> .*c.prm -> .*a.prm" a.prm -o ${out})
  expect_no_output_directory()
elseif(CASE STREQUAL "summary_json_is_a_directory")
  file(MAKE_DIRECTORY ${out}/summary.json/kept)
  expect_refusal("Output/Output directory = .*out: .*out/summary.json is a directory" ${PRM} -o ${out} --set "${short}")
  if(NOT IS_DIRECTORY ${out}/summary.json/kept OR EXISTS ${out}/parameters.prm)
    message(FATAL_ERROR "${CASE}: the refusal changed the output directory")
  endif()
elseif(CASE STREQUAL "input_is_the_output_parameters")
  # README: "run it again with pantocat-fem output/benchmark-48/parameters.prm".
  # A refusal (here: inside the run, after parameters.prm was rewritten) puts
  # the input back as it was; an earlier run's results stay.
  execute_process(COMMAND ${EXE} ${PRM} -o ${out} --set "${short}" --set Output/Plots=false
                  RESULT_VARIABLE status OUTPUT_QUIET)
  file(SHA256 ${out}/parameters.prm before)
  file(SHA256 ${out}/summary.json summary_before)
  expect_refusal("Time integration/Time step = 0.0001: above the stability limit"
                 ${out}/parameters.prm --set "Time integration/Time step=1e-4")
  expect_refusal("Pantograph/Speed = -5: must be > 0" ${out}/parameters.prm --set "Pantograph/Speed=-5")
  file(SHA256 ${out}/parameters.prm after)
  file(SHA256 ${out}/summary.json summary_after)
  if(NOT before STREQUAL after OR NOT summary_before STREQUAL summary_after)
    message(FATAL_ERROR "${CASE}: a refusal changed the input parameters.prm or summary.json")
  endif()
elseif(CASE STREQUAL "warning_then_refusal_is_one_line")
  # A forced step above the limit warns; the unresolved load then refuses the
  # run: one line, the error.
  expect_refusal("^pantocat-fem: error: Discretisation/Number of intervals = 50: the grid spacing"
                 ${PRM} -o ${out} --set "Time integration/Time step=1e-3"
                 --set "Time integration/Force step size=true"
                 --set "Discretisation/Number of intervals=50")
  expect_no_output_directory()
else()
  message(FATAL_ERROR "unknown CASE ${CASE}")
endif()
