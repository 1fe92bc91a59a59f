#!/usr/bin/env bash
# The S55 figures of doc/catenaries.md: the shipped cases and a grid study
# (element size h and step dt, FEM and FDM) of the evaluation window's
# contact-force statistics. Runs the program once per row and prints one
# Markdown table row per run from its summary.json.
# Usage, from the repository root:  scripts/s55-study.sh [exe] [outdir] [group]
#   group: cases | fdm | fem | all (default all)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pantocat-fem}
out=${2:-output/s55-study}
group=${3:-all}
mkdir -p "$out"

row() { # name, prm, --set arguments...
  local name=$1 prm=$2
  shift 2
  local dir="$out/$name" sets=()
  for s in "$@"; do sets+=(--set "$s"); done
  local start end
  start=$(date +%s.%N)
  "$exe" "$prm" --set "Output/Output directory=$dir" --set "Output/Plots=false" \
    "${sets[@]}" > "$dir.log" 2>&1 || { echo "| $name | failed: $(tail -1 "$dir.log") |"; return; }
  end=$(date +%s.%N)
  python3 - "$dir/summary.json" "$name" "$start" "$end" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
wall = float(sys.argv[4]) - float(sys.argv[3])
for k, p in enumerate(s["pantographs"]):
    st = p["statistics"]
    r, f = st["raw"], st["filtered"]
    up = st.get("max_steady_arm_uplift_m")
    uplift = "-" if up is None else f"{1000 * up:.1f}"
    name = sys.argv[2] + (f" p{k + 1}" if len(s["pantographs"]) > 1 else "")
    print(f"| {name} | {s['discretisation']} {s['number_of_intervals']} "
          f"| {s['integrator']} {s['time_step']:g} "
          f"| {f['mean']:.2f} | {f['std']:.2f} | {f['max']:.1f} | {f['min']:.1f} "
          f"| {r['std']:.2f} | {r['max']:.1f} | {r['min']:.1f} "
          f"| {r['contact_loss_percent']:.2f} | {uplift} | {wall:.0f} s |")
PY
}

echo "| run | grid | method, dt [s] | F_m filt. [N] | sigma filt. | max filt. | min filt. | sigma raw | max raw | min raw | loss raw [%] | steady-arm uplift [mm] | wall |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
S=prm/catenary/section-s55.prm
if [[ $group == cases || $group == all ]]; then
  row s55-320 $S
  row s55-250 prm/catenary/section-s55-250kmh.prm
  row s55-two prm/catenary/section-s55-two-pantographs.prm
fi
if [[ $group == fdm || $group == all ]]; then
  for n in 1100 2200 4400; do
    row fdm-$n $S "Discretisation/Method=fdm" "Discretisation/Number of intervals=$n"
  done
  for dt in 2e-4 5e-5; do
    row fdm-2200-dt$dt $S "Discretisation/Method=fdm" "Time integration/Time step=$dt"
  done
fi
if [[ $group == fem || $group == all ]]; then
  row fem-1100 $S "Discretisation/Number of intervals=1100"
  row fem-2200-dt2e-4 $S "Time integration/Time step=2e-4"
fi
