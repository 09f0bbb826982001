#!/usr/bin/env bash
# The small variant of the FreeFEM study (examples/freefem): one solve on a
# coarse mesh of the channel, one adaptation on the CAD model, a second
# solve from the transferred solution. Checks that the files pass between
# the two programs (vertex counts on both sides, the solution read back by
# Metrica), that the adapted mesh lies on the model, and that cD is within
# 10% of the benchmark's 6.18533.
# Usage: tests/test_freefem_loop.sh METRICA
set -euo pipefail
metrica="$1"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
example="$here/../examples/freefem"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
fail() {
  echo "test_freefem_loop: $*" >&2
  exit 1
}

"$example/run" --iterations 1 --complexity 80 --size 0.15 --threads 2 --output-dir "$dir" --metrica "$metrica"

[ -f "$dir/history.csv" ] || fail "no history.csv"
[ "$(head -1 "$dir/history.csv")" = "iteration,vertices,tets,cd,cl,solver_seconds,metrica_seconds,model_distance,newton" ] ||
  fail "history.csv header: $(head -1 "$dir/history.csv")"
[ "$(wc -l <"$dir/history.csv")" -eq 3 ] || fail "history.csv should hold 2 rows"
for k in 00 01; do
  row=$(grep "^${k#0}," "$dir/history.csv") || fail "no row for iteration $k"
  IFS=, read -r _ nv nt cd _ _ _ distance _ <<<"$row"
  # FreeFEM's vertex and tet counts are the file's.
  info=$("$metrica" info "$dir/mesh-$k.meshb")
  file_nv=$(echo "$info" | sed -n 's/^  vertices *\([0-9,]*\)$/\1/p' | head -1 | tr -d ,)
  file_nt=$(echo "$info" | sed -n 's/^  tetrahedra *\([0-9,]*\)$/\1/p' | head -1 | tr -d ,)
  [ "$nv" = "$file_nv" ] && [ "$nt" = "$file_nt" ] || fail "mesh-$k: FreeFEM read $nv vertices, $nt tets; the file has $file_nv, $file_nt"
  # The solution FreeFEM wrote is read by Metrica: a multiscale metric of it.
  "$metrica" metric "$dir/mesh-$k.meshb" --field-file "$dir/solution-$k.sol" --fields 1,2 --complexity 500 \
    -o "$dir/check-$k.solb" -q || fail "metrica cannot use solution-$k.sol"
  python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) <= 1e-8 else 1)" "$distance" ||
    fail "mesh-$k: boundary $distance from the model"
done
"$metrica" check "$dir/mesh-01.meshb" --geometry "$example/channel.geo" -q || fail "mesh-01 is not valid on the model"
grep -q "newton" "$dir/solver-01.txt" || fail "no Newton iterations in the second solve's log"
python3 - "$row" <<'PY' || fail "cD of the adapted mesh beyond 10% of 6.18533: $row"
import sys
cd = float(sys.argv[1].split(",")[3])
sys.exit(0 if abs(cd - 6.18533) / 6.18533 < 0.10 else 1)
PY
echo "test_freefem_loop: passed ($row)"
