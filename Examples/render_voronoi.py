# SPDX-License-Identifier: BSD-3-Clause
"""Render shrunken anisotropic Voronoi cells colored by the metric's stretch ratio
(the paper's Fig. 19/20 tensor-field visualization) to a PNG, headless.

usage (under X, e.g. xvfb-run -a):
    python3 render_voronoi.py OUTPUT_DIR [PNG]
OUTPUT_DIR is an `anisovoronoi --output-dir` folder (voronoi_faces.vtp, and mesh.vtu or
sites.vtp for the metric at the sites).
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper,
                                               vtkRenderer, vtkRenderWindow,
                                               vtkWindowToImageFilter)
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkIOImage import vtkPNGWriter
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (registers the OpenGL back end)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (scalar bar text)


def site_stretch(sites):
    """Stretch ratio sqrt(lmax/lmin) of the metric interpolated at each site."""
    m = sites.GetPointData().GetArray("Metric")
    if m is None:
        return None
    t = vtk_to_numpy(m)
    full = np.empty((t.shape[0], 3, 3))
    full[:, 0, 0], full[:, 1, 1], full[:, 2, 2] = t[:, 0], t[:, 1], t[:, 2]
    full[:, 0, 1] = full[:, 1, 0] = t[:, 3]
    full[:, 1, 2] = full[:, 2, 1] = t[:, 4]
    full[:, 0, 2] = full[:, 2, 0] = t[:, 5]
    ev = np.linalg.eigvalsh(full)
    flat = np.all(np.abs(t[:, [2, 4, 5]]) == 0, axis=1)  # 2D metrics: ignore the zero ZZ
    lo = np.where(flat, ev[:, 1], ev[:, 0])
    return np.sqrt(ev[:, 2] / np.maximum(lo, 1e-300))


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    folder = sys.argv[1]
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(folder, "voronoi.png")
    readers = {}
    for name in ("voronoi_faces", "sites"):
        r = vtkXMLPolyDataReader()
        r.SetFileName(os.path.join(folder, name + ".vtp"))
        r.Update()
        readers[name] = r.GetOutput()
    faces, sites = readers["voronoi_faces"], readers["sites"]
    if faces.GetNumberOfCells() == 0:
        print("render_voronoi: no Voronoi faces in", folder, file=sys.stderr)
        return 1
    site_id = vtk_to_numpy(faces.GetCellData().GetArray("SiteId")).astype(np.int64)
    # The dual mesh's points are the final sites (sampled ones, then any inserted by the
    # repair of inverted elements), numbered like the cells' SiteId; sites.vtp has the
    # sampled ones only.
    stretch = None
    mesh_file = os.path.join(folder, "mesh.vtu")
    if os.path.exists(mesh_file):
        r = vtkXMLUnstructuredGridReader()
        r.SetFileName(mesh_file)
        r.Update()
        if r.GetOutput().GetNumberOfPoints() > site_id.max():
            stretch = site_stretch(r.GetOutput())
    if stretch is None:
        stretch = site_stretch(sites)
    if stretch is not None and len(stretch) <= site_id.max():
        print("render_voronoi: the site files do not cover every Voronoi cell; coloring by "
              "site id", file=sys.stderr)
        stretch = None
    values = stretch[site_id] if stretch is not None else site_id.astype(float)
    arr = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float64), deep=True)
    arr.SetName("Stretch" if stretch is not None else "SiteId")
    faces.GetCellData().AddArray(arr)
    faces.GetCellData().SetActiveScalars(arr.GetName())

    lut = vtkLookupTable()
    lut.SetHueRange(0.667, 0.0)
    lut.SetTableRange(float(values.min()), float(max(values.max(), values.min() + 1e-9)))
    lut.Build()
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(faces)
    mapper.SetScalarModeToUseCellData()
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(lut.GetTableRange())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().EdgeVisibilityOn()
    actor.GetProperty().SetEdgeColor(0.15, 0.15, 0.15)
    actor.GetProperty().SetLineWidth(0.5)
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(arr.GetName())
    bar.SetNumberOfLabels(5)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.AddActor2D(bar)
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.GradientBackgroundOn()
    renderer.SetBackground2(0.75, 0.8, 0.9)
    # Look across the thinnest extent of the domain, so that the cells fill the picture.
    b = faces.GetBounds()
    size = [b[1] - b[0], b[3] - b[2], b[5] - b[4]]
    thin = size.index(min(size))
    center = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    direction = [0.35, 0.35, 0.35]
    direction[thin] = 1.0
    up = [0.0, 0.0, 0.0]
    up[(thin + 2) % 3] = 1.0
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(center)
    camera.SetPosition([center[i] + direction[i] for i in range(3)])
    camera.SetViewUp(up)
    renderer.ResetCamera()
    camera.Zoom(1.1)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(1200, 900)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(png)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("render_voronoi: wrote", png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
