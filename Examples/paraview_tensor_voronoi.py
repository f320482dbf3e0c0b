# SPDX-License-Identifier: BSD-3-Clause
"""Anisotropic Voronoi cells of a stress tensor field in ParaView (paper Fig. 19/20 style).

Reads the CalculiX compressor result (Debian package calculix-cgx-examples), applies the
one-click "Aniso Anisotropic Voronoi" filter to its STRESS tensors and saves the shrunken
cells colored by the metric's stretch ratio. Written as a ParaView Python trace: in the GUI,
Tools > Start Trace while doing the same clicks records these calls. Without the .frd file the
analytic SphereCylindrical metric is used instead.

usage:
    xvfb-run -a pvbatch --force-offscreen-rendering paraview_tensor_voronoi.py \
        [--plugin AnisoVoronoi.so] [--cells 2000] [--iterations 50] [--output voronoi.png]
The plugin path may also come from the environment variable AV_PLUGIN.
"""
import argparse
import os

from paraview.simple import *  # noqa: F401,F403

FRD = "/usr/share/doc/calculix-cgx-examples/examples/result.frd"

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.environ.get("AV_PLUGIN"),
                    help="AnisoVoronoi.so (default: $AV_PLUGIN)")
parser.add_argument("--cells", type=int, default=2000, help="number of Voronoi cells")
parser.add_argument("--iterations", type=int, default=50, help="embedding iterations")
parser.add_argument("--input", default=FRD, help="CalculiX .frd result with STRESS")
parser.add_argument("--output", default="tensor_voronoi.png", help="PNG to write")
args = parser.parse_args()
if not args.plugin:
    parser.error("give --plugin or set AV_PLUGIN to the built AnisoVoronoi.so")
LoadPlugin(args.plugin, ns=globals())

# ---- trace starts here (what Tools > Start Trace records) ------------------------------
if os.path.exists(args.input):
    # File > Open result.frd ("CalculiX FRD Reader"), first step (the first vibration mode).
    source = CalculiXFRDReader(registrationName=os.path.basename(args.input), FileName=args.input)
    tensors, mode = ["POINTS", "STRESS"], "Tensor Field"
else:
    print("paraview_tensor_voronoi: %s not found, using the analytic SphereCylindrical metric"
          % args.input)
    source = AnisoAnalyticMetricSource(registrationName="SphereCylindrical", Preset=4,
                                       Resolution=12)
    tensors, mode = ["POINTS", "Metric"], "Metric Field"

# Filters > AnisoVoronoi > Aniso Anisotropic Voronoi (the run-main.sh settings).
voronoi = AnisoAnisotropicVoronoi(registrationName="AnisoAnisotropicVoronoi1", Input=source)
voronoi.Tensors = tensors
voronoi.FieldMode = mode
voronoi.NumberOfCells = args.cells
voronoi.TargetDimension = 8
voronoi.Iterations = args.iterations
voronoi.MaximumAnisotropy = 10.0
voronoi.MinimumEigenvalue = 0.1
voronoi.SmoothingIterations = 10
voronoi.ShrinkFactor = 0.7

renderView1 = GetActiveViewOrCreate("RenderView")
renderView1.ViewSize = [1000, 750]
renderView1.OrientationAxesVisibility = 0
voronoiDisplay = Show(OutputPort(voronoi, 0), renderView1, "UnstructuredGridRepresentation")
ColorBy(voronoiDisplay, ("CELLS", "Stretch"))
stretchLUT = GetColorTransferFunction("Stretch")
stretchLUT.ApplyPreset("Jet", True)
voronoiDisplay.RescaleTransferFunctionToDataRange(True, False)
voronoiDisplay.SetScalarBarVisibility(renderView1, True)
scalarBar = GetScalarBar(stretchLUT, renderView1)
scalarBar.Title = "Stretch"
scalarBar.ComponentTitle = ""

renderView1.ResetCamera()
camera = GetActiveCamera()
camera.Elevation(30)
camera.Azimuth(30)
renderView1.ResetCamera()
SaveScreenshot(args.output, renderView1, ImageResolution=[1000, 750])
# ---- trace ends here --------------------------------------------------------------------

cells = servermanager.Fetch(voronoi)
fd = cells.GetFieldData()
print("paraview_tensor_voronoi: %d cells, L_avg %.2f %%, L_max %.2f %%, stretch %.2f..%.2f -> %s"
      % (cells.GetNumberOfCells(), fd.GetArray("L_avg").GetTuple1(0),
         fd.GetArray("L_max").GetTuple1(0),
         *cells.GetCellData().GetArray("Stretch").GetRange(), args.output))
