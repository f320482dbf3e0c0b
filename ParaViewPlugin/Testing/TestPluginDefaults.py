# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch: what the one-click proxies do with their defaults (issue 16).

- Gaussian2D from Aniso Analytic Metric Source through Aniso Anisotropic Voronoi, nothing
  set: Field Mode Automatic uses the "Metric" array as a metric, so the cells keep the
  source's stretch range [1, 3.84] (Tensor Field would square it), and the field-data string
  FieldMode says so.
- Aniso Anisotropic Mesh on the README's compressor (result.frd), nothing set: a valid mesh
  (no inverted element, no stalled repair).
- The stage filters' input domains: Aniso Particle Sampler / Restricted Voronoi / Restricted
  Delaunay accept an embedded mesh, not a mesh without a point metric.
Run: xvfb-run -a pvbatch --force-offscreen-rendering TestPluginDefaults.py (env AV_PLUGIN).
"""
import os

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin = os.environ.get("AV_PLUGIN")
assert plugin and os.path.exists(plugin), "set AV_PLUGIN to the built AnisoVoronoi.so"
LoadPlugin(plugin, ns=globals())

source = AnisoAnalyticMetricSource(Preset=0, Resolution=40)  # Gaussian2D
voronoi = AnisoAnisotropicVoronoi(Input=source, NumberOfCells=400, TargetDimension=3,
                                  Iterations=10, SamplingIterations=20)
voronoi.UpdatePipeline()
cells = servermanager.Fetch(voronoi)
lo, hi = cells.GetCellData().GetArray("Stretch").GetRange()
mode = cells.GetFieldData().GetAbstractArray("FieldMode").GetValue(0)
print("gaussian2d, defaults: %d cells, stretch %.3f..%.3f, FieldMode %s"
      % (cells.GetNumberOfCells(), lo, hi, mode))
assert voronoi.FieldMode == "Automatic", voronoi.FieldMode
assert mode.startswith("Metric Field"), mode
assert 1.0 - 1e-9 <= lo < 1.5 and 3.0 < hi <= 3.85, (lo, hi)

frd = "/usr/share/doc/calculix-cgx-examples/examples/result.frd"
assert os.path.exists(frd), frd + " is missing (package calculix-cgx-examples)"
reader = OpenDataFile(frd)
mesh = AnisoAnisotropicMesh(Input=reader)
mesh.UpdatePipeline()
fd = servermanager.Fetch(mesh).GetFieldData()
value = lambda name: fd.GetArray(name).GetTuple1(0)  # noqa: E731
print("compressor mesh, defaults: inverted %g (before repair %g), stalled %g, G_avg %.3f"
      % (value("inverted"), value("NumInvertedBeforeRepair"), value("RepairStalled"),
         value("G_avg")))
assert value("inverted") == 0 and value("RepairStalled") == 0

# Offered on an embedded mesh, not on a mesh without a point metric (a sphere with normals).
# (InputArrayDomain only sees component counts: a mesh with a metric passes it too, as 6 is
# a possible embedding dimension; RequestData then names the missing Embedding array.)
embedding = AnisoEmbedding(Input=source, TargetDimension=3, Iterations=2)
for name in ("AnisoParticleSampler", "AnisoRestrictedVoronoi", "AnisoRestrictedDelaunay"):
    proxy = getattr(servermanager.filters, name)()
    prop = proxy.SMProxy.GetProperty("Input")
    verdicts = []
    for producer in (Sphere(), embedding):
        producer.UpdatePipeline()
        prop.RemoveAllUncheckedProxies()
        prop.AddUncheckedInputConnection(producer.SMProxy, 0)
        verdicts.append(bool(prop.IsInDomains()))
    prop.RemoveAllUncheckedProxies()
    print("%s offered on: normals only %s, embedded mesh %s" % ((name,) + tuple(verdicts)))
    assert verdicts == [False, True], (name, verdicts)
print("TestPluginDefaults: OK")
