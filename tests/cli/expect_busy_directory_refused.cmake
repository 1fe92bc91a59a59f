# Two runs into one output directory (doc/studies.md, "One run per output
# directory"): the first holds the directory's lock while it runs; the second,
# started meanwhile, is refused at once (exit 2, one line naming the
# directory and the first run's process; it does not wait for the lock) and
# touches nothing: the first run completes, and its parameters.prm and
# summary.json are its own.
#   -DEXE=... -DPRM=prm/benchmark-32.prm -DWORKDIR=dir
cmake_minimum_required(VERSION 3.13)
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
set(out ${WORKDIR}/out)
# The first run is held (SIGSTOP) as soon as it has written its
# parameters.prm, after taking the lock; the second runs meanwhile, and the
# first then goes on (SIGCONT) and completes.
file(WRITE ${WORKDIR}/two_runs.sh [=[
exe=$1; prm=$2; out=$3
"$exe" "$prm" -o "$out" --set Output/Plots=false --set "Time integration/Time step=1e-5" \
  --set "Output/Time series interval=10" >first.out 2>first.err &
first=$!
while [ ! -s "$out/parameters.prm" ] && kill -0 $first 2>/dev/null; do :; done
kill -STOP $first
ls -lA --time-style=+%s.%N "$out" >listing.before
md5sum "$out"/* >content.before
start=$(date +%s%N)
"$exe" "$prm" -o "$out" --set "Pantograph/Final position=3" >second.out 2>second.err
echo $? >second.status
ls -lA --time-style=+%s.%N "$out" >listing.after
md5sum "$out"/* >content.after
echo $(( ($(date +%s%N) - start) / 1000000 )) >second.ms
kill -0 $first 2>/dev/null && echo running >first.when_second_ended
kill -CONT $first
wait $first
echo $? >first.status
]=])
execute_process(COMMAND sh two_runs.sh ${EXE} ${PRM} ${out} WORKING_DIRECTORY ${WORKDIR}
                TIMEOUT 60 RESULT_VARIABLE status)
file(STRINGS ${WORKDIR}/second.status second_status)
file(STRINGS ${WORKDIR}/second.ms second_ms)
file(STRINGS ${WORKDIR}/first.status first_status)
file(READ ${WORKDIR}/second.err second_err)
file(READ ${WORKDIR}/first.err first_err)
if(NOT EXISTS ${WORKDIR}/first.when_second_ended)
  message(FATAL_ERROR "the first run ended before the second: no overlap to test")
endif()
string(REGEX REPLACE "\n$" "" line "${second_err}")
if(NOT second_status EQUAL 2 OR line MATCHES "\n" OR NOT line MATCHES
   "^pantocat-fem: error: Output/Output directory = .*/out: another run [(]process [0-9]+[)] is writing into this directory[;] wait until it ends or choose another directory$")
  message(FATAL_ERROR "the second run: exit ${second_status}, expected one refusal line:\n${second_err}")
endif()
foreach(what listing content)
  file(READ ${WORKDIR}/${what}.before before)
  file(READ ${WORKDIR}/${what}.after after)
  if(NOT before STREQUAL after)
    message(FATAL_ERROR "the refused run changed the directory:\n${before}\n${after}")
  endif()
endforeach()
if(NOT first_status EQUAL 0)
  message(FATAL_ERROR "the first run failed (${first_status}):\n${first_err}")
endif()
file(READ ${out}/summary.json summary)
file(READ ${out}/parameters.prm parameters)
if(NOT summary MATCHES "\"status\": \"completed\"" OR
   NOT parameters MATCHES "set Final position += 18\n" OR
   parameters MATCHES "set Final position += 3 ")
  message(FATAL_ERROR "the first run's outputs are not its own:\n${summary}")
endif()
message(STATUS "second run refused in ${second_ms} ms: ${line}")
