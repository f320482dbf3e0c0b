# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch: the one-click proxies Aniso Anisotropic Voronoi / Aniso Anisotropic Mesh and the
Examples/paraview_tensor_voronoi.py script.

Cube1 (6^3 grid, S = 1 + 9x) with its "Metric" point array as the field: 100 cells whose
shrunk volumes sum to 0.8^3 of the unit box, Stretch within the metric's [1, 10]; the mesh
companion has no inverted element and carries the quality field data. The example script
then renders the compressor (or the fallback) into a PNG that must not be blank.
Run: xvfb-run -a pvbatch --force-offscreen-rendering TestPluginComposite.py (env AV_PLUGIN).
"""
import os
import shutil
import subprocess
import tempfile

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin = os.environ.get("AV_PLUGIN")
assert plugin and os.path.exists(plugin), "set AV_PLUGIN to the built AnisoVoronoi.so"
LoadPlugin(plugin, ns=globals())

source = AnisoAnalyticMetricSource(Preset=1, Resolution=6)  # Cube1 on [0, 1]^3
common = dict(Input=source, Tensors=["POINTS", "Metric"], FieldMode="Metric Field",
              NumberOfCells=100, TargetDimension=5, Iterations=10, SamplingIterations=10,
              SamplingWarmupIterations=0)
voronoi = AnisoAnisotropicVoronoi(ShrinkFactor=0.8, **common)
voronoi.UpdatePipeline()
cells = servermanager.Fetch(voronoi)
cd = cells.GetCellData()
n = cells.GetNumberOfCells()
total = sum(cd.GetArray("Measure").GetTuple1(c) for c in range(n))
lo, hi = cd.GetArray("Stretch").GetRange()
print("composite: %d cells, shrunk volume %.12g, stretch %.3f..%.3f" % (n, total, lo, hi))
assert n == 100, n
assert {int(cd.GetArray("SiteId").GetTuple1(c)) for c in range(n)} == set(range(100))
assert abs(total - 0.8 ** 3) < 1e-9, total
# Cube1: S = 1 + 9x in [1, 10]; 100 sites spread over x, so the range is wide.
assert 1.0 - 1e-9 <= lo < 2.5 and 7.0 < hi <= 10.0 + 1e-9, (lo, hi)
fd = cells.GetFieldData()
for name in ("L_avg", "L_max", "MetricScale", "RelativeVolumeError"):
    assert fd.GetArray(name) is not None, name
assert fd.GetArray("RelativeVolumeError").GetTuple1(0) < 1e-9
assert 0 < fd.GetArray("L_avg").GetTuple1(0) <= fd.GetArray("L_max").GetTuple1(0)
faces = servermanager.Fetch(voronoi, idx=1)
assert faces.GetCellData().GetArray("Stretch") is not None
assert faces.GetCellData().GetArray("FaceKind") is not None
energy = servermanager.Fetch(voronoi, idx=2)
# 10 iterations, then on to convergence (MaxIterations 500): initial state + at least 10
assert 11 <= energy.GetNumberOfRows() <= 501, energy.GetNumberOfRows()

mesh = AnisoAnisotropicMesh(**common)
mesh.UpdatePipeline()
m = servermanager.Fetch(mesh)
mfd = m.GetFieldData()
print("mesh: %d tets, inverted %g, G_avg %.3f" % (
    m.GetNumberOfCells(), mfd.GetArray("inverted").GetTuple1(0), mfd.GetArray("G_avg").GetTuple1(0)))
assert m.GetNumberOfPoints() == 100 and m.GetNumberOfCells() > 100
assert mfd.GetArray("inverted").GetTuple1(0) == 0
assert mfd.GetArray("NumInverted").GetTuple1(0) == 0
assert mesh.RepairInverted == 1 and mesh.MaxRepairRounds == 10 and mesh.RepairNonManifold == 1
assert mfd.GetArray("NumInsertedSites").GetTuple1(0) == 0  # nothing inverted before either
assert 0.5 < mfd.GetArray("G_avg").GetTuple1(0) <= 1.0
assert m.GetCellData().GetArray("MinAngle") is not None
hist = servermanager.Fetch(mesh, idx=1)
assert sum(hist.GetValueByName(r, "Count").ToInt() for r in range(hist.GetNumberOfRows())) == \
    m.GetNumberOfCells()

# The example script, small, into a temporary PNG that must show several colors.
example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples",
                       "paraview_tensor_voronoi.py")
with tempfile.TemporaryDirectory() as tmp:
    png = os.path.join(tmp, "tensor_voronoi.png")
    pvbatch = shutil.which("pvbatch") or "/usr/bin/pvbatch"  # sys.executable is not pvbatch
    run = subprocess.run([pvbatch, "--force-offscreen-rendering", example, "--plugin",
                          plugin, "--cells", "150", "--iterations", "10", "--output", png],
                         capture_output=True, text=True, timeout=120)
    print(run.stdout[-2000:], run.stderr[-2000:])
    assert run.returncode == 0 and os.path.exists(png), run.returncode
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    image = reader.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3]
    colors, counts = np.unique(pixels, axis=0, return_counts=True)
    background = counts.max() / len(pixels)
    print("example PNG: %d distinct colors, background %.1f %%" % (len(colors), 100 * background))
    assert len(colors) > 20, len(colors)
    assert background < 0.97, background
    # Color-mapped cells: more than a handful of strongly saturated (non-grey) pixels.
    p = pixels.astype(int)
    saturated = (p.max(axis=1) - p.min(axis=1)) > 100
    assert saturated.sum() > 1000, saturated.sum()
print("TestPluginComposite: OK")
