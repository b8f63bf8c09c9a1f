#!/usr/bin/python3
"""Regenerates the VTK-written test meshes with Debian's python3-vtk9 (run from this folder).

hex2_v42.vtk, hex2_v51.vtk   legacy ASCII, old CELLS lists and the 5.1 OFFSETS/CONNECTIVITY layout
hex2_ascii.vtu               XML, ascii arrays (VTK adds a compressor attribute and InformationKey children)
hex2_binary.vtu              XML, inline base64, UInt32 headers
tet5_uint64.vtu              XML, inline base64, UInt64 headers, with a point data array
hex2_zlib.vtu                XML, compressed inline data (unsupported: error test)
hex2_appended.vtu            XML, appended data (unsupported: error test)
"""
import vtk


def grid(points, cells, cell_type):
    g = vtk.vtkUnstructuredGrid()
    p = vtk.vtkPoints()
    p.SetDataTypeToDouble()
    for q in points:
        p.InsertNextPoint(*q)
    g.SetPoints(p)
    for c in cells:
        ids = vtk.vtkIdList()
        for i in c:
            ids.InsertNextId(i)
        g.InsertNextCell(cell_type, ids)
    return g


def xml(g, name, mode, compress=False, uint64=False):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetInputData(g)
    w.SetFileName(name)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary, "appended": w.SetDataModeToAppended}[mode]()
    if compress:
        w.SetCompressorTypeToZLib()
    else:
        w.SetCompressorTypeToNone()
    if uint64:
        w.SetHeaderTypeToUInt64()
    w.Write()


# 2 x 1 x 1 hexahedra, VTK_HEXAHEDRON order.
points = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1, 2)]
index = lambda x, y, z: 6 * z + 3 * y + x
hexes = [[index(*q) for q in [(i, 0, 0), (i + 1, 0, 0), (i + 1, 1, 0), (i, 1, 0),
                              (i, 0, 1), (i + 1, 0, 1), (i + 1, 1, 1), (i, 1, 1)]] for i in range(2)]
hex2 = grid(points, hexes, vtk.VTK_HEXAHEDRON)

legacy = vtk.vtkUnstructuredGridWriter()
legacy.SetInputData(hex2)
legacy.SetFileName("hex2_v51.vtk")
legacy.Write()
legacy.SetFileVersion(42)
legacy.SetFileName("hex2_v42.vtk")
legacy.Write()
xml(hex2, "hex2_ascii.vtu", "ascii")
xml(hex2, "hex2_binary.vtu", "binary")
xml(hex2, "hex2_zlib.vtu", "binary", compress=True)
xml(hex2, "hex2_appended.vtu", "appended")

# The unit cube as five tetrahedra.
cube = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
tets = [[0, 1, 3, 4], [2, 3, 1, 6], [5, 4, 6, 1], [7, 6, 4, 3], [1, 3, 4, 6]]
tet5 = grid(cube, tets, vtk.VTK_TETRA)
marker = vtk.vtkDoubleArray()
marker.SetName("marker")
for i in range(8):
    marker.InsertNextValue(i)
tet5.GetPointData().AddArray(marker)
xml(tet5, "tet5_uint64.vtu", "binary", uint64=True)
