#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Scales the cell counts of every hex block of an OpenFOAM blockMeshDict.

The tutorials' meshes (squareBend: 112,000 cells) are finer than a test input needs and take
minutes to solve on two cores; a factor 0.5 gives 1/8 of the cells and the same geometry.

usage: scale_block_mesh.py system/blockMeshDict FACTOR
"""
import re
import sys


def main():
    path, factor = sys.argv[1], float(sys.argv[2])
    text = open(path).read()

    def scale(m):
        counts = [max(1, round(int(c) * factor)) for c in m.group(2).split()]
        return m.group(1) + "(" + " ".join(str(c) for c in counts) + ")"

    # hex (v0 ... v7) [zone] (nx ny nz)
    new, n = re.subn(r"(hex\s*\([\d\s]+\)\s*\w*\s*)\(\s*(\d+\s+\d+\s+\d+)\s*\)", scale, text)
    if n == 0:
        raise SystemExit(path + ": no hex block found")
    open(path, "w").write(new)


if __name__ == "__main__":
    main()
