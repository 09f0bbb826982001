"""The build backend of `pip install .` (PEP 517): the wheel is built by the
project's own CMake build and packed here, with nothing to download, so
that it works offline and with --no-build-isolation:

    python3 -m venv --system-site-packages venv
    venv/bin/pip install --no-build-isolation .
    venv/bin/pip install --no-build-isolation --config-settings build-dir=build .   (reuse a build)

The module is built for the interpreter pip runs (a venv's base
interpreter, same version and headers); numpy and Debian's -dev packages
(scripts/setup) must be there. config settings: build-dir (default
build-python/ in the source tree), jobs (default: the cores).
"""
import base64
import csv
import hashlib
import io
import os
import re
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
NAME = "metrica"


def _version():
    text = (ROOT / "CMakeLists.txt").read_text()
    found = re.search(r"project\(Metrica VERSION ([0-9.]+)", text)
    if not found:
        raise RuntimeError("metrica_build: no project(Metrica VERSION ...) in CMakeLists.txt")
    return found.group(1)


def _dist_info():
    return f"{NAME}-{_version()}.dist-info"


def _metadata():
    return (
        "Metadata-Version: 2.1\n"
        f"Name: {NAME}\n"
        f"Version: {_version()}\n"
        "Summary: Metric-based anisotropic adaptation of tetrahedral meshes (C++ with a Python module)\n"
        "License: see the source tree\n"
        "Requires-Python: >=3.9\n"
        "Requires-Dist: numpy\n"
    )


def _tag():
    impl = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{impl}-{impl}-{platform}"


def _interpreter():
    # A venv's interpreter builds as its base one (same version and
    # headers), so that an existing build for that interpreter is reused.
    return getattr(sys, "_base_executable", None) or sys.executable


def _build(config_settings):
    settings = config_settings or {}
    build = Path(settings.get("build-dir") or ROOT / "build-python").resolve()
    jobs = str(settings.get("jobs") or os.cpu_count() or 1)
    if not (build / "CMakeCache.txt").exists():
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        "-DCMAKE_UNITY_BUILD=ON", "-DMETRICA_BUILD_PYTHON=ON", "-DMETRICA_BUILD_BENCH=OFF",
                        f"-DPython3_EXECUTABLE={_interpreter()}"], check=True, stdout=sys.stderr)
    subprocess.run(["cmake", "--build", str(build), "--target", "metrica_python", "-j", jobs], check=True,
                   stdout=sys.stderr)
    package = build / "python" / NAME
    modules = list(package.glob("_metrica*.so"))
    if not modules:
        raise RuntimeError(f"metrica_build: {build} built no Python module (is METRICA_BUILD_PYTHON on there?)")
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    if not any(m.name.endswith(suffix) for m in modules):
        raise RuntimeError(f"metrica_build: {build} holds a module for another interpreter ({modules[0].name}; "
                           f"this one loads *{suffix}): give another build-dir")
    return package


def _record_row(path, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return [path, f"sha256={digest}", str(len(data))]


def get_requires_for_build_wheel(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    folder = Path(metadata_directory) / _dist_info()
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "METADATA").write_text(_metadata())
    return folder.name


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    package = _build(config_settings)
    name = f"{NAME}-{_version()}-{_tag()}.whl"
    info = _dist_info()
    rows = []
    with zipfile.ZipFile(Path(wheel_directory) / name, "w", zipfile.ZIP_DEFLATED) as wheel:
        def add(path, data):
            wheel.writestr(path, data)
            rows.append(_record_row(path, data))

        for file in sorted(package.rglob("*")):
            if file.is_file() and "__pycache__" not in file.parts:
                add(f"{NAME}/{file.relative_to(package).as_posix()}", file.read_bytes())
        add(f"{info}/METADATA", _metadata().encode())
        add(f"{info}/WHEEL", f"Wheel-Version: 1.0\nGenerator: metrica_build\nRoot-Is-Purelib: false\nTag: {_tag()}\n"
            .encode())
        record = io.StringIO()
        writer = csv.writer(record, lineterminator="\n")
        writer.writerows(rows + [[f"{info}/RECORD", "", ""]])
        wheel.writestr(f"{info}/RECORD", record.getvalue())
    return name
