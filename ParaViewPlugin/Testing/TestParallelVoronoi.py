# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch under MPI: the AnisoVoronoi chain split over processes.

Run: mpiexec -n 2 pvbatch --force-offscreen-rendering TestParallelVoronoi.py (env AV_PLUGIN;
also passes with one process). Cube1 (6^3 grid) -> Aniso Embedding (5D, 10 iterations) ->
Aniso Particle Sampler (80 sites) -> Aniso Restricted Voronoi (MergeBySite off).

Checks:
- the whole-mesh filters give exactly one copy when all pieces are gathered (80 sites, the
  whole embedded mesh), although every process computed them (the RVD asks for them whole);
- the gathered RVD equals a serial reference computed in this process with the plain VTK
  class on the same mesh and sites: same cells in the same order (site, element, measure,
  number of points) and the same total Measure (rel 1e-12);
- with n processes, process p produced exactly the cells of element block p (non-empty,
  disjoint): each process's piece is fetched on its own and carries its PieceNumber.
"""
import builtins
import os

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin = os.environ.get("AV_PLUGIN")
assert plugin and os.path.exists(plugin), "set AV_PLUGIN to the built AnisoVoronoi.so"
LoadPlugin(plugin, ns=globals())
from anisovoronoi import vtkAnisoRestrictedVoronoi  # noqa: E402  (plain VTK class)

nprocs = servermanager.ActiveConnection.GetNumberOfDataPartitions()
print("processes:", nprocs)

source = AnisoAnalyticMetricSource(Preset=1, Resolution=6)  # Cube1 on [0, 1]^3
embedding = AnisoEmbedding(Input=source, TargetDimension=5, Iterations=10)
sampler = AnisoParticleSampler(Input=embedding, NumberOfSites=80, Iterations=10)
voronoi = AnisoRestrictedVoronoi(Input=embedding, Sites=sampler, MergeBySite=0)

voronoi.UpdatePipeline()

# Gathered whole-mesh outputs: one copy only.
mesh = servermanager.Fetch(embedding)
sites = servermanager.Fetch(sampler)
ncells = mesh.GetNumberOfCells()
print("embedded mesh: %d tets, sites: %d" % (ncells, sites.GetNumberOfPoints()))
assert ncells == 6 * 5 ** 3, ncells  # 6 points per side, 6 tets per cube
assert sites.GetNumberOfPoints() == 80, sites.GetNumberOfPoints()

# Serial reference on the same inputs, in this process.
ref_filter = vtkAnisoRestrictedVoronoi()
ref_filter.SetInputData(0, mesh)
ref_filter.SetInputData(1, sites)
ref_filter.SetMergeBySite(False)
ref_filter.Update()
ref = ref_filter.GetOutput()

# Each process's piece, fetched one process at a time (Fetch(proxy, rank)), in rank order.
# (The all-process Fetch(voronoi) appends with vtkAppendFilter and came back with process 0's
# polyhedra only in ParaView 5.11; the data information counts all of them.)
pieces = [servermanager.Fetch(voronoi, p) for p in range(nprocs)]
assert voronoi.GetDataInformation(0).GetNumberOfCells() == \
    builtins.sum(g.GetNumberOfCells() for g in pieces)

def cells_of(grid):
    cd = grid.GetCellData()
    s, e, m = cd.GetArray("SiteId"), cd.GetArray("ElementId"), cd.GetArray("Measure")
    return [(int(s.GetTuple1(c)), int(e.GetTuple1(c)), m.GetTuple1(c),
             grid.GetCell(c).GetNumberOfPoints()) for c in range(grid.GetNumberOfCells())]


ref_cells = cells_of(ref)
par_cells = [c for g in pieces for c in cells_of(g)]
ref_total = builtins.sum(c[2] for c in ref_cells)
par_total = builtins.sum(c[2] for c in par_cells)
print("serial: %d cells, volume %.15g; gathered: %d cells, volume %.15g" % (
    len(ref_cells), ref_total, len(par_cells), par_total))
assert len(ref_cells) > ncells  # pieces: at least one per element, more where cells meet
assert len(par_cells) == len(ref_cells)
assert abs(par_total - ref_total) <= 1e-12 * ref_total
assert abs(ref_total - 1.0) < 1e-9
# Same pieces: order of the gather is rank 0, 1, ..., i.e. element order as in the serial run.
mismatch = [i for i, (a, b) in enumerate(zip(ref_cells, par_cells))
            if a[0] != b[0] or a[1] != b[1] or a[3] != b[3] or abs(a[2] - b[2]) > 1e-14]
assert not mismatch, "first differing cell %d: %s vs %s" % (
    mismatch[0], ref_cells[mismatch[0]], par_cells[mismatch[0]])

# Process p clipped exactly the elements [p*N/n, (p+1)*N/n), and each block is non-empty.
for p, g in enumerate(pieces):
    fd = g.GetFieldData()
    assert int(fd.GetArray("PieceNumber").GetTuple1(0)) == p
    assert int(fd.GetArray("NumberOfPieces").GetTuple1(0)) == nprocs
    elements = {c[1] for c in cells_of(g)}
    print("process %d: %d cells, elements %d..%d" % (
        p, g.GetNumberOfCells(), min(elements), max(elements)))
    assert elements == set(range(ncells * p // nprocs, ncells * (p + 1) // nprocs)), p
print("OK")
