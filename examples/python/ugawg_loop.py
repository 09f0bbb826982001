"""The UGAWG analytic cases from Python: a box of 6 x 3^3 tets adapted five
times to each metric, the metric evaluated again on each new mesh; prints
the size and the share of edges of unit length, and writes each result.

    PYTHONPATH=build/python python3 examples/python/ugawg_loop.py
"""
import logging
import numpy as np

import metrica

logging.basicConfig(level=logging.WARNING)

# The unit cube split into 6 tets per hex (the command's `metrica cube`).
n = 3
grid = np.linspace(0.0, 1.0, n + 1)
points = np.array([(x, y, z) for z in grid for y in grid for x in grid])
index = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)
tets = []
for k in range(n):
    for j in range(n):
        for i in range(n):
            c = [index(i + a, j + b, k + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
            # Six tets around the diagonal c[0] - c[7] (Kuhn's split).
            for p, q in ((1, 3), (3, 2), (2, 6), (6, 4), (4, 5), (5, 1)):
                tets.append([c[0], c[p], c[q], c[7]])
tets = np.array(tets)
# The boundary: the faces on one tet only, their surface id by side
# (1-6: x = 0, x = 1, y = 0, ...).
faces = np.sort(np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 2, 3]], tets[:, [0, 1, 3]], tets[:, [0, 1, 2]]]), axis=1)
unique, count = np.unique(faces, axis=0, return_counts=True)
triangles = unique[count == 1]
corner = points[triangles]
axis = np.argmax(np.ptp(corner, axis=1) == 0, axis=1)  # the coordinate the face keeps
side = corner[np.arange(len(triangles)), 0, axis] > 0.5
triangle_ids = 1 + 2 * axis + side

for case in ("linear", "polar-1", "polar-2"):
    mesh = metrica.Mesh(points, tets, triangles, triangle_ids)
    for it in range(5):
        mesh, report = metrica.adapt(mesh, analytic=case, concurrency="serial")
    q = report["quality"]
    print(f"{case:>8}: {mesh.num_vertices} vertices, {mesh.num_tets} tets, "
          f"{100 * q['unit_length_share']:.1f}% of edges in [1/sqrt 2, sqrt 2], worst tet {q['mean_ratio']['min']:.3f}")
    metrica.write(mesh, f"{case}.meshb")
