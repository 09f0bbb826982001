#!/usr/bin/env bash
# The small variant of the OpenFOAM study (examples/openfoam): the seed's
# laminar delta wing, one rhoSimpleFoam solve on the graded first mesh, one
# adaptation on the CAD model to the Mach number, a second solve started
# from the mapped solution. Checks that the loop runs, that each mesh is
# valid and on the model (the loop's own metrica check --geometry, 1e-8),
# that OpenFOAM's points are the mesh's vertices (foam_case.py mach), and
# that CD and CL move toward the seed's final values.
# Usage: tests/test_openfoam_loop.sh METRICA PYTHONPATH
set -euo pipefail
metrica="$1"
export PYTHONPATH="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
example="$here/../examples/openfoam"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
fail() {
  echo "test_openfoam_loop: $*" >&2
  exit 1
}

"$example/run" --iterations 1 --complexity 2500 --solver-iterations 200 --threads 2 --output-dir "$dir" \
  --metrica "$metrica"

[ "$(head -1 "$dir/history.csv")" = "iteration,vertices,tets,cd,cl,solver_seconds,metrica_seconds" ] ||
  fail "history.csv header: $(head -1 "$dir/history.csv")"
[ "$(wc -l <"$dir/history.csv")" -eq 3 ] || fail "history.csv should hold 2 rows"
IFS=, read -r _ nv0 _ cd0 cl0 _ _ < <(sed -n 2p "$dir/history.csv")
IFS=, read -r _ nv1 _ cd1 cl1 _ _ < <(sed -n 3p "$dir/history.csv")
[ "$nv1" -gt "$nv0" ] || fail "the adapted mesh has $nv1 vertices, the first $nv0"
awk -v a="$cd0" -v b="$cd1" -v c="$cl0" -v d="$cl1" 'BEGIN {
  cd = 0.165396; cl = 0.346937
  e0 = a - cd; e1 = b - cd; f0 = c - cl; f1 = d - cl
  exit !((e1 < 0 ? -e1 : e1) < (e0 < 0 ? -e0 : e0) && (f1 < 0 ? -f1 : f1) < (f0 < 0 ? -f0 : f0))
}' || fail "CD $cd0 -> $cd1, CL $cl0 -> $cl1: not toward 0.165396 and 0.346937"
"$metrica" check "$dir/mesh-01.meshb" --geometry "$example/delta-wing.geo" -q || fail "mesh-01 is not valid on the model"
echo "test_openfoam_loop: CD $cd0 -> $cd1, CL $cl0 -> $cl1 (references 0.165396, 0.346937)"
