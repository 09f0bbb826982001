# Opens .msh files with gmsh's own library (libgmsh, through its C API) and
# prints, for each, its physical groups and its numbers of tetrahedra and
# triangles; exits 1 when the files disagree or gmsh refuses one.
#   python3 gmsh_reads_back.py A.msh B.msh ...
import ctypes
import sys

gmsh = ctypes.CDLL("libgmsh.so")
ierr = ctypes.c_int()


def call(name, *args):
    getattr(gmsh, name)(*args, ctypes.byref(ierr))
    if ierr.value != 0:
        sys.exit(f"gmsh: {name} failed on {sys.argv}")


def pairs(name, dim):
    p = ctypes.POINTER(ctypes.c_int)()
    n = ctypes.c_size_t()
    call(name, ctypes.byref(p), ctypes.byref(n), dim)
    return sorted((p[2 * i], p[2 * i + 1]) for i in range(n.value // 2))


def elements(element_type):
    tags = ctypes.POINTER(ctypes.c_size_t)()
    ntags = ctypes.c_size_t()
    nodes = ctypes.POINTER(ctypes.c_size_t)()
    nnodes = ctypes.c_size_t()
    call("gmshModelMeshGetElementsByType", element_type, ctypes.byref(tags), ctypes.byref(ntags),
         ctypes.byref(nodes), ctypes.byref(nnodes), -1, ctypes.c_size_t(0), ctypes.c_size_t(1))
    return ntags.value


call("gmshInitialize", 0, None, 0)
call("gmshOptionSetNumber", b"General.Terminal", ctypes.c_double(0))
seen = []
for path in sys.argv[1:]:
    call("gmshClear")
    call("gmshOpen", path.encode())
    summary = (pairs("gmshModelGetPhysicalGroups", -1), elements(4), elements(2))
    print(path, "physical groups", summary[0], "tets", summary[1], "triangles", summary[2])
    seen.append(summary)
call("gmshFinalize")
sys.exit(0 if all(s == seen[0] for s in seen) else 1)
