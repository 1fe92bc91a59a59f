#!/usr/bin/env bash
# The plots of issue 16 from the benchmarks' Markdown tables:
#   doc/figures/scaling-unknowns.png     time per step against n (bench_scaling)
#   doc/figures/scaling-constraints.png  time per step against m (bench_constraints)
#   doc/figures/scaling-constraints-section.png  the same on a 1000 m span, where
#       m = 200 is a real section's density (bench_constraints --span=1000)
# Usage, from the repository root:
#   scripts/plot-scaling.sh SCALING_TABLE CONSTRAINTS_TABLE [SECTION_TABLE]
# where the tables are the saved outputs of
#   build/bench_scaling > doc/figures/scaling-unknowns.md
#   build/bench_constraints 20000 2 10 40 100 200 > doc/figures/scaling-constraints.md
#   build/bench_constraints 8000 10 40 100 200 --span=1000 \
#       > doc/figures/scaling-constraints-section.md
set -euo pipefail
cd "$(dirname "$0")/.."
scaling=${1:-doc/figures/scaling-unknowns.md}
constraints=${2:-doc/figures/scaling-constraints.md}
section=${3:-doc/figures/scaling-constraints-section.md}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# bench_scaling: | spans | (n | m | us/step | ns/(n step) |) x 4 columns.
python3 - "$scaling" "$work/unknowns.dat" <<'PY'
import sys
rows = [l for l in open(sys.argv[1]) if l.startswith("|") and not l.startswith("|---")]
header = [c.strip() for c in rows[0].strip().strip("|").split("|")]
names = [header[1 + 4 * k].rsplit(":", 1)[0] for k in range((len(header) - 1) // 4)]
with open(sys.argv[2], "w") as out:
    for k, name in enumerate(names):
        out.write(f'"{name}"\n')
        for r in rows[1:]:
            c = [x.strip() for x in r.strip().strip("|").split("|")]
            out.write(f"{c[1 + 4 * k]} {c[3 + 4 * k]} {c[2 + 4 * k]}\n")
        out.write("\n\n")
PY
# bench_constraints: | m | (us/step | ratio |) x columns; its first table only
# (the steps in banded solves follow it after a blank line).
for table in "$constraints" "$section"; do
[ -f "$table" ] || continue
python3 - "$table" "$work/$(basename "$table" .md).dat" <<'PY'
import itertools, sys
lines = itertools.dropwhile(lambda l: not l.startswith("|"), open(sys.argv[1]))
first = itertools.takewhile(lambda l: l.startswith("|"), lines)
rows = [l for l in first if not l.startswith("|---")]
header = [c.strip() for c in rows[0].strip().strip("|").split("|")]
names = [header[1 + 2 * k].replace(" [us/step]", "") for k in range((len(header) - 1) // 2)]
with open(sys.argv[2], "w") as out:
    for k, name in enumerate(names):
        out.write(f'"{name}"\n')
        for r in rows[1:]:
            c = [x.strip() for x in r.strip().strip("|").split("|")]
            if c[0].isdigit():
                out.write(f"{max(int(c[0]), 1)} {c[1 + 2 * k]}\n")
        out.write("\n\n")
PY
done
n_unknowns=$(grep -c '^"' "$work/unknowns.dat")
constraints_dat="$work/$(basename "$constraints" .md).dat"
section_dat="$work/$(basename "$section" .md).dat"
n_constraints=$(grep -c '^"' "$constraints_dat")
# The settings all three plots share.
preamble="set terminal pngcairo size 1000,650 noenhanced
set colorsequence podo
set logscale xy
set format x '%g'
set grid xtics ytics mxtics mytics
set key top left"
gnuplot <<EOF
$preamble
set output 'doc/figures/scaling-unknowns.png'
set title "Time per step against unknowns n (bench_scaling: 20 m spans repeated, dx = 0.04 m, m = 3 per span)" font ',11'
set xrange [500:200000]
set xlabel 'unknowns n'
set ylabel 'time per step [us]'
plot for [k=0:$((n_unknowns - 1))] '$work/unknowns.dat' index k using 1:2 with linespoints lw 2 title columnheader(1), \
     [1000:100000] x * 0.01 with lines dt 2 lc 'gray' title 'slope 1 (10 ns per unknown)'
set output 'doc/figures/scaling-constraints.png'
set title "Time per step against fixed constraints m (bench_constraints: one 100 m span; m = 0 drawn at 1)" font ',11'
set xrange [*:*]
set xlabel 'fixed constraints m (droppers)'
plot for [k=0:$((n_constraints - 1))] '$constraints_dat' index k using 1:2 with linespoints lw 2 title columnheader(1)
EOF
echo "wrote doc/figures/scaling-unknowns.png doc/figures/scaling-constraints.png"
if [ -f "$section_dat" ]; then
  n_section=$(grep -c '^"' "$section_dat")
  gnuplot <<EOF
$preamble
set output 'doc/figures/scaling-constraints-section.png'
set title "Time per step against fixed constraints m on a 1000 m span (m = 200: 5 m apart, a real section's density; m = 0 drawn at 1)" font ',11'
set xlabel 'fixed constraints m (droppers)'
set ylabel 'time per step [us]'
plot for [k=0:$((n_section - 1))] '$section_dat' index k using 1:2 with linespoints lw 2 title columnheader(1)
EOF
  echo "wrote doc/figures/scaling-constraints-section.png"
fi
