"""The Python module: numpy <-> Mesh <-> file round trips, metrics, the
adaptation (the command's serial output to the bit), errors, and Ctrl-C.
Run by CTest (label python) with PYTHONPATH=BUILD/python and METRICA_CLI
set to the command."""
import filecmp
import os
import signal
import subprocess
import sys
import threading
import warnings

import numpy as np
import pytest

import metrica

CLI = os.environ.get("METRICA_CLI", "metrica")


def cube(tmp_path, n=3):
    path = tmp_path / "cube.meshb"
    subprocess.run([CLI, "cube", "--n", str(n), "-o", str(path), "-q"], check=True)
    return path


def two_tets():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float)
    tets = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])
    return points, tets


def test_arrays_round_trip_through_a_mesh_and_files(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    again = metrica.Mesh(mesh.points, mesh.tets, mesh.triangles, mesh.triangle_ids, mesh.tet_ids)
    for name in ("points", "tets", "triangles", "triangle_ids", "tet_ids"):
        assert np.array_equal(getattr(again, name), getattr(mesh, name)), name
    assert mesh.points.dtype == np.float64 and mesh.points.shape == (mesh.num_vertices, 3)
    assert mesh.tets.shape == (mesh.num_tets, 4)
    for suffix in (".mesh", ".meshb", ".msh"):
        path = tmp_path / ("out" + suffix)
        metrica.write(again, path)
        back = metrica.read(path)
        assert np.array_equal(back.points, mesh.points) and np.array_equal(back.tets, mesh.tets), suffix
        assert np.array_equal(back.triangle_ids, mesh.triangle_ids), suffix


def test_info_and_check():
    with pytest.warns(metrica.MetricaWarning, match="1 faces between two regions have no input triangle"):
        mesh = metrica.Mesh(*two_tets(), tet_ids=np.array([2, 3]))
    mesh.check()
    info = mesh.info()
    assert info["vertices"] == 5 and info["tets"] == 2
    assert info["volume"] == pytest.approx(1 / 6 + 1 / 3)
    assert set(info["regions"]) == {2, 3}
    assert info["internal_faces"] == 1  # the face between the two regions


def test_a_cube_of_points_and_tets_keeps_its_edges_and_corners(tmp_path):
    # No triangles: the boundary is split at edges sharper than 45 degrees.
    full = metrica.read(cube(tmp_path, n=4))
    mesh = metrica.Mesh(full.points, full.tets)
    info = mesh.info()
    assert len(info["surfaces"]) == 6 and info["ridge_curves"] == 12 and info["corners"] == 8
    adapted, _ = metrica.adapt(mesh, analytic="linear", concurrency="serial", cycles=4)
    after = adapted.info()
    assert len(after["surfaces"]) == 6 and after["ridge_curves"] == 12 and after["corners"] == 8
    assert after["volume"] == pytest.approx(1.0, abs=1e-12)
    # ridge_angle=180: one surface, no ridge; out of [0, 180]: refused.
    with pytest.warns(metrica.MetricaWarning, match="192 boundary faces have no input triangle"):
        flat = metrica.Mesh(full.points, full.tets, ridge_angle=180).info()
    assert len(flat["surfaces"]) == 1 and flat["corners"] == 0
    with pytest.raises(metrica.InputError, match="ridge_angle"):
        metrica.Mesh(full.points, full.tets, ridge_angle=200)


def test_bad_arrays_raise_the_commands_messages():
    points, tets = two_tets()
    with pytest.raises(metrica.InputError, match=r"expected shape \(n, 3\)"):
        metrica.Mesh(points[:, :2], tets)
    with pytest.raises(metrica.InputError, match="expected float64 values, got dtype <U"):
        metrica.Mesh(points.astype(str), tets)
    with pytest.raises(metrica.InputError, match="out of range"):
        metrica.Mesh(points, tets + 1)
    bad = points.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match="not finite|NaN|nan"):
        metrica.Mesh(bad, tets)
    with pytest.raises(metrica.InputError, match="1 inverted of 2"):
        metrica.Mesh(points, np.array([[0, 1, 2, 3], [2, 1, 3, 4]]))
    with pytest.raises(metrica.InputError):
        metrica.read("/nonexistent/mesh.meshb")


def test_fields_round_trip(tmp_path):
    values = np.arange(12, dtype=float).reshape(2, 6) + 1.0
    metrica.write_field(tmp_path / "m.solb", values)
    (back,) = metrica.read_field(tmp_path / "m.solb")
    assert np.array_equal(back, values)
    with pytest.raises(metrica.InputError):
        metrica.write_field(tmp_path / "m.solb", np.zeros((2, 4)))


def test_serial_adaptation_is_the_commands_to_the_bit(tmp_path):
    start = cube(tmp_path)
    by_command = tmp_path / "command.meshb"
    subprocess.run([CLI, "adapt", str(start), "--analytic", "linear", "--iterations", "2", "--concurrency", "serial",
                    "-o", str(by_command), "-q"], check=True)
    adapted, report = metrica.adapt(metrica.read(start), analytic="linear", iterations=2, concurrency="serial")
    by_python = tmp_path / "python.meshb"
    metrica.write(adapted, by_python)
    assert filecmp.cmp(by_command, by_python, shallow=False)
    assert report["quality"]["unit_length_share"] > 0.9
    assert report["ops"]["split"]["applied"] > 0 and report["cycles"]


UGAWG = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data", "ugawg")


def test_adaptation_on_a_cad_model_is_the_commands_to_the_bit(tmp_path):
    step = os.path.join(UGAWG, "cube-cylinder.step")
    start = tmp_path / "start.meshb"
    subprocess.run([CLI, "bootstrap", step, "-o", str(start), "--size", "0.25", "--threads", "1", "-q"], check=True)
    by_command = tmp_path / "command.meshb"
    subprocess.run([CLI, "adapt", str(start), "--geometry", step, "--analytic", "polar-2", "--cycles", "4",
                    "--quality-passes", "1", "--concurrency", "serial", "-o", str(by_command), "-q"], check=True)
    adapted, _ = metrica.adapt(metrica.read(start), analytic="polar-2", geometry=step, cycles=4, quality_passes=1,
                               concurrency="serial")
    adapted.check()
    assert np.array_equal(adapted.points, metrica.read(by_command).points)
    assert np.array_equal(adapted.tets, metrica.read(by_command).tets)
    with pytest.raises(metrica.InputError):
        metrica.adapt(metrica.read(start), analytic="polar-2", geometry=tmp_path / "none.step", cycles=1)


def test_quality_measures_and_a_metric_written_beside_its_mesh(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    metric = metrica.analytic_metric(mesh, "linear")
    q = metrica.quality(mesh, metric)
    assert q["edge_ends"].shape == (q["edges"], 2) and q["edge_lengths"].shape == (q["edges"],)
    assert q["mean_ratios"].shape == (mesh.num_tets,)
    assert q["edge_lengths"].min() == pytest.approx(q["length"]["min"])
    assert q["mean_ratios"].min() == pytest.approx(q["mean_ratio"]["min"])
    a, b = q["edge_ends"][0]
    assert 0 <= a < b < mesh.num_vertices
    assert "edge_ends" not in metrica.quality(mesh, metric, measures=False)
    metrica.write(mesh, tmp_path / "m.meshb", metric=metric)
    (back,) = metrica.read_field(tmp_path / "m.solb")
    assert np.array_equal(back, metric)
    with pytest.raises(metrica.InputError, match="rows"):
        metrica.write(mesh, tmp_path / "n.meshb", metric=metric[1:])
    with pytest.raises(metrica.InputError, match="beside a .mesh or .meshb, or into a .vtu"):
        metrica.write(mesh, tmp_path / "n.msh", metric=metric)
    assert not (tmp_path / "n.meshb").exists()


def test_adaptation_to_a_metric_array_leaves_the_input_alone(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    before = mesh.points.copy()
    metric = metrica.analytic_metric(mesh, "linear", hmin=0.05)
    seen = []
    adapted, report = metrica.adapt(mesh, metric, threads=2, on_cycle=seen.append, cycles=4)
    adapted.check()
    assert adapted.num_tets > mesh.num_tets and len(seen) == len(report["cycles"]) >= 4
    assert np.array_equal(mesh.points, before)
    q = metrica.quality(adapted, metrica.analytic_metric(adapted, "linear", hmin=0.05))
    assert q["tets"] == adapted.num_tets


def test_bad_adaptation_calls_raise(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    with pytest.raises(metrica.InputError, match="one of metric"):
        metrica.adapt(mesh)
    with pytest.raises(metrica.InputError, match="unknown option 'cycle'"):
        metrica.adapt(mesh, analytic="linear", cycle=3)
    # The command's settings table, its domains: an integer count, a length > 0.
    with pytest.raises(metrica.InputError, match=r"cycles must be an integer in \[0, 1000\]"):
        metrica.adapt(mesh, analytic="linear", cycles=2.5)
    with pytest.raises(metrica.InputError, match=r"max_length must be in \(0, 1000000\]"):
        metrica.adapt(mesh, analytic="linear", max_length=0)
    with pytest.raises(metrica.InputError, match="need min_length < max_length"):
        metrica.adapt(mesh, analytic="linear", min_length=2, max_length=1.5)
    assert "smooth_below" in metrica.adapt.__doc__ and "default 0.5" in metrica.adapt.__doc__
    with pytest.raises(metrica.InputError, match="unknown analytic metric"):
        metrica.adapt(mesh, analytic="quadratic")
    with pytest.raises(metrica.InputError, match="unknown concurrency"):
        metrica.adapt(mesh, analytic="linear", concurrency="mpi")
    metric = metrica.analytic_metric(mesh, "linear")
    metric[0] = [1, 0, -1, 0, 0, 1]  # not positive definite
    with pytest.raises(metrica.InputError, match="positive definite|SPD"):
        metrica.adapt(mesh, metric)
    with pytest.raises(metrica.InputError, match="rows for"):
        metrica.adapt(mesh, metric[:-1])


def test_ctrl_c_stops_the_run_and_leaves_the_input(tmp_path):
    mesh = metrica.read(cube(tmp_path, 6))
    before = mesh.points.copy()
    # Python's own handler (a test runner may have started us without it).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            metrica.adapt(mesh, analytic="polar-1", iterations=50, concurrency="serial")
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    mesh.check()
    assert np.array_equal(mesh.points, before)


def test_multiscale_metric_intersection_complexity(tmp_path):
    mesh = metrica.read(cube(tmp_path, 4))
    u = metrica.analytic_field(mesh, "tanh3")
    assert u.shape == (mesh.num_vertices,)
    metric = metrica.multiscale_metric(mesh, u, complexity=2000, gradation=3.0)
    assert metric.shape == (mesh.num_vertices, 6)
    assert metrica.complexity(mesh, metric) == pytest.approx(2000, rel=0.02)
    # Two fields intersected ask for at least what each asks.
    both = metrica.multiscale_metric(mesh, np.stack([u, u * u], axis=1), complexity=2000)
    assert both.shape == metric.shape
    iso = np.tile([4.0, 0, 4.0, 0, 0, 4.0], (mesh.num_vertices, 1))
    met = metrica.intersect(metric, iso)
    assert np.all(met[:, 0] >= np.maximum(metric[:, 0], 4.0) - 1e-9)
    assert np.array_equal(metrica.intersect(iso, iso), iso)
    with pytest.raises(metrica.InputError):
        metrica.multiscale_metric(mesh, u, complexity=-1)
    with pytest.raises(metrica.InputError, match="rows for"):
        metrica.multiscale_metric(mesh, u[:-1], complexity=100)


def test_interpolation_and_error(tmp_path):
    coarse = metrica.read(cube(tmp_path, 3))
    fine, _ = metrica.adapt(coarse, analytic="linear", concurrency="serial")
    u = metrica.analytic_field(coarse, "tanh3")
    carried = metrica.interpolate(coarse, u, fine)
    assert carried.shape == (fine.num_vertices,)
    # A linear field is carried exactly.
    x = coarse.points[:, 0] + 2 * coarse.points[:, 1]
    assert np.allclose(metrica.interpolate(coarse, x, fine), fine.points[:, 0] + 2 * fine.points[:, 1])
    two = metrica.interpolate(coarse, np.stack([x, -x], axis=1), fine)
    assert two.shape == (fine.num_vertices, 2) and np.allclose(two[:, 1], -two[:, 0])
    e_coarse = metrica.error(coarse, u, exact="tanh3")
    e_fine = metrica.error(fine, metrica.analytic_field(fine, "tanh3"), exact="tanh3")
    assert 0 < e_fine < e_coarse
    against_fine = metrica.error(coarse, u, reference=fine, reference_values=metrica.analytic_field(fine, "tanh3"))
    assert against_fine > 0


def test_the_multiscale_metric_of_a_planar_front_across_the_axes(tmp_path):
    # tanh(10 (x + y + z - 1.5)): its Hessian is of rank one along (1, 1, 1).
    mesh = metrica.read(cube(tmp_path, 8))
    u = np.tanh(10 * (mesh.points.sum(axis=1) - 1.5))
    metric = metrica.multiscale_metric(mesh, u, complexity=2000)
    assert np.all(np.isfinite(metric))
    assert metrica.complexity(mesh, metric) == pytest.approx(2000, rel=0.01)


def test_a_metric_array_is_the_background_of_the_run_and_the_report_is_in_it(tmp_path):
    coarse = metrica.read(cube(tmp_path, 3))
    metric = metrica.analytic_metric(coarse, "linear", hmin=0.05)
    adapted, report = metrica.adapt(coarse, metric, concurrency="serial", cycles=4)
    # Measured in the array given (on the mesh it was given on), the report's
    # figures again.
    q = metrica.quality(adapted, metric, metric_mesh=coarse, measures=False)
    assert q["unit_length_share"] == pytest.approx(report["quality"]["unit_length_share"], abs=1e-12)
    assert q["mean_ratio"]["min"] == pytest.approx(report["quality"]["mean_ratio"]["min"], abs=1e-12)
    # The metric moves log-Euclidean: exp of a linear log field exactly.
    def log_linear(p):
        x, y, z = p[:, 0], p[:, 1], p[:, 2]
        return np.stack([1 + x, 0.3 * y, 2 - z, 0.2 * x - 0.1, 0.5 * z, 3 * y], axis=1)

    def spd_exp(logs):
        out = []
        for l in logs:
            m = np.array([[l[0], l[1], l[3]], [l[1], l[2], l[4]], [l[3], l[4], l[5]]])
            w, v = np.linalg.eigh(m)
            e = v @ np.diag(np.exp(w)) @ v.T
            out.append([e[0, 0], e[0, 1], e[1, 1], e[0, 2], e[1, 2], e[2, 2]])
        return np.array(out)

    moved = metrica.interpolate(coarse, spd_exp(log_linear(coarse.points)), adapted, metric=True)
    assert moved.shape == (adapted.num_vertices, 6)
    expected = spd_exp(log_linear(adapted.points))
    assert np.abs(moved - expected).max() < 1e-8 * np.abs(expected).max()
    with pytest.raises(metrica.InputError):
        metrica.interpolate(coarse, -metric, adapted, metric=True)


def test_meshio_round_trip(tmp_path):
    meshio = pytest.importorskip("meshio")
    mesh = metrica.read(cube(tmp_path))
    m = metrica.to_meshio(mesh)
    assert isinstance(m, meshio.Mesh)
    back = metrica.from_meshio(m)
    assert np.array_equal(back.tets, mesh.tets) and np.array_equal(back.triangle_ids, mesh.triangle_ids)
    # Our .vtu as meshio reads it: its region ids are one-component cell data.
    metrica.write(mesh, str(tmp_path / "m.vtu"))
    from_vtu = metrica.from_meshio(meshio.read(tmp_path / "m.vtu"))
    assert np.array_equal(from_vtu.tets, mesh.tets) and np.array_equal(from_vtu.tet_ids, mesh.tet_ids)
    # .msh both ways, region 0 (the cube's) beside surfaces 1 to 6.
    assert set(mesh.tet_ids) == {0}
    key = lambda m: np.lexsort(np.sort(m.triangles, axis=1).T)
    metrica.write(mesh, tmp_path / "m.msh")
    from_msh = metrica.from_meshio(meshio.read(tmp_path / "m.msh"))
    assert set(from_msh.tet_ids) == {0}
    assert np.array_equal(from_msh.triangle_ids[key(from_msh)], mesh.triangle_ids[key(mesh)])
    ids = [mesh.tet_ids, mesh.triangle_ids]
    written = meshio.Mesh(mesh.points, [("tetra", mesh.tets), ("triangle", mesh.triangles)],
                          cell_data={"gmsh:physical": ids, "gmsh:geometrical": ids})
    meshio.write(tmp_path / "w.msh", written, file_format="gmsh22", binary=False)
    back = metrica.read(tmp_path / "w.msh")
    assert set(back.tet_ids) == {0}
    assert np.array_equal(back.triangle_ids[key(back)], mesh.triangle_ids[key(mesh)])


def test_the_namespace_holds_metrica_only():
    assert not {"os", "logging", "np", "numpy"} & set(dir(metrica))
    assert set(metrica.__all__) <= set(dir(metrica))


def test_a_pipeline_composed_in_python(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    seen = []
    p = metrica.Pipeline(
        cycle=[("collapse", {}), ("split", {}),
               ("delaunay", "flip", {"criterion": "metric-delaunay"}),
               ("edge-weight", "flip", {"criterion": "edge-weight"}),
               ("smooth", {"below": 0.3})],
        polish=[("flip", {"seed_below": 0.75}), ("smooth", {"below": 1.0})],
        cycles=4, quality_passes=2, repair_rounds=0)
    adapted, report = p.run(mesh, analytic="linear", concurrency="serial", on_cycle=seen.append)
    adapted.check()
    assert report["ops"]["edge-weight"]["tried"] > 0 and report["ops"]["delaunay"]["applied"] > 0
    assert sum(1 for c in report["cycles"] if c["kind"] == "cycle") <= 4 and seen
    assert report["quality"]["unit_length_share"] > 0.8
    # Serial runs are reproducible; a stage left out changes the result.
    again, _ = p.run(mesh, analytic="linear", concurrency="serial")
    assert np.array_equal(again.points, adapted.points)
    p.cycle = p.cycle[:2] + p.cycle[4:]
    fewer, report = p.run(mesh, analytic="linear", concurrency="serial")
    assert "edge-weight" not in report["ops"] and fewer.num_tets != adapted.num_tets
    with pytest.raises(metrica.InputError, match="unknown operation 'refine'"):
        metrica.Pipeline(cycle=[("refine", {})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match="unknown option 'below'"):
        metrica.Pipeline(cycle=[("collapse", {"below": 1})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match="unknown criterion of stage 'flip' 'delaunay'"):
        metrica.Pipeline(cycle=[("flip", {"criterion": "delaunay"})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match="two stages named"):
        metrica.Pipeline(cycle=[("flip", {}), ("flip", {})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match=r"seed_below must be a number in \[0, 1\]"):
        metrica.Pipeline(cycle=[("flip", {"seed_below": 1.5})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match=r"max_sweeps must be a whole number in \[1, 1000\]"):
        metrica.Pipeline(cycle=[("flip", {"max_sweeps": 2.5})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match="face_flips must be true or false"):
        metrica.Pipeline(cycle=[("flip", {"face_flips": 1})]).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match=r"unknown rule 'max_sweeps' \(cycles, quality_passes"):
        metrica.Pipeline(cycle=[("flip", {})], max_sweeps=2).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match=r"cycles must be an integer in \[0, 1000\] \(got 2.5\)"):
        metrica.Pipeline(cycle=[("flip", {})], cycles=2.5).run(mesh, analytic="linear")
    with pytest.raises(metrica.InputError, match=r"min_change must be in \[0, 1\]"):
        metrica.Pipeline(cycle=[("flip", {})], min_change=True).run(mesh, analytic="linear")
    # The docstring lists every kind of stage the registry has, with its
    # options, and every rule.
    for op, _, options in metrica._metrica._stage_kinds():
        assert op in metrica.Pipeline.__doc__
        assert all(name in metrica.Pipeline.__doc__ for name, _, _ in options)
    assert all(name in metrica.Pipeline.__doc__ for name, _, _, _ in metrica._metrica._pipeline_rules())


def test_a_pipeline_from_python_and_from_the_command_give_one_mesh(tmp_path):
    start = cube(tmp_path)
    p = metrica.Pipeline(cycle=[("collapse", {}), ("split", {}), ("w", "flip", {"criterion": "edge-weight"})],
                         polish=[("smooth", {"below": 1.0})], max_cycles=3, quality_passes=1)
    adapted, _ = p.run(metrica.read(start), analytic="polar-1", concurrency="serial")
    subprocess.run([CLI, "pipeline", str(start), "--analytic", "polar-1", "--cycle",
                    "collapse,split,w=flip:criterion=edge-weight", "--polish", "smooth:below=1", "--cycles", "3",
                    "--quality-passes", "1", "--concurrency", "serial", "-o", str(tmp_path / "cmd.meshb"), "-q"],
                   check=True)
    by_command = metrica.read(tmp_path / "cmd.meshb")
    assert np.array_equal(by_command.points, adapted.points)
    assert np.array_equal(by_command.tets, adapted.tets)


def test_the_library_warns_through_python_warnings(tmp_path):
    # A message of the calling thread goes to warnings.warn at once.
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float)
    with pytest.warns(metrica.MetricaWarning, match="every tet is negatively oriented; reorienting all 2 tets"):
        mesh = metrica.Mesh(points, np.array([[0, 2, 1, 3], [1, 3, 2, 4]]))
    assert mesh.num_tets == 2
    mesh = metrica.read(cube(tmp_path))
    x = mesh.points
    fields = np.stack([np.tanh(10 * (x[:, 0] - 0.5)), x[:, 1]], axis=1)  # the second is linear
    with pytest.warns(metrica.MetricaWarning, match="field 2 of 2 has a zero Hessian"):
        metrica.multiscale_metric(mesh, fields, 1000)
    # A warning filtered into an error is reported as unraisable, not
    # raised from inside the library.
    seen, hook = [], sys.unraisablehook
    sys.unraisablehook = seen.append
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error", metrica.MetricaWarning)
            metric = metrica.multiscale_metric(mesh, fields, 1000)
    finally:
        sys.unraisablehook = hook
    assert metric.shape == (mesh.num_vertices, 6)
    assert len(seen) == 1 and "zero Hessian" in str(seen[0].exc_value)


def test_adapt_guards_the_size_and_checks_its_counts(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    # As the command: a run predicted past max_tets is refused before any work.
    with pytest.raises(metrica.InputError, match=r"adapt: the metric has complexity .*the limit is 100 tets "
                                                 r"\(max_tets=N raises it"):
        metrica.adapt(mesh, analytic="linear", max_tets=100)
    adapted, prediction = metrica.adapt(mesh, analytic="linear", dry_run=True)
    assert adapted is None and prediction["predicted_tets"] == 10 * prediction["complexity"] > 1000
    assert prediction["predicted_bytes"] == 125 * prediction["predicted_tets"]
    metric = metrica.analytic_metric(mesh, "linear") * 1e8  # sizes of 1e-4 of the linear metric's
    with pytest.raises(metrica.InputError, match="the limit is"):
        metrica.adapt(mesh, metric)  # the default: what 90% of the memory holds
    for bad in (0, 1.5, True, "2", -1):
        with pytest.raises(metrica.InputError, match="threads must be a whole number in"):
            metrica.adapt(mesh, analytic="linear", threads=bad)
    with pytest.raises(metrica.InputError, match="iterations must be a whole number"):
        metrica.adapt(mesh, analytic="linear", iterations=2.0)
    for bad in (0, -5, float("nan"), "big"):
        with pytest.raises(metrica.InputError, match="max_tets must be a positive number"):
            metrica.adapt(mesh, analytic="linear", max_tets=bad)
    with pytest.raises(metrica.InputError, match="threads must be a whole number"):
        metrica.Pipeline(cycle=[("flip", {})]).run(mesh, analytic="linear", threads=0.5)


def test_a_mesh_is_copied_and_pickled_whole(tmp_path):
    import copy
    import pickle

    mesh = metrica.read(cube(tmp_path))
    for other in (copy.copy(mesh), copy.deepcopy(mesh), pickle.loads(pickle.dumps(mesh))):
        assert other is not mesh
        assert np.array_equal(other.points, mesh.points) and np.array_equal(other.tets, mesh.tets)
        assert np.array_equal(other.triangles, mesh.triangles)
        assert np.array_equal(other.triangle_ids, mesh.triangle_ids) and np.array_equal(other.tet_ids, mesh.tet_ids)
        assert other.info() == mesh.info()
    # A mesh with another kernel's association records keeps them through
    # a pickle: written, the same bytes.
    hsc = metrica.read(os.path.join(os.path.dirname(UGAWG), "hemisphere-cylinder", "hsc01.meshb"))
    metrica.write(hsc, str(tmp_path / "a.meshb"))
    metrica.write(pickle.loads(pickle.dumps(hsc)), str(tmp_path / "b.meshb"))
    assert filecmp.cmp(tmp_path / "a.meshb", tmp_path / "b.meshb", shallow=False)
    with pytest.raises(metrica.InputError, match="a pickled mesh is"):
        metrica.Mesh.__new__(metrica.Mesh).__setstate__((b"x", "4"))
    assert metrica.__version__ == subprocess.run([CLI, "--version"], capture_output=True, text=True,
                                                 check=True).stdout.split()[1]
    p = metrica.Pipeline(cycle=[("flip", {})], cycles=3)
    assert repr(p) == "metrica.Pipeline(cycle=[('flip', {})], polish=[], repair=[], cycles=3)"


def test_arrays_from_lists_and_integers_bad_values_as_input_errors(tmp_path):
    points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    from_lists = metrica.Mesh(points, [[0, 1, 2, 3]])
    assert from_lists.num_tets == 1 and from_lists.points.dtype == np.float64
    from_ints = metrica.Mesh(np.array(points, dtype=np.int64), np.array([[0, 1, 2, 3]]))
    assert np.array_equal(from_ints.points, from_lists.points)
    with pytest.raises(TypeError, match="points: expected an array or a sequence of rows, got object"):
        metrica.Mesh(object(), [[0, 1, 2, 3]])
    with pytest.raises(metrica.InputError, match="tets: expected integer values"):
        metrica.Mesh(points, [[0.0, 1.0, 2.0, 3.0]])
    with pytest.raises(metrica.InputError, match="points: expected shape"):
        metrica.Mesh([[0, 0], [1, 0]], [[0, 1, 2, 3]])
    # A metric that is not positive definite is not written.
    mesh = metrica.read(cube(tmp_path))
    metric = metrica.analytic_metric(mesh, "linear")
    metric[3] = [1, 0, -1, 0, 0, 1]
    with pytest.raises(metrica.InputError, match="not positive definite"):
        metrica.write(mesh, str(tmp_path / "x.meshb"), metric=metric)
    assert not (tmp_path / "x.meshb").exists() and not (tmp_path / "x.solb").exists()


def test_a_box_is_the_commands_cube(tmp_path):
    from_file = metrica.read(cube(tmp_path))  # metrica cube --n 3
    made = metrica.box(3)
    assert np.array_equal(made.points, from_file.points) and np.array_equal(made.tets, from_file.tets)
    assert np.array_equal(made.triangle_ids, from_file.triangle_ids)
    long = metrica.box((2, 1, 1), lo=(-1, 0, 0), hi=(1, 1, 1))
    assert long.num_tets == 12 and long.info()["volume"] == pytest.approx(2.0)
    for bad in (0, 2.5, True, (1, 2)):
        with pytest.raises(metrica.InputError, match="box: n"):
            metrica.box(bad)
    with pytest.raises(metrica.InputError, match="box: need lo < hi"):
        metrica.box(2, lo=(1, 0, 0), hi=(0, 1, 1))


def test_vtu_and_su2_read_back_with_their_ids_and_vtu_point_data(tmp_path):
    mesh = metrica.read(cube(tmp_path))
    metric = metrica.analytic_metric(mesh, "linear")
    u = mesh.points[:, 0]
    metrica.write(mesh, tmp_path / "m.vtu", metric=metric, fields={"u": u, "p": mesh.points})
    for suffix in (".vtu", ".su2"):
        if suffix == ".su2":
            metrica.write(mesh, tmp_path / "m.su2")
        back = metrica.read(tmp_path / ("m" + suffix))
        assert np.array_equal(back.points, mesh.points) and np.array_equal(back.tets, mesh.tets), suffix
        key = lambda m: np.lexsort(np.sort(m.triangles, axis=1).T)
        assert np.array_equal(back.triangle_ids[key(back)], mesh.triangle_ids[key(mesh)]), suffix
    meshio = pytest.importorskip("meshio")
    m = meshio.read(tmp_path / "m.vtu")
    assert np.array_equal(m.point_data["u"].ravel(), u) and np.array_equal(m.point_data["p"], mesh.points)
    # The metric in VTK's order (xx yy zz xy yz xz), which ParaView reads.
    assert np.array_equal(m.point_data["metric"], metric[:, [0, 2, 5, 1, 4, 3]])
    with pytest.raises(metrica.InputError, match="fields= go into a .vtu"):
        metrica.write(mesh, tmp_path / "m.meshb", fields={"u": u})
    with pytest.raises(metrica.InputError, match="field 'u'"):
        metrica.write(mesh, tmp_path / "m.vtu", fields={"u": u[:-1]})


def test_error_against_a_python_function_hessian_and_hessian_metric(tmp_path):
    mesh = metrica.read(cube(tmp_path, 6))
    u = metrica.analytic_field(mesh, "tanh3")

    def tanh3(p):
        return np.tanh((p[:, 0] + 1.3) ** 20 * (p[:, 1] - 0.3) ** 9 * p[:, 2])

    assert metrica.error(mesh, u, exact=tanh3) == pytest.approx(metrica.error(mesh, u, exact="tanh3"), rel=1e-12)
    with pytest.raises(metrica.InputError, match="must return"):
        metrica.error(mesh, u, exact=lambda p: p)
    with pytest.raises(metrica.InputError, match="analytic field's name or a function"):
        metrica.error(mesh, u, exact=3)
    # A quadratic field's Hessian, exact at interior vertices of the Kuhn box.
    q = mesh.points[:, 0] ** 2 + mesh.points[:, 0] * mesh.points[:, 1]
    h = metrica.hessian(mesh, q)
    inner = np.all((mesh.points > 0.2) & (mesh.points < 0.8), axis=1)
    assert np.allclose(h[inner], [2, 1, 0, 0, 0, 0], atol=1e-9)
    # The metric of a Hessian as the multiscale metric of the field makes it.
    from_h = metrica.hessian_metric(mesh, metrica.hessian(mesh, u), complexity=500)
    assert metrica.complexity(mesh, from_h) == pytest.approx(500, rel=0.01)
    with pytest.raises(metrica.InputError, match="hessian_metric: complexity"):
        metrica.hessian_metric(mesh, h, complexity=-1)


def test_messages_number_vertices_and_tets_from_0():
    points, tets = two_tets()
    with pytest.raises(metrica.InputError, match=r"tet 0 \(vertices 0 2 1 3\) is inverted"):
        metrica.Mesh(points, np.array([[0, 2, 1, 3], [1, 2, 3, 4]]))
    mesh = metrica.Mesh(points, tets)
    bad = np.tile([1.0, 0, 1, 0, 0, 1], (5, 1))
    bad[3] = [-1, 0, 1, 0, 0, 1]
    with pytest.raises(metrica.InputError, match="metric at vertex 3 is not positive definite"):
        metrica.complexity(mesh, bad)


def test_the_type_stubs_name_what_the_extension_holds():
    import ast
    from pathlib import Path

    import metrica._metrica as ext

    stub = Path(ext.__file__).with_name("_metrica.pyi")
    tree = ast.parse(stub.read_text())
    named = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    public = {name for name in dir(ext) if not name.startswith("__")}
    assert public - {"__version__"} <= named | {"__version__"}, public - named
    assert named <= public | {"_Path"}, named - public
    assert (stub.parent / "py.typed").exists()
