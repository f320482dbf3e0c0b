# SPDX-License-Identifier: BSD-3-Clause
"""Writes DIR/NAME.vtp (VTK XML polydata, inline binary) for each DIR/NAME.off (run with
pvpython). Polygons are kept as they are; the .off stays next to it for the VTK-free readers.

usage: pvpython off_to_vtp.py DIR NAME...
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter


def tokens(path):
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0]
            yield from line.split()


def read_off(path):
    t = tokens(path)
    if next(t) != "OFF":
        raise SystemExit(path + ": not an ASCII OFF file")
    nv, nf = int(next(t)), int(next(t))
    next(t)  # edge count, unused
    pts = np.array([float(next(t)) for _ in range(3 * nv)]).reshape(nv, 3)
    offsets, conn = [0], []
    for _ in range(nf):
        n = int(next(t))
        conn += [int(next(t)) for _ in range(n)]
        offsets.append(len(conn))
        # colors, if any, end the line; the OFF files used here have none
    if conn and (min(conn) < 0 or max(conn) >= nv):
        raise SystemExit(path + ": vertex index out of range")
    return pts, np.array(offsets), np.array(conn)


def main():
    out_dir, names = sys.argv[1], sys.argv[2:]
    for name in names:
        pts, offsets, conn = read_off(os.path.join(out_dir, name + ".off"))
        poly = vtkPolyData()
        p = vtkPoints()
        p.SetData(numpy_to_vtk(np.ascontiguousarray(pts), deep=1))
        poly.SetPoints(p)
        cells = vtkCellArray()
        cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=1),
                      numpy_to_vtkIdTypeArray(conn, deep=1))
        poly.SetPolys(cells)
        w = vtkXMLPolyDataWriter()
        w.SetInputData(poly)
        w.SetDataModeToBinary()
        w.SetFileName(os.path.join(out_dir, name + ".vtp"))
        if not w.Write():
            raise SystemExit("cannot write " + name + ".vtp")
        print("%s: %d points, %d polygons" % (name, poly.GetNumberOfPoints(),
                                              poly.GetNumberOfPolys()))


if __name__ == "__main__":
    main()
