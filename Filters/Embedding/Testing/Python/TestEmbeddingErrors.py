# SPDX-License-Identifier: BSD-3-Clause
"""vtkAnisoEmbedding on bad input: every case must fail RequestData with an error message a
user can act on (caught here through an ErrorEvent observer), never crash, and leave the
input untouched. Also: empty input gives an empty output without error, and an input of two
bodies that touch without shared points gets a warning and InputBodies = 2."""
import math
import sys

from anisovoronoi import vtkAnisoEmbedding
from vtkmodules.vtkCommonCore import vtkCommand, vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, VTK_TETRA, vtkUnstructuredGrid

failures = []


def tet_grid(metric_rows, comps=6, cells=((0, 1, 2, 3),), cell_type=VTK_TETRA):
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    for x in [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)]:
        p.InsertNextPoint(*x)
    g.SetPoints(p)
    for c in cells:
        g.InsertNextCell(cell_type, len(c), list(c))
    if metric_rows is not None:
        m = vtkDoubleArray()
        m.SetName("Metric")
        m.SetNumberOfComponents(comps)
        for row in metric_rows:
            m.InsertNextTuple(row)
        g.GetPointData().AddArray(m)
    return g


def run(grid, expect, dim=5):
    errors = []
    f = vtkAnisoEmbedding()
    f.AddObserver(vtkCommand.ErrorEvent, lambda obj, ev: errors.append(ev))
    f.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda obj, ev: None)
    f.SetInputData(grid)
    f.SetTargetDimension(dim)
    f.SetIterations(3)
    before = grid.GetPointData().GetNumberOfArrays()
    f.Update()
    if expect and not errors:
        failures.append("no error for: " + expect)
        print("FAILED: no error for", expect)
    if not expect and errors:
        failures.append("unexpected error")
    if grid.GetPointData().GetNumberOfArrays() != before:
        failures.append("input modified: " + expect)
    return f


I6 = [2, 2, 2, 0, 0, 0]
good = [I6] * 5
run(tet_grid(good), "")  # sanity: a valid case passes
run(vtkUnstructuredGrid(), "")  # empty in, empty out, no error
run(tet_grid(None), "missing metric array")
run(tet_grid([[2, 2, 2, 0]] * 5, comps=4), "4-component metric")
run(tet_grid(good[:4]), "metric with too few tuples")
run(tet_grid([I6, [math.nan, 2, 2, 0, 0, 0], I6, I6, I6]), "NaN in the metric")
run(tet_grid([I6, [-1, 2, 2, 0, 0, 0], I6, I6, I6]), "non-SPD metric")
run(tet_grid(good, cells=((0, 2, 1, 3), (1, 2, 3, 4))), "inverted element")
run(tet_grid(good, cells=((0, 1, 2, 2),)), "degenerate element")
run(tet_grid(good, cells=((0, 1, 2, 3, 4, 0, 1, 2),), cell_type=VTK_HEXAHEDRON), "hexahedron")
run(tet_grid(good), "target dimension not above the input dimension", dim=3)



def touching_tets(shared):
    """Tets (0,1,2,3) and (1,2,3,4) on the face (1,2,3): shared points, or copies of them."""
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    pts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    for x in pts:
        p.InsertNextPoint(*x)
    g.SetPoints(p)
    g.InsertNextCell(VTK_TETRA, 4, [0, 1, 2, 3])
    g.InsertNextCell(VTK_TETRA, 4, [1, 2, 3, 4] if shared else [5, 6, 7, 4])
    m = vtkDoubleArray()
    m.SetName("Metric")
    m.SetNumberOfComponents(6)
    for _ in pts:
        m.InsertNextTuple(I6)
    g.GetPointData().AddArray(m)
    return g


for shared, bodies in ((True, 1), (False, 2)):
    warnings = []
    f = vtkAnisoEmbedding()
    f.AddObserver(vtkCommand.WarningEvent, lambda obj, ev: warnings.append(ev))
    f.SetInputData(touching_tets(shared))
    f.SetTargetDimension(5)
    f.SetIterations(3)
    f.Update()
    field = f.GetOutput().GetFieldData().GetArray("InputBodies")
    got = (f.GetNumberOfInputBodies(), field.GetValue(0) if field else None)
    if got != (bodies, bodies) or (len(warnings) > 0) != (bodies > 1):
        failures.append("bodies: %s, %d warning(s), expected %d" % (got, len(warnings), bodies))
        print("FAILED: bodies", got, len(warnings), "expected", bodies)

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
