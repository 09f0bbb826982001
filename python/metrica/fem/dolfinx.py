"""FEniCSx (dolfinx) meshes and P1 functions to and from metrica, for an
adaptive loop with a dolfinx solver (examples/python/fenicsx_loop.py):

    import metrica
    from metrica.fem import dolfinx as mfx

    mesh = metrica.box(8)
    for step in range(4):
        domain, regions, surfaces = mfx.to_dolfinx(mesh)
        uh = solve(domain, surfaces)                   # the user's solver
        u = mfx.vertex_values(uh)                      # in metrica's order
        metric = metrica.multiscale_metric(mesh, u, complexity=4000 * 2**step)
        mesh, report = metrica.adapt(mesh, metric)

Vertex order: a metrica.Mesh made here numbers its vertices as the points
given to dolfinx.mesh.create_mesh (dolfinx's "input" order,
`geometry.input_global_indices`); dolfinx reorders its own nodes, and
`vertex_values`/`set_vertex_values` go through that map so values are
never read in the wrong order. One process (MPI size 1): a distributed
dolfinx mesh is refused with InputError. P1 (affine) geometry only.
"""

import numpy as _np

import dolfinx as _dolfinx
import dolfinx.cpp as _cpp
import dolfinx.mesh as _mesh
import ufl as _ufl
from mpi4py import MPI as _MPI

from .. import InputError, Mesh

__all__ = ["from_dolfinx", "to_dolfinx", "vertex_map", "vertex_values", "set_vertex_values"]


def _cpp_mesh(domain):
    """The C++ mesh behind a dolfinx.mesh.Mesh (its attribute's name moved
    between dolfinx versions)."""
    for name in ("_cpp_object", "_mesh"):
        inner = getattr(domain, name, None)
        if inner is not None:
            return inner
    return domain


def _serial(domain, what):
    if domain.comm.size != 1:
        raise InputError(f"{what}: the dolfinx mesh is distributed over {domain.comm.size} processes; "
                         "metrica.fem.dolfinx works on one (gather the mesh first)")


def _cells(domain, what):
    """The cells' geometry nodes, (m, 4), after the checks."""
    if domain.topology.cell_name() != "tetrahedron":
        raise InputError(f"{what}: the dolfinx mesh has {domain.topology.cell_name()} cells (tetrahedra are adapted)")
    nodes = domain.geometry.dofmap.array
    if nodes.size != 4 * domain.topology.index_map(3).size_local:
        raise InputError(f"{what}: the geometry is not P1 (affine tetrahedra are read)")
    return nodes.reshape(-1, 4)


def vertex_map(domain):
    """For each dolfinx geometry node (row of `domain.geometry.x`), the
    metrica vertex it is: dolfinx's input index of the point."""
    _serial(domain, "vertex_map")
    index = _np.asarray(domain.geometry.input_global_indices, dtype=_np.int64)
    n = domain.geometry.x.shape[0]
    if index.shape != (n,) or not _np.array_equal(_np.sort(index), _np.arange(n)):
        raise InputError("vertex_map: the mesh's input indices are not a numbering of its nodes")
    return index


def from_dolfinx(domain, facet_tags=None, cell_tags=None, *, ridge_angle=None):
    """A metrica.Mesh of a dolfinx tetrahedral mesh: vertices in dolfinx's
    input order (vertex_map), tets in dolfinx's cell order, oriented;
    facet_tags (MeshTags of dimension 2) give the surface ids of their
    triangles (boundary faces left out get ids by the angles between
    faces, as metrica.Mesh does without triangles: ridge_angle), cell_tags
    (dimension 3) the region ids (0 for cells without a tag)."""
    _serial(domain, "from_dolfinx")
    nodes = _cells(domain, "from_dolfinx")
    order = vertex_map(domain)
    points = _np.empty_like(domain.geometry.x)
    points[order] = domain.geometry.x
    tets = order[nodes]
    # dolfinx orders a cell's vertices by their numbers, not by orientation.
    p = points[tets]
    volume = _np.einsum("ij,ij->i", _np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0])
    negative = volume < 0
    tets[negative, 2], tets[negative, 3] = tets[negative, 3], tets[negative, 2].copy()
    tet_ids = _np.zeros(len(tets), dtype=_np.int64)
    if cell_tags is not None:
        if cell_tags.dim != 3:
            raise InputError(f"from_dolfinx: cell_tags has dimension {cell_tags.dim} (3 expected)")
        tet_ids[cell_tags.indices] = cell_tags.values
    triangles = triangle_ids = None
    if facet_tags is not None:
        if facet_tags.dim != 2:
            raise InputError(f"from_dolfinx: facet_tags has dimension {facet_tags.dim} (2 expected)")
        facets = _np.asarray(facet_tags.indices, dtype=_np.int32)
        domain.topology.create_connectivity(2, 0)
        triangles = order[_cpp.mesh.entities_to_geometry(_cpp_mesh(domain), 2, facets, False)]
        triangle_ids = _np.asarray(facet_tags.values, dtype=_np.int64)
    return Mesh(points, tets, triangles, triangle_ids, tet_ids, ridge_angle=ridge_angle)


def to_dolfinx(mesh, comm=None):
    """The dolfinx mesh of a metrica.Mesh (on `comm`, default
    MPI.COMM_SELF) with its ids: (domain, cell_tags, facet_tags), MeshTags
    named "regions" (every cell) and "surfaces" (the boundary and internal
    surface triangles)."""
    comm = _MPI.COMM_SELF if comm is None else comm
    if comm.size != 1:
        raise InputError(f"to_dolfinx: comm has {comm.size} processes; metrica.fem.dolfinx works on one")
    element = _ufl.VectorElement("Lagrange", _ufl.tetrahedron, 1)
    domain = _mesh.create_mesh(comm, mesh.tets.astype(_np.int64), mesh.points, _ufl.Mesh(element))
    nodes = _cells(domain, "to_dolfinx")
    order = vertex_map(domain)
    # Cells: dolfinx's cell c is metrica's tet original_cell_index[c].
    original = _np.asarray(domain.topology.original_cell_index, dtype=_np.int64)
    cells = _np.arange(len(original), dtype=_np.int32)
    cell_tags = _mesh.meshtags(domain, 3, cells, mesh.tet_ids.astype(_np.int32)[original])
    cell_tags.name = "regions"
    # Facets by their topology vertices: metrica vertex -> geometry node ->
    # topology vertex (a P1 cell lists both in the same order).
    domain.topology.create_connectivity(3, 0)
    domain.topology.create_connectivity(2, 0)
    domain.topology.create_connectivity(2, 3)
    cell_vertices = domain.topology.connectivity(3, 0).array.reshape(-1, 4)
    vertex_of_node = _np.empty(domain.geometry.x.shape[0], dtype=_np.int32)
    vertex_of_node[nodes] = cell_vertices
    node_of = _np.empty_like(order)
    node_of[order] = _np.arange(len(order))
    triangles = vertex_of_node[node_of[mesh.triangles]]
    entities = _cpp.graph.AdjacencyList_int32(_np.ascontiguousarray(triangles, dtype=_np.int32))
    facet_tags = _mesh.meshtags_from_entities(domain, 2, entities, mesh.triangle_ids.astype(_np.int32))
    facet_tags.name = "surfaces"
    return domain, cell_tags, facet_tags


def _dofs_and_nodes(V, what):
    element = V.ufl_element()
    if element.family() not in ("Lagrange", "P", "Q", "CG") or element.degree() != 1:
        raise InputError(f"{what}: the function space is {element.family()} of degree {element.degree()} "
                         "(continuous P1 is read at the vertices)")
    domain = V.mesh
    nodes = _cells(domain, what)
    dofs = V.dofmap.list.array.reshape(nodes.shape)
    return dofs, nodes, V.dofmap.index_map_bs


def vertex_values(u):
    """A P1 dolfinx Function's values at the vertices, in metrica's order
    (vertex_map): (n,) for a scalar, (n, k) for a vector of k components."""
    _serial(u.function_space.mesh, "vertex_values")
    dofs, nodes, bs = _dofs_and_nodes(u.function_space, "vertex_values")
    values = u.x.array.real.reshape(-1, bs)
    by_node = _np.empty((u.function_space.mesh.geometry.x.shape[0], bs))
    by_node[nodes.ravel()] = values[dofs.ravel()]
    out = _np.empty_like(by_node)
    out[vertex_map(u.function_space.mesh)] = by_node
    return out[:, 0] if bs == 1 else out


def set_vertex_values(u, values):
    """Sets a P1 dolfinx Function from values at the vertices in metrica's
    order ((n,) or (n, k)): the inverse of vertex_values, e.g. to start a
    solve from the previous mesh's solution interpolated by metrica."""
    _serial(u.function_space.mesh, "set_vertex_values")
    dofs, nodes, bs = _dofs_and_nodes(u.function_space, "set_vertex_values")
    order = vertex_map(u.function_space.mesh)
    values = _np.asarray(values, dtype=_np.float64)
    if values.size != len(order) * bs or values.shape[0] != len(order):
        raise InputError(f"set_vertex_values: {values.shape} values for {len(order)} vertices of {bs} components")
    by_node = values.reshape(len(order), bs)[order]
    target = u.x.array.reshape(-1, bs)
    target[dofs.ravel()] = by_node[nodes.ravel()]
    u.x.scatter_forward()
