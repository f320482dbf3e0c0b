# SPDX-License-Identifier: BSD-3-Clause
"""Runs the README's main job (scripts/run-main.sh, setup skipped) into a temporary folder and
checks what it promises: every output file, a report with a valid dual mesh (no inverted or
non-manifold element left, the Voronoi cells partition the volume) and a rendered picture."""
import json
import os
import subprocess
import sys

root, build, out = sys.argv[1], sys.argv[2], sys.argv[3]
env = dict(os.environ, AV_SKIP_SETUP="1", AV_BUILD_DIR=build)
subprocess.run(["bash", os.path.join(root, "scripts", "run-main.sh"), out], check=True, env=env)
failures = []
for name in ("embedded.vtu", "sites.vtp", "voronoi.vtu", "voronoi_faces.vtp", "mesh.vtu",
             "energy.csv", "report.json", "voronoi.png"):
    if not os.path.isfile(os.path.join(out, name)) or os.path.getsize(os.path.join(out, name)) == 0:
        failures.append("missing or empty: " + name)
report = json.load(open(os.path.join(out, "report.json")))
if report["voronoi_cells"] < report["sites"]:
    failures.append("fewer Voronoi cells than sites")
if report["inverted"] != 0 or report["nonmanifold_faces"] != 0:
    failures.append("dual mesh has %d inverted elements, %d non-manifold faces"
                    % (report["inverted"], report["nonmanifold_faces"]))
if not report["rvd_volume_error"] < 1e-9:
    failures.append("RVD volume error %g" % report["rvd_volume_error"])
if os.path.getsize(os.path.join(out, "voronoi.png")) < 20000:  # a blank frame is ~5 KB
    failures.append("voronoi.png looks empty")
print(json.dumps({k: report[k] for k in ("L_avg", "sites", "voronoi_cells", "inserted_sites",
                                         "G_avg", "inverted")}))
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
