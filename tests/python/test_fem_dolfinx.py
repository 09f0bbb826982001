"""metrica.fem.dolfinx: meshes, ids and P1 values between FEniCSx and
metrica, and the FEniCSx loop of examples/python/fenicsx_loop.py at a small
size. Skipped where dolfinx is not installed (scripts/setup installs
Debian's python3-dolfinx)."""
import csv
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

dolfinx = pytest.importorskip("dolfinx")
from dolfinx import fem, mesh as dmesh  # noqa: E402
from mpi4py import MPI  # noqa: E402

import metrica  # noqa: E402
from metrica.fem import dolfinx as mfx  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def sorted_rows(a):
    a = np.sort(np.asarray(a), axis=1)
    return a[np.lexsort(a.T[::-1])]


def test_a_mesh_goes_to_dolfinx_and_back_with_its_ids():
    mesh = metrica.box(3)
    ids = np.where(mesh.points[mesh.tets].mean(axis=1)[:, 0] < 0.5, 1, 2)
    with pytest.warns(metrica.MetricaWarning, match="between two regions"):
        mesh = metrica.Mesh(mesh.points, mesh.tets, mesh.triangles, mesh.triangle_ids, ids)
    domain, regions, surfaces = mfx.to_dolfinx(mesh)
    assert domain.topology.index_map(3).size_local == mesh.num_tets
    assert regions.name == "regions" and surfaces.name == "surfaces"
    assert sorted(np.unique(regions.values)) == [1, 2]
    # The region of each dolfinx cell is the one of its metrica tet.
    order = mfx.vertex_map(domain)
    cells = order[domain.geometry.dofmap.array.reshape(-1, 4)]
    by_tet = {tuple(sorted(t)): i for t, i in zip(mesh.tets, mesh.tet_ids)}
    assert all(by_tet[tuple(sorted(c))] == v for c, v in zip(cells[regions.indices], regions.values))
    back = mfx.from_dolfinx(domain, surfaces, regions)
    assert np.array_equal(back.points, mesh.points)
    assert np.array_equal(sorted_rows(back.tets), sorted_rows(mesh.tets))
    assert np.array_equal(np.sort(back.tet_ids), np.sort(mesh.tet_ids))
    key = lambda m: np.lexsort(np.sort(m.triangles, axis=1).T)
    assert np.array_equal(back.triangle_ids[key(back)], mesh.triangle_ids[key(mesh)])
    back.check()


def test_dolfinx_own_cube_is_read_oriented_with_its_edges():
    cube = dmesh.create_unit_cube(MPI.COMM_SELF, 3, 3, 3)
    mesh = mfx.from_dolfinx(cube)
    mesh.check()  # every tet positively oriented
    assert mesh.num_vertices == 64 and mesh.num_tets == cube.topology.index_map(3).size_local
    assert mesh.info()["corners"] == 8 and len(mesh.info()["surfaces"]) == 6
    with pytest.raises(metrica.InputError, match="dimension 2"):
        mfx.from_dolfinx(cube, cell_tags=dmesh.meshtags(cube, 2, np.array([], np.int32), np.array([], np.int32)))


def test_vertex_values_are_in_metrica_order_and_set_vertex_values_inverts_them():
    mesh = metrica.box(4)
    domain, _, _ = mfx.to_dolfinx(mesh)
    V = fem.FunctionSpace(domain, ("Lagrange", 1))
    u = fem.Function(V)
    u.interpolate(lambda x: x[0] + 2 * x[1] + 3 * x[2])
    values = mfx.vertex_values(u)
    assert np.allclose(values, mesh.points @ [1, 2, 3], atol=1e-14)
    w = fem.Function(V)
    mfx.set_vertex_values(w, values)
    assert np.array_equal(w.x.array, u.x.array)
    W = fem.VectorFunctionSpace(domain, ("Lagrange", 1))
    g = fem.Function(W)
    g.interpolate(lambda x: np.stack([x[0], x[1], x[2]]))
    assert np.allclose(mfx.vertex_values(g), mesh.points, atol=1e-14)
    P2 = fem.FunctionSpace(domain, ("Lagrange", 2))
    with pytest.raises(metrica.InputError, match="degree 2"):
        mfx.vertex_values(fem.Function(P2))


def test_the_fenicsx_loop_beats_uniform_cubes(tmp_path):
    # The example at one small complexity: its table says adapted and
    # uniform errors at comparable vertex counts.
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    subprocess.run([sys.executable, str(ROOT / "examples/python/fenicsx_loop.py"), "600"], cwd=tmp_path, env=env,
                   check=True, capture_output=True)
    with open(tmp_path / "fenicsx_loop.csv") as f:
        row = next(csv.DictReader(f))
    adapted, uniform = float(row["adapted_l2_error"]), float(row["uniform_l2_error"])
    assert int(row["adapted_vertices"]) <= 1.5 * int(row["uniform_vertices"])
    assert adapted < uniform / 10
