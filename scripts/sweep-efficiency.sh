#!/usr/bin/env bash
# Parallel efficiency of a sweep on 2 MPI ranks (issue 18, doc/studies.md):
# runs the sweep serially and with mpirun -np 2, checks that both write the
# same CSV, and prints
#   wall-clock efficiency  E = T_1 / (2 T_2)
#   load balance           B = (busy time of both ranks) / (2 T_2)
#   CPU share              S = CPU time / wall time of the runs, serial and on 2 ranks
# (B from <name>_runs.csv: how well the work queue keeps both ranks busy,
# whatever else the machine runs; E also counts the cores' contention, which
# S shows: S = 1 on an idle machine, about 0.5 if other jobs hold a core;
# E S1/S2 estimates the efficiency the ranks would reach on whole cores).
# A benchmark, not a test: run it on an otherwise idle machine.
#   scripts/sweep-efficiency.sh [prm] [build dir]
# From the repository root; default prm/studies/speed-sweep-s55.prm.
set -euo pipefail
prm=${1:-prm/studies/speed-sweep-s55.prm}
exe=${2:-build}/pantocat-fem
out=$(mktemp -d)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
now() { date +%s.%N; }
t0=$(now); "$exe" "$prm" -o "$out/serial" --set "Output/Plots=false" > "$out/serial.log"; t1=$(now)
mpirun --oversubscribe -np 2 "$exe" "$prm" -o "$out/mpi" --set "Output/Plots=false" > "$out/mpi.log"; t2=$(now)
name=$(basename "$(ls "$out"/serial/*_runs.csv)" _runs.csv)
cmp -s "$out/serial/$name.csv" "$out/mpi/$name.csv" || { echo "CSV differ"; exit 1; }
share() { awk -F, 'NR > 1 { wall += $(NF - 3); cpu += $(NF - 2) } END { printf "%.2f", cpu / wall }' "$1"; }
awk -v t1="$(echo "$t1 - $t0" | bc)" -v t2="$(echo "$t2 - $t1" | bc)" \
  -v s1="$(share "$out/serial/${name}_runs.csv")" -v s2="$(share "$out/mpi/${name}_runs.csv")" \
  -v load="$(cut -d' ' -f1-3 /proc/loadavg)" -F, '
  NR > 1 { busy += $(NF - 3) }
  END { printf "serial %.1f s, 2 ranks %.1f s: efficiency %.2f, load balance %.2f, CPU share %s serial, %s on 2 ranks (load %s); with whole cores (E S1/S2) about %.2f\n",
        t1, t2, t1 / (2 * t2), busy / (2 * t2), s1, s2, load, t1 * s1 / (2 * t2 * s2) }' "$out/mpi/${name}_runs.csv"
rm -rf "$out"
