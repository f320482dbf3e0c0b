# SPDX-License-Identifier: BSD-3-Clause
"""Cuts a CalculiX .frd down to a fuzzing seed: the header, the first 20 nodes, the first
element (when its nodes are among them) and the first two result blocks restricted to those
nodes. Usage: cut_frd.py IN.frd OUT.frd"""
import sys

NODES = 20


def main(src_path, dst_path):
    src = open(src_path, errors="replace").read().splitlines()
    out, i = [], 0
    while i < len(src) and not src[i].startswith("    2C"):
        out.append(src[i])
        i += 1
    out.append("    2C%26d%37d" % (NODES, 1))
    i += 1
    nodes = []
    while i < len(src) and src[i].startswith(" -1"):
        if len(nodes) < NODES:
            nodes.append(src[i])
        i += 1
    out += nodes + [" -3"]
    while i < len(src) and not src[i].startswith("    3C"):
        i += 1
    out.append("    3C%26d%37d" % (1, 1))
    i += 1
    element = [src[i]]
    i += 1
    while i < len(src) and src[i].startswith(" -2"):
        element.append(src[i])
        i += 1
    out += element + [" -3"]
    blocks = 0
    while i < len(src) and blocks < 2:
        if src[i].startswith("  100C"):
            while i < len(src) and not src[i].startswith(" -1"):
                out.append(src[i])
                i += 1
            while i < len(src) and src[i].startswith(" -1"):
                if int(src[i][3:13]) <= NODES:
                    out.append(src[i])
                i += 1
            out.append(" -3")
            blocks += 1
        i += 1
    out.append(" 9999")
    open(dst_path, "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
