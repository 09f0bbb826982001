# Sourced by examples/openfoam/run and examples/openfoam/uniform after their
# options are read: finds the metrica program ($metrica, else
# build/cli/metrica, else PATH), checks OpenFOAM's tools, exports what
# examples/openfoam/solve needs (METRICA, WM_PROJECT_DIR, the module's
# PYTHONPATH) and defines count MESH WHAT (vertices, tetrahedra, ... of a
# mesh, from metrica info). Expects $root, $metrica and a die function.
if [ -z "$metrica" ]; then
  if [ -x "$root/build/cli/metrica" ]; then metrica="$root/build/cli/metrica"; else metrica="$(command -v metrica || true)"; fi
fi
[ -x "$metrica" ] || die "no metrica program (build it with scripts/build, or give --metrica)"
for tool in gmshToFoam rhoSimpleFoam mapFields foamToVTK decomposePar reconstructPar mpirun; do
  command -v "$tool" >/dev/null || die "$tool not found: scripts/setup installs Debian's openfoam"
done
export METRICA="$metrica" WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
export PYTHONPATH="$root/build/python${PYTHONPATH:+:$PYTHONPATH}"

count() { "$metrica" info "$1" | sed -n "s/^  $2 *\([0-9,]*\).*/\1/p" | head -1 | tr -d ,; }
