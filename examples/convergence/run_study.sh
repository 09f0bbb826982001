#!/usr/bin/env bash
# The full verification study: the adaptive loop on sinfun3,
# tanh3 and sinatan3 from complexity 1000, doubling every 10 iterations up
# to 128000 (80 iterations), then the convergence table and plot.
# Usage: examples/convergence/run_study.sh [OUTPUT_DIR=study] [extra metrica loop options]
# Takes hours on 2 cores (the 128k iterations dominate); not part of CI.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="${1:-study}"
shift || true
"$root/scripts/build"
if ! python3 -c "import matplotlib" 2>/dev/null && [ "$(id -u)" -eq 0 ]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-matplotlib >/dev/null
fi
mkdir -p "$out"
for field in sinfun3 tanh3 sinatan3; do
  "$root/build/cli/metrica" loop --field "$field" --complexity 1000 --double-every 10 \
    --iterations 80 --csv "$out/$field.csv" "$@"
done
python3 "$root/examples/convergence/plot_convergence.py" "$out"/sinfun3.csv "$out"/tanh3.csv "$out"/sinatan3.csv \
  -o "$out/convergence.png" | tee "$out/report.md"
