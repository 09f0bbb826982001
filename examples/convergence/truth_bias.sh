#!/usr/bin/env bash
# How the error measure bends a convergence slope. refine's
# published errors (UGAWG error-est-results) are measured against the
# loop's last mesh (the "truth", complexity 512k) instead of the exact
# field, which lowers the error the closer a mesh is to the truth. This
# runs the loop from complexity 1000 doubling every 5 iterations to 32000,
# then measures the last mesh of each complexity both ways: against the
# exact field and against the 32k mesh (metrica error --truth), and prints
# the ratio.
# Usage: examples/convergence/truth_bias.sh [OUTPUT_DIR=truth-bias] [FIELD...]
# (default fields sinfun3 sinatan3; about 2 minutes on 2 cores)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="${1:-truth-bias}"
shift || true
fields=("$@")
[ ${#fields[@]} -gt 0 ] || fields=(sinfun3 sinatan3)
"$root/scripts/build"
metrica="$root/build/cli/metrica"
mkdir -p "$out"
error_of() { "$metrica" error "$@" | grep -o -E 'L2 error [0-9.e+-]+' | awk '{print $3}'; }
echo "| field | complexity | vertices | error vs exact | error vs the 32k mesh | ratio |"
echo "|---|---|---|---|---|---|"
for field in "${fields[@]}"; do
  "$metrica" loop --field "$field" --complexity 1000 --double-every 5 --iterations 30 \
    --output-dir "$out/$field" --csv "$out/$field.csv" -q
  truth="$out/$field/loop-30.meshb"
  for i in 05 10 15 20 25; do
    mesh="$out/$field/loop-$i.meshb"
    exact=$(error_of "$mesh" --analytic "$field")
    against=$(error_of "$mesh" --analytic "$field" --truth "$truth")
    # This iteration's complexity and vertex count, from the loop's own CSV.
    awk -F, -v it=$((10#$i)) -v f="$field" -v e="$exact" -v t="$against" \
      '$1 == it { printf "| %s | %d | %d | %.3e | %.3e | %.2f |\n", f, $2, $3, e, t, t / e }' "$out/$field.csv"
  done
done
