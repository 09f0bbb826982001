#!/usr/bin/env bash
# The small variant of the OpenFOAM study (examples/openfoam): the seed's
# laminar delta wing, one rhoSimpleFoam solve on the graded first mesh, two
# adaptations on the CAD model to the Mach number (complexity 2,500 then
# 5,000), each solve started from the mapped solution, OpenFOAM on 2
# processes (decomposePar, reconstructPar). Checks that options out of range
# stop the loop before any work, that the loop runs, that
# each mesh is valid and on the model (the loop's own metrica check
# --geometry, 1e-8), that OpenFOAM's points are the mesh's vertices
# (foam_case.py mach), and that the larger of the CD and CL errors against
# the seed's final values shrinks (the first mesh's CD is close by chance,
# docs/solver-loop.md); then that
# examples/openfoam/uniform solves a coarser mesh of the model (one process)
# and tabulates it.
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

# Options out of range stop the loop before any work.
for bad in "--norm 0.5" "--max-anisotropy 0.9" "--complexity -1"; do
  # shellcheck disable=SC2086
  if "$example/run" $bad --output-dir "$dir/bad" --metrica "$metrica" 2>"$dir/bad.err"; then fail "run $bad succeeded"; fi
  grep -q "examples/openfoam/run: --" "$dir/bad.err" && [ ! -e "$dir/bad" ] || fail "run $bad: $(cat "$dir/bad.err")"
done

"$example/run" --iterations 2 --complexity 2500 --steps 1 --solver-iterations 300 --threads 2 --solver-processes 2 \
  --output-dir "$dir" --metrica "$metrica"

[ "$(head -1 "$dir/history.csv")" = "iteration,vertices,tets,cd,cl,drift,solver_seconds,metrica_seconds" ] ||
  fail "history.csv header: $(head -1 "$dir/history.csv")"
[ "$(wc -l <"$dir/history.csv")" -eq 4 ] || fail "history.csv should hold 3 rows"
IFS=, read -r _ nv0 _ cd0 cl0 _ _ _ < <(sed -n 2p "$dir/history.csv")
IFS=, read -r _ nv1 _ cd1 cl1 _ _ _ < <(sed -n 4p "$dir/history.csv")
[ "$nv1" -gt "$nv0" ] || fail "the last adapted mesh has $nv1 vertices, the first $nv0"
awk -v a="$cd0" -v b="$cd1" -v c="$cl0" -v d="$cl1" 'BEGIN {
  cd = 0.165396; cl = 0.346937
  e0 = (a - cd) / cd; e1 = (b - cd) / cd; f0 = (c - cl) / cl; f1 = (d - cl) / cl
  e0 = e0 < 0 ? -e0 : e0; e1 = e1 < 0 ? -e1 : e1; f0 = f0 < 0 ? -f0 : f0; f1 = f1 < 0 ? -f1 : f1
  exit !((e1 > f1 ? e1 : f1) < (e0 > f0 ? e0 : f0))
}' || fail "CD $cd0 -> $cd1, CL $cl0 -> $cl1: the larger error against 0.165396 and 0.346937 did not shrink"
"$metrica" check "$dir/mesh-02.meshb" --geometry "$example/delta-wing.geo" -q || fail "mesh-02 is not valid on the model"

"$example/uniform" --factors 1.5 --solver-iterations 100 --solver-processes 1 --output-dir "$dir/uniform" \
  --metrica "$metrica"
[ "$(wc -l <"$dir/uniform/uniform.csv")" -eq 2 ] || fail "uniform.csv should hold 1 row"
IFS=, read -r f nvu _ cdu clu _ _ < <(sed -n 2p "$dir/uniform/uniform.csv")
[ "$f" = 1.5 ] && [ "$nvu" -lt "$nv0" ] || fail "uniform mesh at factor $f has $nvu vertices, the first mesh $nv0"
awk -v a="$cdu" -v b="$clu" 'BEGIN { exit !(a > 0.1 && a < 0.3 && b > 0.2 && b < 0.6) }' ||
  fail "uniform mesh: CD $cdu, CL $clu are not a delta wing's"
echo "test_openfoam_loop: CD $cd0 -> $cd1, CL $cl0 -> $cl1 (references 0.165396, 0.346937); uniform x1.5: $nvu vertices, CD $cdu, CL $clu"
