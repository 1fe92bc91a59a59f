# report.html of S55 (and a speed sweep's report) as a real browser reads
# them: Debian's chromium, headless, parses each page and dumps its DOM. The
# run's page must hold the assessment table with one row per criterion, the
# statistics table and the three pictures as inline SVG (force over x, uplift,
# dropper slack), each with a drawn path; the sweep's page its table of runs
# and its picture. Labelled `browser` (needs chromium: scripts/install-dependencies.sh --browser).
#   -DEXE=... -DPRM=... -DSWEEP_PRM=... -DOUTDIR=dir
include(${CMAKE_CURRENT_LIST_DIR}/run_or_fail.cmake)
find_program(CHROMIUM NAMES chromium chromium-browser)
if(NOT CHROMIUM)
  message(FATAL_ERROR "chromium is not installed (scripts/install-dependencies.sh --browser)")
endif()
file(REMOVE_RECURSE ${OUTDIR})

function(dom_of page variable)
  execute_process(COMMAND ${CHROMIUM} --headless --no-sandbox --disable-gpu
                          --dump-dom file://${page}
                  OUTPUT_VARIABLE dom ERROR_QUIET RESULT_VARIABLE rc TIMEOUT 120)
  if(NOT rc EQUAL 0 OR NOT dom MATCHES "</html>")
    message(FATAL_ERROR "chromium could not read ${page} (exit ${rc})")
  endif()
  set(${variable} "${dom}" PARENT_SCOPE)
endfunction()

function(expect_count dom pattern expected what)
  string(REGEX MATCHALL "${pattern}" found "${dom}")
  list(LENGTH found n)
  if(NOT n EQUAL expected)
    message(FATAL_ERROR "${what}: ${n} found, ${expected} expected")
  endif()
endfunction()

run_or_fail("run" out COMMAND ${EXE} ${PRM} -o ${OUTDIR}/run)
dom_of(${OUTDIR}/run/report.html dom)
expect_count("${dom}" "<svg[ >]" 3 "inline SVG pictures in report.html")
expect_count("${dom}" "<figure>" 3 "figures in report.html")
expect_count("${dom}" "<td class=\"(pass|fail)\">" 6 "assessed criteria in report.html")
if(NOT dom MATCHES "id=\"statistics-1\"" OR NOT dom MATCHES "id=\"contact-events\""
   OR NOT dom MATCHES "<path")
  message(FATAL_ERROR "report.html lacks its statistics, its events or drawn curves")
endif()

run_or_fail("sweep" out COMMAND ${EXE} ${SWEEP_PRM} -o ${OUTDIR}/sweep
            --set "Sweep/Speeds=250, 320" --set "Pantograph/Final position=330")
dom_of(${OUTDIR}/sweep/speed_sweep_report.html dom)
expect_count("${dom}" "<svg[ >]" 1 "inline SVG pictures in speed_sweep_report.html")
expect_count("${dom}" "<tr>" 3 "rows of the runs table (header and two speeds)")
