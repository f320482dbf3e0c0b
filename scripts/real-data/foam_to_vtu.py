# SPDX-License-Identifier: BSD-3-Clause
"""Converts the last time of an OpenFOAM case into the real-data inputs (run with pvpython).

Reads the internal mesh with ParaView's OpenFOAM reader (cell data interpolated to the
points), takes the point gradient of the velocity (vtkGradientFilter) and stores its
symmetric part, the strain rate S = (grad U + grad U^T) / 2, as a 6-component point array
"StrainRate" in VTK order XX YY ZZ XY YZ XZ, next to the velocity "U". Writes
  OUT.vtu  VTK XML, inline binary (appended mode does not read back with ParaView 5.11 here);
  OUT.frd  the same mesh and fields as a CalculiX ASCII result file (he8 elements, results
           SRATE and U), for the VTK-free benchmark (IO/Kernel/FrdReader).

usage: pvpython foam_to_vtu.py CASE_DIR VELOCITY_ARRAY OUT_BASENAME
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
from vtkmodules.vtkFiltersGeneral import vtkGradientFilter
from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

VTK_HEXAHEDRON = 12


def read_internal_mesh(case_dir):
    foam = os.path.join(case_dir, "case.foam")
    open(foam, "a").close()
    r = vtkOpenFOAMReader()
    r.SetFileName(foam)
    r.UpdateInformation()
    times = r.GetTimeValues()
    if times is None or times.GetNumberOfTuples() == 0:
        raise SystemExit(case_dir + ": no time directory written")
    r.EnableAllPatchArrays()
    for i in range(r.GetNumberOfPatchArrays()):
        name = r.GetPatchArrayName(i)
        r.SetPatchArrayStatus(name, 1 if name == "internalMesh" else 0)
    r.CreateCellToPointOn()
    r.DecomposePolyhedraOn()
    r.UpdateTimeStep(times.GetValue(times.GetNumberOfTuples() - 1))
    r.Update()
    block = r.GetOutput().GetBlock(0)
    if not isinstance(block, vtkUnstructuredGrid):
        raise SystemExit(case_dir + ": the internal mesh is not an unstructured grid")
    return block, times.GetValue(times.GetNumberOfTuples() - 1)


def strain_rate(grid, velocity):
    if grid.GetPointData().GetArray(velocity) is None:
        raise SystemExit("no point array " + velocity)
    g = vtkGradientFilter()
    g.SetInputData(grid)
    g.SetInputArrayToProcess(0, 0, 0, 0, velocity)  # points
    g.SetResultArrayName("GradU")
    g.Update()
    # rows: du/dx du/dy du/dz dv/dx dv/dy dv/dz dw/dx dw/dy dw/dz
    d = vtk_to_numpy(g.GetOutput().GetPointData().GetArray("GradU")).astype(np.float64)
    sym = np.column_stack((d[:, 0], d[:, 4], d[:, 8], 0.5 * (d[:, 1] + d[:, 3]),
                           0.5 * (d[:, 5] + d[:, 7]), 0.5 * (d[:, 2] + d[:, 6])))
    if not np.all(np.isfinite(sym)):
        raise SystemExit("the velocity gradient is not finite")
    s = numpy_to_vtk(np.ascontiguousarray(sym), deep=1)
    s.SetName("StrainRate")
    for c, n in enumerate(("XX", "YY", "ZZ", "XY", "YZ", "XZ")):
        s.SetComponentName(c, n)
    out = vtkUnstructuredGrid()
    out.SetPoints(grid.GetPoints())
    out.SetCells(grid.GetCellTypesArray(), grid.GetCells())
    u = grid.GetPointData().GetArray(velocity)
    out.GetPointData().AddArray(u)
    out.GetPointData().AddArray(s)
    return out


def write_vtu(grid, path):
    w = vtkXMLUnstructuredGridWriter()
    w.SetInputData(grid)
    w.SetDataModeToBinary()
    w.SetFileName(path)
    if not w.Write():
        raise SystemExit("cannot write " + path)


def e12(v):
    return "%12.5E" % v


def write_frd(grid, velocity, path, time_value):
    n, m = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    for c in range(m):
        if grid.GetCellType(c) != VTK_HEXAHEDRON:
            raise SystemExit("frd export: cell %d is not a hexahedron" % c)
    lines = ["    1C", "    1UDATE              real-data (AnisoVoronoi)"]
    lines.append("    2C%24d%37d" % (n, 1))
    pts = grid.GetPoints()
    for i in range(n):
        x = pts.GetPoint(i)
        lines.append(" -1%10d%s%s%s" % (i + 1, e12(x[0]), e12(x[1]), e12(x[2])))
    lines.append(" -3")
    lines.append("    3C%24d%37d" % (m, 1))
    ids = vtkIdList()
    for c in range(m):
        grid.GetCellPoints(c, ids)
        lines.append(" -1%10d%5d%5d%5d" % (c + 1, 1, 0, 1))
        lines.append(" -2" + "".join("%10d" % (ids.GetId(k) + 1) for k in range(8)))
    lines.append(" -3")
    pd = grid.GetPointData()
    blocks = (("SRATE", pd.GetArray("StrainRate"),
               (("SXX", 1, 1), ("SYY", 2, 2), ("SZZ", 3, 3), ("SXY", 1, 2), ("SYZ", 2, 3),
                ("SZX", 3, 1)), 4),
              ("U", pd.GetArray(velocity),
               (("U1", 1, 0), ("U2", 2, 0), ("U3", 3, 0)), 2))
    # value order of each block: VTK tuples are XX YY ZZ XY YZ XZ, the frd SZX is XZ
    for name, arr, comps, ctype in blocks:
        # 100C columns: value 13-24, node count 25-36, step 59-63, analysis 64-73, format 74+
        lines.append("  100CL  101%s%12d%22d%5d%-10s%2d" % (e12(time_value), n, 1, 1, "STATIC", 1))
        lines.append(" -4  %-8s%5d    1" % (name, len(comps)))
        for cname, i1, i2 in comps:
            lines.append(" -5  %-8s%5d%5d%5d%5d" % (cname, 1, ctype, i1, i2))
        nc = arr.GetNumberOfComponents()
        for i in range(n):
            t = arr.GetTuple(i)
            lines.append(" -1%10d%s" % (i + 1, "".join(e12(t[k]) for k in range(min(6, nc)))))
        lines.append(" -3")
    lines.append(" 9999")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    case_dir, velocity, base = sys.argv[1:]
    grid, t = read_internal_mesh(case_dir)
    out = strain_rate(grid, velocity)
    write_vtu(out, base + ".vtu")
    write_frd(out, velocity, base + ".frd", t)
    print("%s: %d points, %d cells, time %g" % (os.path.basename(base), out.GetNumberOfPoints(),
                                                out.GetNumberOfCells(), t))


if __name__ == "__main__":
    main()
