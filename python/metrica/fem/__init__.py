"""Metrica beside finite-element libraries: meshes, ids and P1 fields moved
between their objects and metrica's.

    metrica.fem.dolfinx   FEniCSx (dolfinx 0.5 or newer), imported on its own
                          so that `import metrica` never needs dolfinx.
"""
