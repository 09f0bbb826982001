#!/bin/sh
# pip install of the package as a user makes it: a venv that sees Debian's
# numpy, `pip install --no-build-isolation` of the source tree with the
# wheel packed from the build directory given (python/build_backend), then
# metrica imported from the venv, elsewhere, and a small adaptation run.
#   pip_install.sh PYTHON SOURCE_DIR BUILD_DIR
set -eu
python=$1
source_dir=$2
build_dir=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$python" -m venv --system-site-packages "$tmp/venv"
"$tmp/venv/bin/pip" install -q --no-build-isolation --no-index --config-settings "build-dir=$build_dir" "$source_dir"
cd "$tmp"
"$tmp/venv/bin/python" - "$tmp/venv" <<'PY'
import sys
import metrica
assert metrica.__file__.startswith(sys.argv[1]), metrica.__file__
adapted, report = metrica.adapt(metrica.box(3), analytic="linear", concurrency="serial", cycles=2)
adapted.check()
print("pip install: metrica", metrica.__version__, "from", metrica.__file__, "adapts:", adapted)
PY
"$tmp/venv/bin/pip" uninstall -q -y metrica
