# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView GUI client, used as a new user does: open the compressor (.frd), Apply, add
"Aniso Anisotropic Voronoi", Apply with the defaults. Then, through the Python API: the
render view shows the cells colored by Stretch with one color bar (Stretch) and the Faces
output hidden; one energy chart view (Iteration on x, log y, the E_* series only); the
screenshot of the views matches the reference within a tolerance. Then "Aniso Anisotropic
Mesh" on the same reader opens one angle histogram view (bin centers in degrees as x, only
the counts as bars).

Apply is what pqApplyBehavior::showData does on a source's first Apply, through the same
server-manager calls (ShowInPreferredView for every output port with the active view,
AssignViewToLayout, hiding the input, the scalar bar of a scalar-colored representation):
Debian's ParaView 5.11 plays no Python test scripts (QtTesting without Python), so the
button itself cannot be clicked from a script. The proxies' XML hints, which decide the
picture, are read by exactly those calls.

Run by CTest through run_gui_test.py as `xvfb-run paraview --dr --script=THIS`; the script
writes its log and verdict (status.txt) into AV_OUTPUT and ends the client itself.
Environment: AV_PLUGIN (the plugin), AV_FRD (the .frd), AV_BASELINE (reference PNG),
AV_OUTPUT (folder for the log, the status file and the screenshot).
"""
import os
import sys
import traceback

from paraview.simple import *  # noqa: F401,F403
from paraview.modules.vtkRemotingViews import (vtkSMParaViewPipelineControllerWithRendering,
                                               vtkSMPVRepresentationProxy)

failures = []
OUT = os.environ["AV_OUTPUT"]
LOG = open(os.path.join(OUT, "log.txt"), "w")


def log(text):
    LOG.write(text + "\n")
    LOG.flush()


def check(cond, what):
    log(("ok:     " if cond else "FAILED: ") + what)
    if not cond:
        failures.append(what)


def finish():
    """The verdict for run_gui_test.py, then the end of the client with the same status."""
    log("TestGUIOneClick: %s" % ("OK" if not failures else "%d failure(s)" % len(failures)))
    LOG.close()
    with open(os.path.join(OUT, "status.txt"), "w") as f:
        f.write("FAILED\n" if failures else "OK\n")
    os._exit(1 if failures else 0)


def apply_first_time(source):
    """What the Apply button does on a source's first Apply (pqApplyBehavior::showData)."""
    controller = vtkSMParaViewPipelineControllerWithRendering()
    view = GetActiveView()
    current = view.SMProxy if view is not None else None
    layout = GetLayout().SMProxy
    for port in range(source.SMProxy.GetNumberOfOutputPorts()):
        preferred = controller.ShowInPreferredView(source.SMProxy, port, current)
        if preferred is None:
            continue
        controller.AssignViewToLayout(preferred, layout, 0)
        if preferred == current and "Input" in source.ListProperties():
            controller.Hide(source.Input.SMProxy, 0, preferred)  # replace_input (default)
        rep = preferred.FindRepresentation(source.SMProxy, port)
        if rep is not None and vtkSMPVRepresentationProxy.GetUsingScalarColoring(rep):
            vtkSMPVRepresentationProxy.SetScalarBarVisibility(rep, preferred, True)
        if current is None:
            current = preferred
    for v in GetViews():  # the GUI resets the display of the views it shows data in first
        if v.GetXMLName() == "RenderView":
            v.ResetCamera()
        Render(v)


def port_reps(view, proxy):
    """{output port: representation} of `proxy` in `view`."""
    out = {}
    for rep in view.Representations:
        prop = rep.SMProxy.GetProperty("Input")
        if prop is None or prop.GetNumberOfProxies() == 0:
            continue
        if prop.GetProxy(0) == proxy.SMProxy:
            out[prop.GetOutputPortForConnection(0)] = rep
    return out


def visible_scalar_bar_titles(view):
    titles = []
    for rep in view.Representations:
        if rep.GetXMLName() == "ScalarBarWidgetRepresentation" and rep.Visibility:
            titles.append(rep.Title)
    return titles


def compare_images(path, baseline):
    """Mean absolute difference and the share of very different pixels (numpy)."""
    import numpy as np
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def load(p):
        r = vtkPNGReader()
        r.SetFileName(p)
        r.Update()
        img = r.GetOutput()
        dims = img.GetDimensions()
        a = vtk_to_numpy(img.GetPointData().GetScalars()).astype(float)
        return a.reshape(dims[1], dims[0], -1)[:, :, :3]

    a, b = load(path), load(baseline)
    if a.shape != b.shape:
        return None, None
    d = np.abs(a - b)
    return d.mean(), float((d.max(axis=2) > 80).mean())


try:
    LoadPlugin(os.environ["AV_PLUGIN"], ns=globals())
    reader = OpenDataFile(os.environ["AV_FRD"])
    check(reader is not None and reader.GetXMLName() == "AnisoFRDReader", "the .frd opened")
    apply_first_time(reader)
    voronoi = AnisoAnisotropicVoronoi(Input=reader)  # every property at its default
    SetActiveSource(voronoi)
    apply_first_time(voronoi)

    views = GetViews()
    render = [v for v in views if v.GetXMLName() == "RenderView"]
    charts = [v for v in views if v.GetXMLName() != "RenderView"]
    check(len(render) == 1, "one render view")
    check(len(charts) == 1 and charts[0].GetXMLName() == "AnisoEnergyChartView",
          "one energy chart view: %s" % [v.GetXMLName() for v in charts])
    rv = render[0]
    reps = port_reps(rv, voronoi)
    check(0 in reps and reps[0].Visibility == 1, "Voronoi Cells shown in the render view")
    check(1 not in reps or reps[1].Visibility == 0, "Faces not shown by default")
    check(list(reps[0].ColorArrayName) == ["CELLS", "Stretch"],
          "cells colored by Stretch: %s" % list(reps[0].ColorArrayName))
    titles = visible_scalar_bar_titles(rv)
    check(titles == ["Stretch"], "one color bar, Stretch: %s" % titles)
    rr = port_reps(rv, reader)
    check(0 not in rr or rr[0].Visibility == 0, "the input is hidden (replaced by the cells)")
    fd = voronoi.GetCellDataInformation()
    check(fd.GetArray("ElementId") is None, "no ElementId array on the cells")

    if charts:
        cv = charts[0]
        creps = port_reps(cv, voronoi)
        check(list(creps.keys()) == [2], "the chart shows the Energy port: %s" % list(creps.keys()))
        if 2 in creps:
            cr = creps[2]
            check(cr.UseIndexForXAxis == 0 and cr.XArrayName == "Iteration",
                  "x axis is Iteration (%s, index %s)" % (cr.XArrayName, cr.UseIndexForXAxis))
            vis = dict(zip(cr.SeriesVisibility[0::2], cr.SeriesVisibility[1::2]))
            check(vis.get("Iteration") == "0" and vis.get("E_total") == "1",
                  "E_* plotted, Iteration not: %s" % vis)
        check(cv.LeftAxisLogScale == 1, "log y axis")

    # The screenshot of the views, as the user sees them, against the reference.
    shot = os.path.join(OUT, "gui-one-click.png")
    SaveScreenshot(shot, GetLayout(), ImageResolution=[1400, 700])
    check(os.path.exists(shot), "screenshot written: " + shot)
    baseline = os.environ.get("AV_BASELINE", "")
    if os.path.exists(baseline):
        mean, share = compare_images(shot, baseline)
        log("image difference: mean %s, share of pixels off by > 80: %s" % (mean, share))
        check(mean is not None and mean < 1.5 and share < 0.01,
              "screenshot matches the reference %s" % baseline)
    else:
        check(False, "reference image missing: %s" % baseline)

    # The mesh companion on the same reader: its histogram opens in one angle histogram view
    # with the bin centers (degrees) as x and only the counts as bars.
    SetActiveView(rv)
    mesh = AnisoAnisotropicMesh(Input=reader)
    SetActiveSource(mesh)
    before = len(GetViews())
    apply_first_time(mesh)
    hist = [v for v in GetViews() if v.GetXMLName() == "AnisoAngleHistogramView"]
    check(len(GetViews()) == before + 1 and len(hist) == 1, "one angle histogram view")
    if hist:
        hr = port_reps(hist[0], mesh).get(1)
        check(hr is not None and hr.UseIndexForXAxis == 0 and hr.XArrayName == "MinAngle",
              "histogram x axis is the bin centers in degrees")
        if hr is not None:
            vis = dict(zip(hr.SeriesVisibility[0::2], hr.SeriesVisibility[1::2]))
            check(vis == {"MinAngle": "0", "Count": "1"}, "only Count drawn as bars: %s" % vis)
            col = servermanager.Fetch(mesh, idx=1).GetColumnByName("MinAngle")
            check(col is not None and abs(col.GetValue(0) - 2.5) < 1e-12,
                  "bin centers in degrees (first 2.5)")
    mrep = port_reps(rv, mesh).get(0)
    check(mrep is not None and mrep.Visibility == 1, "the mesh shown in the render view")
except Exception:  # noqa: BLE001 - report and fail, never hang the GUI
    log(traceback.format_exc())
    failures.append("exception")
finish()
