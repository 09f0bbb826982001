#!/usr/bin/env bash
# `metrica adapt` under mpirun (docs/distributed.md) on small cases, each
# run under a timeout so that a hang fails instead of blocking: valid and
# conforming output (metrica check), balanced parts, the same output to the
# bit for a given N with --concurrency serial, the parallel read and write
# round trip (--rounds 0), an error on one rank (every rank exits 1, one
# message, no output left behind), more ranks than the mesh has work for,
# the boundary on a CAD model, two regions with the surface between them,
# the last round undone on a part that it would leave poorer, rounds
# without a new cut,
# ASCII outputs, --metric-out, --keep-surface, --dry-run and --vtu.
# Usage: tests/test_mpi.sh METRICA [CASE]   (CASE: adapt, repeat, roundtrip, errors, geometry, regions, options; all by default)
set -euo pipefail
metrica="$1"
only="${2:-all}"
data="$(cd "$(dirname "$0")" && pwd)/data/ugawg"
msh="$(cd "$(dirname "$0")" && pwd)/data/msh"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
fail() {
  echo "test_mpi: $*" >&2
  exit 1
}
# Root in CI; two cores for up to three ranks; one node, so shared memory
# without the probe of UCX's devices (docs/distributed.md).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_pml="${OMPI_MCA_pml:-ob1}"
run() {
  local n=$1
  shift
  timeout 300 mpirun --oversubscribe -np "$n" "$metrica" "$@"
}
"$metrica" cube --n 8 -o "$dir/cube.meshb" -q

# Valid, conforming, in the unit band, balanced: on 2 and 3 ranks.
if [ "$only" = all ] || [ "$only" = adapt ]; then
  for n in 2 3; do
    out="$dir/adapt-$n.txt"
    run "$n" adapt "$dir/cube.meshb" --analytic linear -o "$dir/a$n.meshb" --concurrency serial >"$out" 2>&1 ||
      { cat "$out"; fail "adapt on $n ranks failed"; }
    "$metrica" check "$dir/a$n.meshb" -q || fail "the output of $n ranks is not valid"
    # Every face of the output between two tets or listed as a triangle:
    # metrica check refuses an open (non-conforming) boundary.
    report=$("$metrica" quality "$dir/a$n.meshb" --analytic linear)
    share=$(sed -n 's/.*edges in \[1\/sqrt2, sqrt2\] *\([0-9.]*\)%.*/\1/p' <<<"$report")
    minq=$(sed -n 's/.*mean ratio *min \([0-9.]*\).*/\1/p' <<<"$report")
    awk -v s="$share" -v q="$minq" 'BEGIN { exit !(s >= 95 && q >= 0.2) }' ||
      { cat "$out"; fail "$n ranks: $share% of the edges in range, min Q $minq (want >= 95%, >= 0.2)"; }
    balance=$(sed -n 's/.*the most \([0-9.]*\) x the mean.*/\1/p' "$out")
    awk -v b="$balance" 'BEGIN { exit !(b <= 1.10) }' || { cat "$out"; fail "$n ranks: the largest part is $balance x the mean"; }
    volume=$("$metrica" info "$dir/a$n.meshb" | sed -n 's/^  volume *\([0-9.e+-]*\).*/\1/p')
    awk -v v="$volume" 'BEGIN { exit !(v > 0.999999999 && v < 1.000000001) }' || fail "$n ranks: volume $volume (the cube's is 1)"
  done
fi

# A metric file, and ranks left without tets by a first round on one part:
# every rank still takes part in every exchange.
if [ "$only" = all ] || [ "$only" = adapt ]; then
  "$metrica" metric "$dir/cube.meshb" --analytic linear -o "$dir/m.solb" -q
  run 3 adapt "$dir/cube.meshb" -m "$dir/m.solb" --threads 1 -o "$dir/m3.meshb" --metric-out "$dir/m3.solb" \
    >"$dir/m3.txt" 2>&1 ||
    { cat "$dir/m3.txt"; fail "a metric file on 3 ranks failed"; }
  grep -q "round 1: .* (1 part," "$dir/m3.txt" || { cat "$dir/m3.txt"; fail "a metric file on 3 ranks: not one part first"; }
  "$metrica" check "$dir/m3.meshb" -q || fail "a metric file on 3 ranks: invalid output"
  # The metric written is the field given (the input's metric on the input
  # mesh) at the output's vertices: both measure the output alike.
  own=$("$metrica" quality "$dir/m3.meshb" -m "$dir/m3.solb" | grep 'edges in \[')
  report=$("$metrica" quality "$dir/m3.meshb" -m "$dir/m.solb" --metric-mesh "$dir/cube.meshb")
  given=$(grep 'edges in \[' <<<"$report")
  [ "$own" = "$given" ] || fail "a metric file on 3 ranks: the metric written is not the field given ($own / $given)"
  # As the single process: the rounds' split floor (0.01) neither keeps the
  # coarse cube off the field's layer at z = 0.5 nor leaves tets at it.
  share=$(sed -n 's/.*edges in \[1\/sqrt2, sqrt2\] *\([0-9.]*\)%.*/\1/p' <<<"$report")
  minq=$(sed -n 's/.*mean ratio *min \([0-9.]*\).*/\1/p' <<<"$report")
  awk -v s="$share" -v q="$minq" 'BEGIN { exit !(s >= 95 && q >= 0.2) }' ||
    { cat "$dir/m3.txt"; fail "a metric file on 3 ranks: $share% of the edges in range, min Q $minq (want >= 95%, >= 0.2)"; }
fi

# The last round a run allows is undone on a part where it would leave a
# tet poorer than it was given: polar-1 on 3 ranks, 2 rounds, whose
# second round does so on one part (serial: the same on every run); the
# part keeps its tets and the output stays valid and conforming.
if [ "$only" = all ] || [ "$only" = adapt ]; then
  run 3 adapt "$dir/cube.meshb" --analytic polar-1 --iterations 2 --rounds 2 --concurrency serial \
    -o "$dir/u3.meshb" >"$dir/u3.txt" 2>&1 || { cat "$dir/u3.txt"; fail "polar-1 on 3 ranks, 2 rounds, failed"; }
  grep -q "iteration 2 round 2: .* parts, [0-9]* undone," "$dir/u3.txt" ||
    { cat "$dir/u3.txt"; fail "polar-1 on 3 ranks, 2 rounds: no part undone (the case no longer reaches the undo)"; }
  "$metrica" check "$dir/u3.meshb" -q || fail "polar-1 on 3 ranks with a part undone: invalid output"
  minq=$("$metrica" quality "$dir/u3.meshb" --analytic polar-1 | sed -n 's/.*mean ratio *min \([0-9.]*\).*/\1/p')
  awk -v q="$minq" 'BEGIN { exit !(q >= 0.2) }' || { cat "$dir/u3.txt"; fail "polar-1 on 3 ranks with a part undone: min Q $minq"; }
fi

# A first round on a mesh already at its size whose cut crosses polar-1's
# layer (the 20^3 cube: grid vertices on r = 0.5 lie on the faces kept
# between the parts): the splits beside the kept faces' long edges stop at
# the split's floor, and the next rounds adapt there again. Without the
# floor they made hubs of needles (Q 1e-11) no round undid: min Q 0.0000.
if [ "$only" = all ] || [ "$only" = adapt ]; then
  "$metrica" cube --n 20 -o "$dir/c20.meshb" -q
  run 2 adapt "$dir/c20.meshb" --analytic polar-1 --concurrency serial -o "$dir/p20.meshb" >"$dir/p20.txt" 2>&1 ||
    { cat "$dir/p20.txt"; fail "polar-1 from the 20^3 cube on 2 ranks failed"; }
  "$metrica" check "$dir/p20.meshb" -q || fail "polar-1 from the 20^3 cube on 2 ranks: invalid output"
  minq=$("$metrica" quality "$dir/p20.meshb" --analytic polar-1 | sed -n 's/.*mean ratio *min \([0-9.]*\).*/\1/p')
  awk -v q="$minq" 'BEGIN { exit !(q >= 0.2) }' ||
    { cat "$dir/p20.txt"; fail "polar-1 from the 20^3 cube on 2 ranks: min Q $minq (want >= 0.2)"; }
fi

# Past 50k tets per rank the cut works on clusters of tets, smoothed:
# from the 2 ranks' output above (about 50k tets: cut in 2 from the first
# round) to some 400k tets, valid, in range, balanced.
if [ "$only" = all ] || [ "$only" = adapt ]; then
  "$metrica" metric "$dir/a2.meshb" --analytic linear --complexity 40000 -o "$dir/big.solb" -q
  run 2 adapt "$dir/a2.meshb" -m "$dir/big.solb" --threads 1 -o "$dir/big.meshb" >"$dir/big.txt" 2>&1 ||
    { cat "$dir/big.txt"; fail "400k tets on 2 ranks failed"; }
  "$metrica" check "$dir/big.meshb" -q || fail "400k tets on 2 ranks: invalid output"
  tets=$(sed -n 's/^wrote .* \([0-9]*\) tets (libMeshb.*/\1/p' "$dir/big.txt")
  share=$(sed -n 's/.*edges in \[1\/sqrt2, sqrt2\] *\([0-9.]*\)%.*/\1/p' "$dir/big.txt")
  balance=$(sed -n 's/.*the most \([0-9.]*\) x the mean.*/\1/p' "$dir/big.txt")
  grep -q "round 2: .* (2 parts," "$dir/big.txt" || { cat "$dir/big.txt"; fail "400k tets on 2 ranks: no second round on 2 parts"; }
  awk -v t="$tets" -v s="$share" -v b="$balance" 'BEGIN { exit !(t > 200000 && s >= 95 && b <= 1.10) }' ||
    { cat "$dir/big.txt"; fail "400k tets on 2 ranks: $tets tets, $share% in range, balance $balance"; }
fi

# The same output to the bit for a given N (serial concurrency): a second
# run, written as ASCII by all ranks, is the text the single process
# writes for the first run's mesh and metric (each value's shortest
# exact digits: the same doubles, and both writers agree).
if [ "$only" = all ] || [ "$only" = repeat ]; then
  run 2 adapt "$dir/cube.meshb" --analytic polar-1 -o "$dir/r1.meshb" --metric-out "$dir/r1.solb" --concurrency serial -q
  run 2 adapt "$dir/cube.meshb" --analytic polar-1 -o "$dir/r3.mesh" --metric-out "$dir/r3.sol" --concurrency serial -q
  "$metrica" convert "$dir/r1.meshb" "$dir/r1.mesh" -q
  "$metrica" convert "$dir/r1.solb" "$dir/r1.sol" -q
  cmp "$dir/r1.mesh" "$dir/r3.mesh" || fail "two serial runs on 2 ranks differ, or the .mesh of 2 ranks is not the .meshb's text"
  cmp "$dir/r1.sol" "$dir/r3.sol" || fail "two serial runs on 2 ranks differ, or the .sol of 2 ranks is not the .solb's text"
fi

# Read in slices, cut, move and write in parallel: the same mesh back.
if [ "$only" = all ] || [ "$only" = roundtrip ]; then
  run 3 adapt "$dir/cube.meshb" --analytic linear --rounds 0 -o "$dir/rt.meshb" -q
  "$metrica" check "$dir/rt.meshb" -q || fail "the round trip is not valid"
  strip() { "$metrica" info "$1" | grep -E '^  (vertices|tetrahedra|triangles|volume) |^ +[0-9]+ +[0-9,]+ +[0-9.]+$'; }
  diff <(strip "$dir/cube.meshb") <(strip "$dir/rt.meshb") || fail "the round trip changed the mesh's counts, volume or surfaces"
  # The ASCII path: rank 0 reads and sends the slices out.
  "$metrica" convert "$dir/cube.meshb" "$dir/cube.mesh" -q
  run 2 adapt "$dir/cube.mesh" --analytic linear --rounds 0 -o "$dir/rt2.meshb" -q
  diff <(strip "$dir/cube.meshb") <(strip "$dir/rt2.meshb") || fail "the ASCII round trip changed the mesh"
fi

# Errors: a bad slice on the last rank only, an output that cannot be
# written. Every rank exits 1 (no hang: the timeout), one message.
if [ "$only" = all ] || [ "$only" = errors ]; then
  python3 - "$dir/cube.meshb" "$dir/bad.meshb" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
# The last tet's first vertex out of range (version 2: 32-bit ints, offsets).
pos = 8
while True:
    code, nxt = struct.unpack_from("<ii", data, pos)
    if code == 8:
        count = struct.unpack_from("<i", data, pos + 8)[0]
        last = pos + 12 + (count - 1) * 20
        struct.pack_into("<i", data, last, 999999)
        break
    pos = nxt
open(sys.argv[2], "wb").write(data)
PY
  set +e
  msg=$(run 3 adapt "$dir/bad.meshb" --analytic linear -o "$dir/bad-out.meshb" 2>&1)
  code=$?
  set -e
  [ "$code" -ne 0 ] && [ "$code" -ne 124 ] || fail "a bad slice: exit $code (want 1, no hang): $msg"
  grep -q "rank 2 of 3: .*names vertex 999999" <<<"$msg" || fail "a bad slice: no message from rank 2: $msg"
  [ "$(grep -c '^error' <<<"$msg")" -eq 1 ] || fail "a bad slice: not one message: $msg"
  [ ! -e "$dir/bad-out.meshb" ] || fail "a bad slice left an output"
  # More ranks than the mesh has work for: the first rounds run on fewer.
  "$metrica" cube --n 1 -o "$dir/tiny.meshb" -q
  run 3 adapt "$dir/tiny.meshb" --analytic linear -o "$dir/tiny-out.meshb" >"$dir/tiny.txt" 2>&1 ||
    { cat "$dir/tiny.txt"; fail "6 tets on 3 ranks failed"; }
  grep -q "round 1: .* (1 part," "$dir/tiny.txt" || { cat "$dir/tiny.txt"; fail "6 tets on 3 ranks: not one part first"; }
  "$metrica" check "$dir/tiny-out.meshb" -q || fail "6 tets on 3 ranks: invalid output"
  set +e
  msg=$(run 2 adapt "$dir/cube.meshb" --analytic linear -o "$dir/cube.su2" 2>&1)
  code=$?
  set -e
  [ "$code" -eq 2 ] || fail "an .su2 output under mpirun: exit $code (want 2): $msg"
  ls "$dir" | grep -q tmp && fail "a temporary file was left: $(ls "$dir")"
fi
# On the CAD model (cube-cylinder, UGAWG's STEP file): every boundary
# vertex on its entity within 1e-8 (check --geometry), with a second
# iteration on 2 parts; the output carries the association for the next
# run; a model that does not match the mesh is refused.
if [ "$only" = all ] || [ "$only" = geometry ]; then
  run 2 adapt "$data/cube-cylinder.meshb" --geometry "$data/cube-cylinder.step" --analytic polar-2 --iterations 2 \
    --threads 1 -o "$dir/cc.meshb" >"$dir/cc.txt" 2>&1 || { cat "$dir/cc.txt"; fail "cube-cylinder on 2 ranks failed"; }
  grep -q "iteration 2 round 1: .* (2 parts," "$dir/cc.txt" || { cat "$dir/cc.txt"; fail "cube-cylinder: no round on 2 parts"; }
  # The input's VerticesOnGeometric* records read in slices: the single
  # process takes 158 of UGAWG's (u, v) as they are.
  grep -q "211 boundary vertices associated .* (158 with the input's parameters)" "$dir/cc.txt" ||
    { cat "$dir/cc.txt"; fail "cube-cylinder: the input's association records were not read as the single process reads them"; }
  report=$("$metrica" check "$dir/cc.meshb" --geometry "$data/cube-cylinder.step" -v 2>&1) ||
    { echo "$report"; fail "cube-cylinder on 2 ranks: invalid or off the model"; }
  from_file=$(sed -n 's/.*associated (\([0-9,]*\) with the input.s parameters).*/\1/p' <<<"$report" | tr -d ,)
  [ "${from_file:-0}" -gt 1000 ] || { echo "$report"; fail "cube-cylinder on 2 ranks: the output carries no association"; }
  minq=$("$metrica" quality "$dir/cc.meshb" --analytic polar-2 | sed -n 's/.*mean ratio *min \([0-9.]*\).*/\1/p')
  awk -v q="$minq" 'BEGIN { exit !(q >= 0.3) }' || fail "cube-cylinder on 2 ranks: min Q $minq (want >= 0.3)"
  # Five iterations of polar-1: some later rounds find what the round
  # before left unfinished inside the parts and run without a new cut.
  run 2 adapt "$data/cube-cylinder.meshb" --geometry "$data/cube-cylinder.step" --analytic polar-1 --iterations 5 \
    --concurrency serial -o "$dir/cc5.meshb" >"$dir/cc5.txt" 2>&1 || { cat "$dir/cc5.txt"; fail "cube-cylinder, polar-1, 5 iterations on 2 ranks failed"; }
  grep -q "round [0-9]*: .* no cut, adapt" "$dir/cc5.txt" ||
    { cat "$dir/cc5.txt"; fail "cube-cylinder, polar-1, 5 iterations on 2 ranks: no round without a cut"; }
  "$metrica" check "$dir/cc5.meshb" --geometry "$data/cube-cylinder.step" -q ||
    fail "cube-cylinder, polar-1, 5 iterations on 2 ranks: invalid or off the model"
  minq=$("$metrica" quality "$dir/cc5.meshb" --analytic polar-1 | sed -n 's/.*mean ratio *min \([0-9.]*\).*/\1/p')
  awk -v q="$minq" 'BEGIN { exit !(q >= 0.3) }' || fail "cube-cylinder, polar-1, 5 iterations on 2 ranks: min Q $minq (want >= 0.3)"
  set +e
  msg=$(run 2 adapt "$data/cube-cylinder.meshb" --geometry "$data/cone-cone.step" --analytic polar-2 -o "$dir/cc-bad.meshb" 2>&1)
  code=$?
  set -e
  [ "$code" -eq 1 ] || fail "a model that does not match: exit $code (want 1): $msg"
  grep -q "the model does not match the mesh" <<<"$msg" || fail "a model that does not match: $msg"
  [ ! -e "$dir/cc-bad.meshb" ] || fail "a model that does not match left an output"
fi
# Two regions (a ball in a box, gmsh's .msh 4.1 with physical groups):
# the faces between parts cross the internal surface, which stays
# internal with its id, and each region keeps its volume (no model: the
# interface's vertices stay on the input's facets); on the model
# (box_sphere.geo, its own bootstrap) every boundary and interface vertex
# on it.
if [ "$only" = all ] || [ "$only" = regions ]; then
  regions() { "$metrica" info "$1" | sed -n '/^Regions/,$p' | awk '$1 ~ /^[0-9]+$/ { print $1, $3 }'; }
  run 2 adapt "$msh/box_sphere_41.msh" --analytic linear --hmin 0.06 --hmax 0.06 --iterations 2 --threads 1 \
    -o "$dir/bs.meshb" >"$dir/bs.txt" 2>&1 || { cat "$dir/bs.txt"; fail "two regions on 2 ranks failed"; }
  grep -q "iteration 2 round 1: .* (2 parts," "$dir/bs.txt" || { cat "$dir/bs.txt"; fail "two regions: no round on 2 parts"; }
  "$metrica" check "$dir/bs.meshb" -q || fail "two regions on 2 ranks: invalid output"
  "$metrica" info "$dir/bs.meshb" | grep -Eq '^ +100 +[0-9,]+ +[0-9.]+ +internal' ||
    fail "two regions on 2 ranks: surface 100 is no longer internal: $("$metrica" info "$dir/bs.meshb")"
  paste <(regions "$msh/box_sphere_41.msh") <(regions "$dir/bs.meshb") |
    awk '{ if ($1 != $3 || ($2 - $4) > 1e-6 || ($4 - $2) > 1e-6) bad = 1 } END { exit bad || NR != 2 }' ||
    fail "two regions on 2 ranks: the regions' volumes moved: $(regions "$msh/box_sphere_41.msh") against $(regions "$dir/bs.meshb")"
  "$metrica" bootstrap "$msh/box_sphere.geo" --size 0.15 --threads 1 -o "$dir/bsb.meshb" -q
  run 2 adapt "$dir/bsb.meshb" --geometry "$msh/box_sphere.geo" --analytic linear --hmin 0.06 --hmax 0.06 \
    --iterations 2 --threads 1 -o "$dir/bsg.meshb" >"$dir/bsg.txt" 2>&1 || { cat "$dir/bsg.txt"; fail "two regions on the model failed"; }
  "$metrica" check "$dir/bsg.meshb" --geometry "$msh/box_sphere.geo" -q || fail "two regions on the model: invalid or off the model"
fi
# The options the single process has: --metric-out (one .solb written by
# all ranks, the analytic metric at the output's vertices to the bit),
# --keep-surface (re-adapting on 2 parts leaves every boundary triangle
# where it was), --dry-run (no output), --vtu (the output's vertices and
# tets), --max-tets, and an ASCII --metric-out refused.
if [ "$only" = all ] || [ "$only" = options ]; then
  run 2 adapt "$dir/cube.meshb" --analytic linear --concurrency serial -o "$dir/o.meshb" --metric-out "$dir/o.solb" \
    >"$dir/o.txt" 2>&1 || { cat "$dir/o.txt"; fail "--metric-out on 2 ranks failed"; }
  "$metrica" metric "$dir/o.meshb" --analytic linear -o "$dir/o-ref.solb" -q
  cmp -s "$dir/o.solb" "$dir/o-ref.solb" || fail "--metric-out on 2 ranks: not the metric at the output's vertices"
  run 2 adapt "$dir/o.meshb" --analytic linear --keep-surface --threads 1 -o "$dir/k.meshb" >"$dir/k.txt" 2>&1 ||
    { cat "$dir/k.txt"; fail "--keep-surface on 2 ranks failed"; }
  grep -q "round 1: .* (2 parts," "$dir/k.txt" || { cat "$dir/k.txt"; fail "--keep-surface: no round on 2 parts"; }
  "$metrica" check "$dir/k.meshb" -q || fail "--keep-surface on 2 ranks: invalid output"
  # Each triangle as its three corners' coordinates (sorted) and its id.
  surface() {
    "$metrica" convert "$1" "$dir/s.mesh" -q
    awk '/^Vertices/ { getline n; for (i = 1; i <= n; i++) { getline; v[i] = $1 " " $2 " " $3 } }
      /^Triangles/ { getline n; for (i = 1; i <= n; i++) { getline; a = v[$1]; b = v[$2]; c = v[$3]
        if (a > b) { t = a; a = b; b = t } if (b > c) { t = b; b = c; c = t } if (a > b) { t = a; a = b; b = t }
        print a "|" b "|" c "|" $4 } }' "$dir/s.mesh" | sort
  }
  [ "$(surface "$dir/o.meshb")" = "$(surface "$dir/k.meshb")" ] || fail "--keep-surface on 2 ranks: the surface changed"
  msg=$(run 2 adapt "$dir/cube.meshb" --analytic linear -o "$dir/d.meshb" --dry-run 2>&1) || fail "--dry-run: $msg"
  grep -q "tets out on 2 ranks" <<<"$msg" || fail "--dry-run on 2 ranks: $msg"
  [ ! -e "$dir/d.meshb" ] || fail "--dry-run on 2 ranks wrote an output"
  # --vtu: the appended raw arrays hold the output's vertices, tets and
  # triangles.
  run 2 adapt "$dir/cube.meshb" --analytic linear --concurrency serial -o "$dir/v.meshb" --vtu "$dir/v.vtu" \
    >"$dir/v.txt" 2>&1 || { cat "$dir/v.txt"; fail "--vtu on 2 ranks failed"; }
  "$metrica" convert "$dir/v.meshb" "$dir/v.mesh" -q
  python3 - "$dir/v.vtu" "$dir/v.mesh" <<'PY' || fail "--vtu on 2 ranks: not the output's tets and triangles"
import re, struct, sys
raw = open(sys.argv[1], "rb").read()
head, data = raw.split(b'<AppendedData encoding="raw">', 1)
data = data[data.index(b"_") + 1:]
arrays = {m.group(1): int(m.group(2)) for m in re.finditer(rb'Name="(\w+)"[^>]*offset="(\d+)"', head)}
def block(name, fmt):
    at = arrays[name.encode()]
    n = struct.unpack_from("<Q", data, at)[0]
    return list(struct.unpack_from("<%d%s" % (n // struct.calcsize(fmt), fmt), data, at + 8))
xyz, conn, offs, types, refs = (block("Points", "d"), block("connectivity", "q"), block("offsets", "q"),
                                block("types", "B"), block("ref", "i"))
text = open(sys.argv[2]).read().split("\n")
def section(name):
    i = text.index(name)
    n = int(text[i + 1])
    return [line.split() for line in text[i + 2:i + 2 + n]]
verts = [[float(x) for x in r[:3]] for r in section("Vertices")]
tets = [[int(x) for x in r] for r in section("Tetrahedra")]
tris = [[int(x) for x in r] for r in section("Triangles")]
nt = len(tets)
assert xyz == [c for v in verts for c in v], "points"
assert conn == [v - 1 for t in tets for v in t[:4]] + [v - 1 for f in tris for v in f[:3]], "connectivity"
assert offs == [4 * (k + 1) for k in range(nt)] + [4 * nt + 3 * (k + 1) for k in range(len(tris))], "offsets"
assert types == [10] * nt + [5] * len(tris), "types"
assert refs == [t[4] for t in tets] + [f[3] for f in tris], "refs"
assert raw.endswith(b"</AppendedData>\n</VTKFile>\n"), "the end"
PY
  # One layout: the single process writes the same file from the same mesh.
  "$metrica" convert "$dir/v.meshb" "$dir/v1.vtu" -q
  cmp -s "$dir/v.vtu" "$dir/v1.vtu" || fail "--vtu on 2 ranks: not the bytes the single process writes"
  # A run predicted past --max-tets: refused before any work, exit 1.
  set +e
  msg=$(run 2 adapt "$dir/cube.meshb" --analytic linear -o "$dir/big.meshb" --max-tets 1000 2>&1)
  code=$?
  set -e
  [ "$code" -eq 1 ] && grep -q "the limit is 1e+03 tets" <<<"$msg" || fail "--max-tets 1000 on 2 ranks: exit $code: $msg"
  [ ! -e "$dir/big.meshb" ] || fail "--max-tets on 2 ranks left an output"
  for bad in "--metric-out $dir/m.meshb"; do
    set +e
    # shellcheck disable=SC2086 # the option and its value
    msg=$(run 2 adapt "$dir/cube.meshb" --analytic linear -o "$dir/r.meshb" $bad 2>&1)
    code=$?
    set -e
    [ "$code" -eq 2 ] || fail "$bad on 2 ranks: exit $code (want 2, a usage error): $msg"
    [ ! -e "$dir/r.meshb" ] || fail "$bad on 2 ranks left an output"
  done
fi
echo "test_mpi: ok"
