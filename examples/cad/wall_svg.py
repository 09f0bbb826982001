#!/usr/bin/env python3
"""Draws a cylinder wall of tetrahedral meshes, unrolled, side by side.

    wall_svg.py OUT.svg SURFACE RADIUS TITLE=MESH.mesh [TITLE=MESH.mesh ...]

Each panel shows the boundary triangles of surface id SURFACE of one mesh
(ASCII libMeshb: `metrica convert a.meshb a.mesh`), the cylinder about the
z axis unrolled: horizontal = RADIUS * angle, vertical = z. Under each
panel: the triangle count and the largest |r - RADIUS| of its vertices
(how far the wall's vertices are from the model's cylinder).
"""
import math
import sys


def read_mesh(path):
    """Vertices and (triangle, ref) of an ASCII .mesh file."""
    tokens = open(path).read().split()
    vertices, triangles = [], []
    i = 0
    while i < len(tokens):
        word = tokens[i]
        if word == "Vertices":
            n = int(tokens[i + 1])
            i += 2
            for _ in range(n):
                vertices.append(tuple(float(t) for t in tokens[i:i + 3]))
                i += 4
        elif word == "Triangles":
            n = int(tokens[i + 1])
            i += 2
            for _ in range(n):
                a, b, c, ref = (int(t) for t in tokens[i:i + 4])
                triangles.append(((a - 1, b - 1, c - 1), ref))
                i += 4
        else:
            i += 1
    return vertices, triangles


def panel(vertices, triangles, surface, radius, x0, width, height, title):
    wall = [t for t, ref in triangles if ref == surface]
    used = sorted({v for t in wall for v in t})
    deviation = max((abs(math.hypot(vertices[v][0], vertices[v][1]) - radius) for v in used), default=0.0)
    # Unrolled coordinates; the quarter cylinder spans [0, pi/2 * r] x [0, 1].
    def at(v):
        x, y, z = vertices[v]
        return radius * math.atan2(y, x), z

    points = {v: at(v) for v in used}
    us = [p[0] for p in points.values()]
    zs = [p[1] for p in points.values()]
    umin, umax, zmin, zmax = min(us), max(us), min(zs), max(zs)
    scale = min((width - 20) / max(umax - umin, 1e-12), (height - 80) / max(zmax - zmin, 1e-12))

    def xy(v):
        u, z = points[v]
        return x0 + 10 + (u - umin) * scale, 40 + (zmax - z) * scale

    out = [f'<text x="{x0 + width / 2}" y="24" text-anchor="middle" font-size="16">{title}</text>']
    for t in wall:
        pts = " ".join(f"{xy(v)[0]:.2f},{xy(v)[1]:.2f}" for v in t)
        out.append(f'<polygon points="{pts}" fill="#dfe9f5" stroke="#1f4e79" stroke-width="0.4"/>')
    out.append(
        f'<text x="{x0 + width / 2}" y="{height - 20}" text-anchor="middle" font-size="13">'
        f"{len(wall)} triangles, max |r - {radius}| = {deviation:.1e}</text>"
    )
    return out


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    out_path, surface, radius = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    panels = [arg.split("=", 1) for arg in sys.argv[4:]]
    width, height = 420, 560
    body = []
    for k, (title, path) in enumerate(panels):
        vertices, triangles = read_mesh(path)
        body += panel(vertices, triangles, surface, radius, k * width, width, height, title)
    svg = (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width * len(panels)}" height="{height}" '
        f'font-family="sans-serif"><rect width="100%" height="100%" fill="white"/>'
        + "".join(body)
        + "</svg>\n"
    )
    open(out_path, "w").write(svg)


if __name__ == "__main__":
    main()
