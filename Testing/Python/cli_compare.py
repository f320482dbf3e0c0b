# SPDX-License-Identifier: BSD-3-Clause
"""Helpers of the CLI determinism and load tests: exact signatures of the CLI's output files
and their comparison (timing values aside)."""
import json
import os
import subprocess

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader

from vtk_test_checks import check, failures  # noqa: F401 (re-exported to the CLI tests)

CLI = os.path.join(os.environ["AV_BUILD"], "bin", "anisovoronoi")


def is_timing(name):
    return "Seconds" in name or name.endswith("_seconds") or name == "peak_rss_mb"


def read(path):
    r = vtkXMLPolyDataReader() if path.endswith(".vtp") else vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def array_bytes(a):
    """Every value of a VTK array, exactly (the raw bytes of numeric arrays)."""
    if a.IsA("vtkDataArray"):
        return vtk_to_numpy(a).tobytes()
    return repr([a.GetValue(i) for i in range(a.GetNumberOfValues())])


def dataset_signature(path):
    """{what: exact content} of every point, cell, field array, the points and the cells."""
    d = read(path)
    sig = {"points": array_bytes(d.GetPoints().GetData()) if d.GetPoints() else "",
           "npoints": d.GetNumberOfPoints(), "ncells": d.GetNumberOfCells()}
    if hasattr(d, "GetCells") and d.GetCells() is not None:
        sig["cells"] = array_bytes(d.GetCells().GetConnectivityArray())
    elif hasattr(d, "GetPolys"):
        for kind in ("Verts", "Lines", "Polys", "Strips"):
            sig[kind] = array_bytes(getattr(d, "Get" + kind)().GetConnectivityArray())
    for assoc, data in (("point", d.GetPointData()), ("cell", d.GetCellData()),
                        ("field", d.GetFieldData())):
        for i in range(data.GetNumberOfArrays()):
            a = data.GetAbstractArray(i)
            if assoc == "field" and is_timing(a.GetName()):
                continue
            sig["%s:%s" % (assoc, a.GetName())] = array_bytes(a)
    return sig


def run_cli(args, out):
    """Runs the CLI into `out`; True when it exits 0."""
    p = subprocess.run([CLI] + args + ["--output-dir", out, "--quiet"], capture_output=True,
                       text=True, timeout=600)
    check(p.returncode == 0, "%s exits 0 (stderr: %s)" % (args, p.stderr.strip()[-300:]))
    return p.returncode == 0


def compare_runs(label, a, b):
    names = sorted(os.listdir(a))
    check(names == sorted(os.listdir(b)), label + ": same output files")
    compared = 0
    for name in names:
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if name.endswith((".vtu", ".vtp")):
            sa, sb = dataset_signature(pa), dataset_signature(pb)
            check(sa.keys() == sb.keys(), "%s %s: same arrays" % (label, name))
            for key in sa:
                check(sa[key] == sb.get(key), "%s %s %s identical" % (label, name, key))
                compared += 1
        elif name == "report.json":
            ra, rb = json.load(open(pa)), json.load(open(pb))
            for key in ra:
                if not is_timing(key):
                    check(ra[key] == rb.get(key), "%s report %s: %r vs %r" %
                          (label, key, ra[key], rb.get(key)))
                    compared += 1
        else:
            check(open(pa, "rb").read() == open(pb, "rb").read(), "%s %s identical" % (label, name))
            compared += 1
    print("%s: %d arrays / values compared" % (label, compared))
    check(compared > 20, label + ": something was compared")
    return compared




def output_signature(folder):
    """{file: signature} of a CLI output folder, for comparing many runs at once."""
    sig = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if name.endswith((".vtu", ".vtp")):
            sig[name] = dataset_signature(path)
        elif name == "report.json":
            sig[name] = {k: v for k, v in json.load(open(path)).items() if not is_timing(k)}
        else:
            sig[name] = open(path, "rb").read()
    return sig
