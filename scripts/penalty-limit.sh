#!/usr/bin/env bash
# The rigid limit of the penalty contact (issue 17, doc/impacts.md): runs
# prm/benchmark-32.prm (32 m/s, nothing switches) with the rigid unilateral
# contact and with Scene/Contact = penalty for each k_c, and prints per method
# the difference penalty - rigid of the 20 Hz filtered statistics (max, min,
# mean, sigma) and the observed order per decade of k_c,
# log10(|d(k_c)| / |d(10 k_c)|) (1 = like 1/k_c; per decade also for other steps), in two windows: x_p in
# [2, 17] m (the window ends 1 m before the run) and the whole run.
# Usage, from anywhere:  scripts/penalty-limit.sh [exe] [outdir] [method ...]
#   method: discretisation:integrator:dt, default fdm:bdf2:5e-5 fdm:half-explicit:5e-5
#   K="5e4 5e5 5e6 5e7 5e8" (default) sets the stiffnesses [N/m].
set -euo pipefail
cd "$(dirname "$0")/.."
exe=$(realpath "${1:-build/pantocat-fem}")
out=${2:-output/penalty-limit}
shift $(($# > 2 ? 2 : $#))
methods=("$@")
((${#methods[@]})) || methods=(fdm:bdf2:5e-5 fdm:half-explicit:5e-5)
stiffnesses=${K:-5e4 5e5 5e6 5e7 5e8}
window="2, 17"
mkdir -p "$out"

run() { # dir, discretisation, integrator, dt, more --set values...
  local dir=$1 disc=$2 integrator=$3 dt=$4
  shift 4
  local sets=()
  for s in "$@"; do sets+=(--set "$s"); done
  "$exe" prm/benchmark-32.prm --set "Discretisation/Method=$disc" \
    --set "Time integration/Integrator=$integrator" --set "Time integration/Time step=$dt" \
    --set "Statistics/Low-pass cut-off=20" --set "Statistics/Window=$window" \
    --set "Output/Plots=false" --set "Output/Verbosity=quiet" \
    --set "Output/Output directory=$dir" ${sets[@]+"${sets[@]}"} > "$dir.log" 2>&1 || true
}

for method in "${methods[@]}"; do
  IFS=: read -r disc integrator dt <<< "$method"
  base="$out/$disc-$integrator-$dt"
  run "$base-rigid" "$disc" "$integrator" "$dt" "Scene/Contact=unilateral"
  dirs=()
  for k in $stiffnesses; do
    run "$base-$k" "$disc" "$integrator" "$dt" "Scene/Contact=penalty" "Scene/Contact stiffness=$k"
    dirs+=("$k=$base-$k")
  done
  python3 - "$method" "$window" "$base-rigid" "${dirs[@]}" <<'PY'
import csv, json, math, os, sys

method, window, rigid_dir, runs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
names = ["max", "min", "mean", "std"]

def figures(d):
    """(window figures from summary.json, whole-run figures from contact_force.csv)"""
    s = json.load(open(os.path.join(d, "summary.json")))
    if s.get("status") != "completed":
        return None
    w = s["pantographs"][0]["statistics"]["filtered"]
    rows = list(csv.DictReader(open(os.path.join(d, "contact_force.csv"))))
    f = [float(r["lambda_p_filtered"]) for r in rows]
    m = sum(f) / len(f)
    whole = {"max": max(f), "min": min(f), "mean": m,
             "std": math.sqrt(sum((x - m) ** 2 for x in f) / len(f))}
    return [w[n] for n in names], [whole[n] for n in names]

def reason(d):
    log = open(d + ".log").read().strip().splitlines()
    return log[-1] if log else "no summary"

rigid = figures(rigid_dir)
if rigid is None:
    sys.exit(f"{method}: the rigid run failed: {reason(rigid_dir)}")
print(f"\n{method}: rigid, filtered, x_p in [{window}] m: " +
      ", ".join(f"{n} {v:.4f}" for n, v in zip(names, rigid[0])) + " N")
for which, label in ((0, f"x_p in [{window}] m"), (1, "whole run")):
    print(f"\n{label}: penalty - rigid [N], observed order per decade of k_c\n")
    print("| k_c [N/m] | d max | d min | d mean | d sigma | order max | order min | order mean | order sigma |")
    print("|---|---|---|---|---|---|---|---|---|")
    previous = None
    for run in runs:
        k, d = run.split("=", 1)
        f = figures(d) if os.path.exists(os.path.join(d, "summary.json")) else None
        if f is None:
            print(f"| {k} | {reason(d)[:125]} ... |||||||")
            previous = None
            continue
        diff = [a - b for a, b in zip(f[which], rigid[which])]
        orders = ["-"] * 4
        if previous is not None:
            decades = math.log10(float(k) / previous_k)
            orders = [f"{math.log10(abs(p / x)) / decades:.2f}" if x != 0 and p != 0 else "-"
                      for p, x in zip(previous, diff)]
        print(f"| {k} | " + " | ".join(f"{x:.3e}" for x in diff) + " | " + " | ".join(orders) + " |")
        previous, previous_k = diff, float(k)
PY
done
