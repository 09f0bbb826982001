#!/usr/bin/env bash
# Adaptation on CAD models: the figures of docs/geometry.md.
#
#   examples/cad/run_cad_cases.sh [OUTDIR] [THREADS...]
#
# For each of 1 and 2 threads (or those given):
#   - UGAWG cube-cylinder, 5 iterations of the UGAWG loop (the analytic
#     metric re-evaluated on each new mesh) for linear, polar-1, polar-2,
#     from the UGAWG mesh with its association (keywords 40-42) and the
#     STEP model;
#   - the same polar-2 run from `metrica bootstrap cube-cylinder.step`;
#   - cone-cone (STEP and IGES) bootstrapped, then adapted to a uniform
#     metric (h = 0.05).
# One line per run: edges in range, worst mean ratio, the relative volume
# error against 1 - pi/16 (cube-cylinder), the largest distance of a
# boundary vertex to its entity, the time.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
metrica="${METRICA:-$root/build/cli/metrica}"
data="$root/tests/data/ugawg"
out="${1:-cad-cases}"
shift || true
threads=("$@")
[ ${#threads[@]} -eq 0 ] && threads=(1 2)
mkdir -p "$out"
exact=$(python3 -c 'import math; print(1 - math.pi / 16)')

summary() {  # log file, case name
  local log=$1 name=$2
  local range minq vol dist secs
  range=$(grep 'edges in \[' "$log" | awk '{print $NF}')
  minq=$(grep 'mean ratio   min' "$log" | awk '{print $4}')
  vol=$(grep -o 'volume [0-9.]*$' "$log" | tail -1 | awk '{print $2}')
  dist=$(grep -o 'largest distance to their entity [0-9.e+-]*' "$log" | tail -1 | awk '{print $NF}')
  secs=$(grep -o '([0-9.]* s in all)' "$log" | tr -d '(' | awk '{print $1}')
  local err="-"
  case $name in cube-cylinder*) err=$(python3 -c "print(f'{abs($vol - $exact) / $exact:.2e}')") ;; esac
  printf '%-34s range %7s  min Q %s  volume error %-9s  max distance %-9s  %6s s\n' "$name" "$range" "$minq" "$err" "$dist" "$secs"
}

for t in "${threads[@]}"; do
  for c in linear polar-1 polar-2; do
    "$metrica" adapt "$data/cube-cylinder.meshb" --geometry "$data/cube-cylinder.step" --analytic $c \
      --iterations 5 --threads "$t" -o "$out/cc-$c-t$t.meshb" > "$out/cc-$c-t$t.log"
    summary "$out/cc-$c-t$t.log" "cube-cylinder $c, $t thread(s)"
  done
  "$metrica" bootstrap "$data/cube-cylinder.step" -o "$out/cc-start.meshb" --size 0.2 -q
  "$metrica" adapt "$out/cc-start.meshb" --geometry "$data/cube-cylinder.step" --analytic polar-2 --iterations 5 \
    --threads "$t" -o "$out/cc-boot-polar-2-t$t.meshb" > "$out/cc-boot-t$t.log"
  summary "$out/cc-boot-t$t.log" "cube-cylinder bootstrap polar-2, $t"
  for model in cone-cone.step cone-cone.iges; do
    "$metrica" bootstrap "$data/$model" -o "$out/$model-start.meshb" -q
    "$metrica" metric "$out/$model-start.meshb" --analytic linear --hmin 0.05 --hmax 0.05 -o "$out/$model-h.solb" -q
    "$metrica" adapt "$out/$model-start.meshb" --geometry "$data/$model" -m "$out/$model-h.solb" --threads "$t" \
      -o "$out/$model-t$t.meshb" > "$out/$model-t$t.log"
    "$metrica" check "$out/$model-t$t.meshb" --geometry "$data/$model" -q
    summary "$out/$model-t$t.log" "$model uniform h 0.05, $t"
  done
done
