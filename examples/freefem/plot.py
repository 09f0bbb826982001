#!/usr/bin/env python3
"""The FreeFEM study's plot and tables: cD and cL errors against vertices for
the adapted sequence (examples/freefem/run) and the uniform one
(examples/freefem/uniform), from their history.csv files.

usage: plot.py ADAPTED/history.csv UNIFORM/history.csv -o study.png > table.md
"""
import argparse
import csv
import sys

CD, CL = 6.18533, 0.009401  # Schäfer-Turek 3D-1Z reference values (John 2002)
CD_TARGET, CL_TARGET = 0.003, 0.0005


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot.py: {path} holds no row")
    for r in rows:
        for k in ("vertices", "tets", "newton"):
            r[k] = int(r[k])
        for k in ("cd", "cl", "solver_seconds", "metrica_seconds", "model_distance"):
            r[k] = float(r[k])
        r["cd_error"] = abs(r["cd"] - CD) / CD
        r["cl_error"] = abs(r["cl"] - CL)
    return rows


def table(name, rows):
    print(f"\n{name}\n")
    print("| iteration | vertices | tets | cD | cD error | cL | cL error | solver s | Metrica s | model distance |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {int(r['iteration'])} | {r['vertices']:,} | {r['tets']:,} | {r['cd']:.5f} | {100 * r['cd_error']:.2f}% "
              f"| {r['cl']:+.5f} | {r['cl_error']:.5f} | {r['solver_seconds']:.0f} | {r['metrica_seconds']:.1f} "
              f"| {r['model_distance']:.1e} |")
    solver = sum(r["solver_seconds"] for r in rows)
    metrica = sum(r["metrica_seconds"] for r in rows)
    print(f"\nTotal: {solver + metrica:,.0f} s ({solver:,.0f} s in FreeFEM, {metrica:,.1f} s in Metrica).")


def first_within(rows, key, bound):
    """The fewest vertices from which every later mesh of the sequence stays within bound."""
    best = None
    for r in sorted(rows, key=lambda r: r["vertices"], reverse=True):
        if r[key] > bound:
            break
        best = r
    return best


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("adapted")
    p.add_argument("uniform")
    p.add_argument("-o", "--output", default="freefem-study.png")
    a = p.parse_args()
    adapted, uniform = read(a.adapted), read(a.uniform)
    table("Adapted (Metrica on the CAD model)", adapted)
    table("Uniform (gmsh)", uniform)
    print()
    for key, bound, label in (("cd_error", CD_TARGET, "|cD error| <= 0.3%"), ("cl_error", CL_TARGET, "|cL error| <= 0.0005")):
        cells = []
        for name, rows in (("adapted", adapted), ("uniform", uniform)):
            within = [r for r in rows if r[key] <= bound]
            stays = first_within(rows, key, bound)
            first = f"first at {min(r['vertices'] for r in within):,} vertices" if within else "never"
            last = f"within from {stays['vertices']:,} on" if stays else \
                f"not within at the largest ({max(r['vertices'] for r in rows):,} vertices)"
            cells.append(f"{name} {first}, {last}")
        ra, ru = first_within(adapted, key, bound), first_within(uniform, key, bound)
        ratio = f" (uniform / adapted vertices: {ru['vertices'] / ra['vertices']:.2f})" if ra and ru else ""
        print(f"- {label}: " + "; ".join(cells) + ratio)

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("plot.py: matplotlib is missing (apt-get install python3-matplotlib); the tables are above")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, key, bound, title in ((axes[0], "cd_error", CD_TARGET, "drag: |cD - 6.18533| / 6.18533"),
                                  (axes[1], "cl_error", CL_TARGET, "lift: |cL - 0.009401|")):
        for rows, style, label in ((adapted, "o-", "adapted (Metrica, on the CAD model)"),
                                   (uniform, "s--", "uniform (gmsh)")):
            ax.loglog([r["vertices"] for r in rows], [max(r[key], 1e-7) for r in rows], style, label=label)
        ax.axhline(bound, color="gray", lw=0.8, ls=":")
        ax.set_xlabel("vertices")
        ax.set_title(title)
        ax.grid(True, which="both", lw=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Schäfer-Turek 3D-1Z (Re = 20), FreeFEM P2-P1")
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print(f"\nwrote {a.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
