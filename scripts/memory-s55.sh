#!/usr/bin/env bash
# Peak resident memory of the S55 run (prm/catenary/section-s55.prm) with 5,
# 10 and 20 spans of 55 m (issue 16: under 200 MB, linear in the number of
# spans). The element size stays 0.5 m (110 intervals per span), the
# pantograph runs from anchor to anchor, the evaluation window is spans 2 and
# 3 for every variant (the shipped window, spans 5 and 6, does not exist with
# 5 spans), and the step is 1e-4 s (the half-explicit limit 2/omega_max of
# the 40-span grid, 1.77e-4 s, is below the shipped 2e-4 s); the row
# "shipped" is the shipped case as it is.
# Prints one Markdown table row per run (peak RSS from /usr/bin/time -v).
# Usage, from the repository root:
#   scripts/memory-s55.sh [exe] [outdir] [spans ...]   (default spans: 5 10 20 40)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-build/pantocat-fem}
out=${2:-output/memory-s55}
shift $(($# > 2 ? 2 : $#))
spans=("$@")
[ ${#spans[@]} -gt 0 ] || spans=(5 10 20 40)
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (apt-get install time)" >&2; exit 2; }
mkdir -p "$out"

row() { # label, spans, extra --set arguments...
  local label=$1 n=$2
  shift 2
  local dir="$out/$label" sets=()
  for s in "$@"; do sets+=(--set "$s"); done
  /usr/bin/time -v "$exe" prm/catenary/section-s55.prm \
    --set "Output/Output directory=$dir" --set "Output/Plots=false" \
    "${sets[@]}" > "$dir.log" 2> "$dir.time" ||
    { echo "| $label | failed: $(tail -3 "$dir.time" | head -1) |"; return; }
  python3 - "$dir/summary.json" "$dir.time" "$label" "$n" <<'PY'
import json, re, sys
s = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", text).group(1))
wall = re.search(r"Elapsed \(wall clock\) time.*: (\S+)", text).group(1)
parts = [float(x) for x in wall.split(":")]
seconds = sum(p * 60 ** (len(parts) - 1 - i) for i, p in enumerate(parts))
print(f"| {sys.argv[3]} | {sys.argv[4]} | {s['number_of_intervals']} | {s['steps']} "
      f"| {rss / 1024:.1f} | {s['time_loop_seconds']:.1f} | {seconds:.1f} |")
PY
}

echo "| run | spans | N+1 | steps | peak RSS [MB] | time loop [s] | wall [s] |"
echo "|---|---|---|---|---|---|---|"
for n in "${spans[@]}"; do
  row "spans-$n" "$n" "Catenary/Number of spans=$n" \
    "Discretisation/Number of intervals=$((110 * n))" \
    "Pantograph/Final position=$((55 * n))" "Statistics/Window spans=2, 3" \
    "Time integration/Time step=1e-4"
done
row "shipped" 10
