# Writes box_sphere_{41,22}[_binary].msh from box_sphere.geo with gmsh's own
# library (libgmsh 4.8.4, Debian's libgmsh-dev, through its C API):
#   python3 write_msh.py box_sphere.geo
# then rename v41a.msh -> box_sphere_41.msh, v41b.msh -> box_sphere_41_binary.msh,
# v22a.msh -> box_sphere_22.msh, v22b.msh -> box_sphere_22_binary.msh.
import ctypes, sys
g = ctypes.CDLL("libgmsh.so.4.8")
ierr = ctypes.c_int()
g.gmshInitialize(0, None, 0, ctypes.byref(ierr))
def num(name, v): g.gmshOptionSetNumber(name.encode(), ctypes.c_double(v), ctypes.byref(ierr))
num("General.Terminal", 0)
g.gmshOpen(sys.argv[1].encode(), ctypes.byref(ierr)); assert ierr.value == 0
g.gmshModelMeshGenerate(3, ctypes.byref(ierr)); assert ierr.value == 0
def entities(dim):
    p = ctypes.POINTER(ctypes.c_int)(); n = ctypes.c_size_t()
    g.gmshModelGetEntities(ctypes.byref(p), ctypes.byref(n), dim, ctypes.byref(ierr))
    return [(p[2*i], p[2*i+1]) for i in range(n.value//2)]
print("volumes", entities(3)); print("surfaces", entities(2))
for out, ver, binary in [("v41a.msh",4.1,0),("v41b.msh",4.1,1),("v22a.msh",2.2,0),("v22b.msh",2.2,1)]:
    num("Mesh.MshFileVersion", ver); num("Mesh.Binary", binary)
    g.gmshWrite(out.encode(), ctypes.byref(ierr)); assert ierr.value == 0
g.gmshFinalize(ctypes.byref(ierr))
