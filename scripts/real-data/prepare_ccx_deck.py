#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Copies a CalculiX test deck and asks for nodal results in the .frd.

The decks of calculix-ccx-test only print to the .dat file; the real-data inputs need the
displacements and the stresses at the nodes (*NODE FILE U, *EL FILE S) in every step kept.
--keep-steps N drops the steps after the N-th (the rotor's frequency steps cost time and add
no stress field). --modes N lowers the number of eigenmodes of a *FREQUENCY step.

usage: prepare_ccx_deck.py IN.inp[.gz] OUT.inp [--keep-steps N] [--modes N]
"""
import argparse
import gzip
import re


def read_lines(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt", encoding="latin-1") as f:
        return f.read().splitlines()


def edit(lines, keep_steps, modes):
    out, step, skipping, after_frequency = [], 0, False, False
    for line in lines:
        key = line.strip().lower()
        if key.startswith("*step"):
            step += 1
            skipping = keep_steps > 0 and step > keep_steps
        if skipping:
            continue
        if after_frequency and not key.startswith("*") and not key.startswith("**"):
            # first data line of *FREQUENCY: the number of modes is its first field
            fields = line.split(",")
            fields[0] = " %d" % modes
            line = ",".join(fields)
            after_frequency = False
        if key.startswith("*end step"):
            # output requests go last in the step, so no step option comes after them
            out += ["*NODE FILE", "U", "*EL FILE", "S"]
        out.append(line)
        if modes > 0 and re.match(r"\*frequency\b", key):
            after_frequency = True
    if step == 0:
        raise SystemExit("no *STEP in the deck")
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("inp")
    p.add_argument("out")
    p.add_argument("--keep-steps", type=int, default=0)
    p.add_argument("--modes", type=int, default=0)
    a = p.parse_args()
    lines = edit(read_lines(a.inp), a.keep_steps, a.modes)
    with open(a.out, "w", encoding="latin-1") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
