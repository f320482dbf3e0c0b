#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Runs anisovoronoi-bench on every real case (or the ones named) and prints one Markdown table.

usage: scripts/real-data/bench-table.py [--bench build/bin/anisovoronoi-bench]
           [--data-dir DIR] [--threads 2] [--json FILE] [--cases rotor,mixer,...] [-- BENCH_ARGS]

Each case runs as its own process (`CASE --stage all`), so peak_rss_mb is that case's peak and
a failing case becomes a table row with its error instead of stopping the others. --json keeps
the raw JSON lines. Columns: the embedding's L_avg / L_max (§5.1, %), the dual mesh's G_avg and
smallest angle theta_min (§5.2), % bad (triangles: smallest angle < 30 deg; tets: smallest
dihedral < 15 deg), inverted elements and non-manifold faces after the repair, the RVD's
relative volume (area) error, the wall time of embedding + meshing and the peak memory.
"""
import argparse
import json
import os
import subprocess
import sys
import time

CASES = ["compressor", "rotor", "segmenttet", "cubef2f1", "hueeber1", "squarebend", "mixer",
         "turbine", "knot1", "mushroom", "fandisk"]


def fmt(v, spec):
    if v is None:
        return "–"
    if isinstance(v, str):
        return v
    return format(v, spec)


def run_case(args, name, extra):
    cmd = [args.bench, "real:" + name, "--stage", "all", "--threads", str(args.threads)]
    if args.data_dir:
        cmd += ["--data-dir", args.data_dir]
    cmd += extra
    start = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - start
    lines = [l for l in p.stdout.splitlines() if l.startswith("{")]
    if not lines:
        return {"case": "real:" + name, "error": (p.stderr.strip() or "no output")[:200]}, wall
    return json.loads(lines[-1]), wall


def row(r, wall):
    name = r["case"][len("real:"):]
    if "error" in r:
        return "| %s | – | – | – | – | – | – | – | – | – | – | – | %.0f | – |\n|  | error: %s |" % (
            name, wall, r["error"])
    elements = "tri" if "curvature" in r.get("mesh", "") else "tet"
    seconds = r.get("embed_seconds", 0.0) + r.get("mesh_seconds", 0.0)
    return "| %s | %s %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
        name, "{:,}".format(r["input_vertices"]), "/ {:,} {}".format(r["input_elements"], elements),
        "{:,}".format(r["sites"]), fmt(r.get("L_avg"), ".2f"), fmt(r.get("L_max"), ".1f"),
        fmt(r.get("G_avg"), ".3f"), fmt(r.get("theta_min"), ".2f"), fmt(r.get("pct_bad"), ".2f"),
        fmt(r.get("inverted"), "d"), fmt(r.get("nonmanifold_faces"), "d"),
        fmt(r.get("rvd_volume_error"), ".1e"), "%.1f" % seconds, fmt(r.get("peak_rss_mb"), ".0f"))


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--bench", default=os.path.join(root, "build", "bin", "anisovoronoi-bench"))
    ap.add_argument("--data-dir", default="")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json", default="")
    ap.add_argument("--cases", default=",".join(CASES))
    args = ap.parse_args(argv)
    print("| case | vertices / elements | sites | L_avg % | L_max % | G_avg | θ_min ° | % bad "
          "| inverted | non-manifold | RVD volume error | s | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    raw = []
    failed = 0
    for name in args.cases.split(","):
        r, wall = run_case(args, name, extra)
        raw.append(r)
        failed += "error" in r
        print(row(r, wall), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            f.write("".join(json.dumps(r) + "\n" for r in raw))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
