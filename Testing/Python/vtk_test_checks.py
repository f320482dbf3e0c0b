# SPDX-License-Identifier: BSD-3-Clause
"""Shared by the stage Python tests: check() that records failures instead of stopping, and
Messages, which collects an algorithm's error and warning events (quiet output). A stage test
puts this directory on sys.path (see add_to_path) and ends with finish(name)."""
import os
import sys

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


def finish(name):
    """Exit 1 with the failure count, else print that `name` passed."""
    if failures:
        print("%d failure(s)" % len(failures))
        sys.exit(1)
    print("%s passed" % name)


class Messages:
    """Collects error/warning messages of an algorithm and its executive (quiet output)."""

    def __init__(self, alg):
        self.errors, self.warnings = [], []
        for obj in (alg, alg.GetExecutive()):
            obj.AddObserver(vtkCommand.ErrorEvent, self.on_error)
            obj.AddObserver(vtkCommand.WarningEvent, self.on_warning)

    @calldata_type(VTK_STRING)
    def on_error(self, obj, event, msg):
        self.errors.append(msg)

    @calldata_type(VTK_STRING)
    def on_warning(self, obj, event, msg):
        self.warnings.append(msg)
