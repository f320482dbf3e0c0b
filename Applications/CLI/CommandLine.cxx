// SPDX-License-Identifier: BSD-3-Clause
// The anisovoronoi command line: usage text, option parsing and range checks.
#include "CommandLine.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

namespace avcli
{
namespace
{
const char* const Usage = R"(usage: anisovoronoi [INPUT] --metric SPEC --output-dir DIR [options]
       anisovoronoi in.mesh --sol in.sol -o out.mesh [options]      (MMG style)

Anisotropic Voronoi cells and meshes from a Riemannian metric through a high-dimensional
embedding (AnisoVoronoi). INPUT: VTK legacy (.vtk) or XML (.vtu/.vtp/...), Medit .mesh or
.meshb (metric from --sol: .sol or .solb), CalculiX .frd, or a surface (.stl/.ply/.obj/.off). Non-simplex cells
(hexahedra, quadratic cells, ...) are split into simplices. INPUT may be omitted with
--metric preset:NAME: the preset's own mesh is generated.

metric SPEC:
  tensor:ARRAY     convert a tensor point/cell array (stress, strain rate, ...) into a metric
  metric:ARRAY     ARRAY already is an SPD metric (6 or 9 components)
  curvature        curvature metric of a triangle surface (paper Eq. 19)
  preset:NAME      analytic metric: gaussian2d cube1 cube2 cube3 sphere-cyl sphere-cos

options:
  --sol FILE               Medit .sol/.solb metric (tensor, or scalar size h) for a
                           .mesh/.meshb input; without --metric it is the metric
  --step N                 result step of a .frd input (0-based, default 0)
  --resolution N           mesh size for preset:NAME without INPUT (0 = paper size)
  --sites N                number of Voronoi cells / mesh vertices (default 2000; with --sol
                           and no --sites: the .sol's own count, its complexity / v_unit)
  --dim N                  embedding dimension (default 8)
  --iterations N           embedding iterations always run (default 50)
  --max-iterations N       then on to convergence, up to N in all (default 500; <= the above:
                           exactly --iterations)
  --solver S               embedding global step: auto (direct below 20,000 tet /
                           150,000 triangle mesh vertices),
                           direct or iterative (CG + algebraic multigrid, linear memory)
  --double-solve           embedding: CHOLMOD's double-precision solves (default: float copy)
  --element-metric M       embedding: each element's constant metric, mean (default: the
                           average of its vertex metrics) or edges (fits the paper's edge
                           lengths: lower embedding error, worse final meshes)
  --no-separate-bodies     embedding: bodies of the input with no shared point (a contact
                           assembly) stay touching (default: embedded apart, meshed apart)
  --sample-iterations N    particle L-BFGS iterations at the paper's kernel (default 150;
                           the paper: 50)
  --warmup-iterations N    particle iterations at a narrower kernel first (default 100;
                           0 with --sample-iterations 1500 or more: best quality)
  --no-features            no corner / feature-line sites (paper §4.1 sharp features)
  --feature-angle A        dihedral angle (degrees) above which an edge is a feature line
                           (default 30; 180 = none)
  --feature-patches ARRAY  surfaces: the feature lines are the borders between the patches of
                           this integer cell array (CAD faces, a .mesh file's triangle "Ref")
                           instead of the edges sharper than --feature-angle
  --feature-corners ARRAY  with --feature-patches: point array, nonzero points are corners
  --seed S                 random seed (default 1)
  --mu X                   regularization weight (default 100)
  --scale-free-regularizer  regularizer in units of the input's largest extent, so that mm
                           and m give the same embedding (default: in the input's own length
                           unit, as the paper prints it)
  --shrink F               shrink factor of the Voronoi cells (default 0.8; 1 = none)
  --tensor-as-metric       tensor: use eigenvalues as metric eigenvalues, not stretches
  --clamp                  tensor: clamp eigenvalues instead of taking absolute values
  --min-eigenvalue X       tensor: floor relative to the largest |eigenvalue| (default 1e-3)
  --max-anisotropy X       tensor: cap on the stretch ratio (default 25, 0 = none)
  --smooth N               tensor: log-Euclidean smoothing iterations (default 0)
  --max-stretch X          curvature: cap on the stretch ratio s2 / s1 (default 10, 0 = none;
                           the paper's Cyclide2 needs 29)

metric preparation (on for tensor:ARRAY; for metric:, preset: and --sol inputs only when one
of these options is given; lengths in the input's units, the metric first normalized so that
unit length is one of the --sites output cells):
  --hmin H, --hmax H       smallest / largest size (default 0 = no limit)
  --hgrad B                gradation: sizes grow by at most ~B per cell (default 1.3, MMG's)
  --min-cells-across K     volumes: at least K cells across thin parts of the domain
                           (default 1.25, 0 = off; lowered if they alone need more --sites)
  --no-gradation           no gradation
  --size-mode MODE         tensor (sizes from the tensor, default), uniform (shape only, equal
                           sizes) or blend (det M = det(M_tensor)^A, A from --size-blend)
  --size-blend A           blend exponent in [0, 1] (default 0.5)
  --prepare-metric         prepare a metric:, preset: or --sol metric with the defaults above

meshing:
  --refine N               volumes: remesh the domain with TetGen to about N vertices and
                           interpolate the input's point data onto it (a coarse FE mesh
                           cannot carry a fast-varying metric; default 0 = off)
  --adapt                  adapt the background mesh to the metric and --sites before the
                           embedding: split long metric edges, collapse short ones (edges of
                           at most --adapt-length output edges). Default: tensor: fields are
                           adapted when the mesh is coarser than the output (mean edge longer
                           than one output edge), other metrics keep their mesh
  --no-adapt               never adapt the background mesh
  --adapt-length L         the longest background edge, in output edges (in (0, 10],
                           default 1.5; implies --adapt)
  --no-repair              keep inverted mesh elements (default: insert sites at their dual
                           Voronoi vertices until none is left, paper §4.2)
  --repair-rounds N        insertion rounds at most (default 10)
  --no-repair-nonmanifold  do not repair faces shared by more than two mesh elements
                           (default: insert sites there too, so the mesh is a manifold)
  --no-valid-dual          keep a volume mesh that is still invalid after the repair (default:
                           replace it by the Delaunay tetrahedralization of its sites, carved
                           to the domain and flipped towards the metric's Delaunay criterion)
  --no-mesh-improvement    keep the dual mesh as it is (default: flips and vertex smoothing
                           raise its worst element, measured in the metric)
  --no-boundary-improvement  the mesh improvement leaves every boundary vertex and face of a
                           tet mesh as it is (default: planar patches exactly, smooth curved
                           ones within 0.5 % of the volume)
  --mean-smoothing N       sweeps of the mesh improvement over all movable vertices, each
                           raising the mean shape G of its elements without lowering the
                           worst (default 2, 0 = none)
  --keep-feature-sites     surfaces: the ODT steps keep the corner and feature-line sites on
                           the creases, and the edges along the creases are flipped into the
                           mesh (default: those sites move like the others)
  --no-boundary-notches    surfaces with an open boundary: leave the mesh's boundary vertices
                           that are off the input's boundary (default: the triangles that
                           close those notches are added)
  --improve-rounds N       site improvement rounds before the repair (default 1; 0 = the
                           paper's pipeline): ODT steps and sliver pushes, diagram redone
  --odt-iterations N       ODT steps per improvement round (default 3; 0 = sliver pushes only)
  --output-dir DIR         where the results go (created if missing)
  -o PATH                  PATH ending in .mesh or .meshb: write the anisotropic mesh there
                           and its metric next to it (.sol / .solb, Medit tensor order);
                           other PATHs: the same as --output-dir PATH
  --format medit           also write mesh.mesh and mesh.sol into the output directory
  --quiet                  no progress on stderr
  --help                   this text

writes into DIR: embedded.vtu, sites.vtp, voronoi.vtu, voronoi_faces.vtp, mesh.vtu,
energy.csv, report.json (the benchmark's keys; surfaces add hausdorff, self_intersections,
flipped, euler, boundary_loops against the input surface). With the repair, mesh.vtu and voronoi.vtu
use the final sites (sampled ones first, then inserted ones; sites.vtp: the sampled ones).
With only -o FILE.mesh, nothing but FILE.mesh and its .sol is written.

exit status: 0 success; 1 failure (unreadable or invalid input, a stage failed, a file
could not be written), with a one-line reason on stderr; 2 bad command line.
)";

bool HasMeditMeshExtension(const std::string& path)
{
  auto endsWith = [&path](const std::string& suffix)
  {
    if (path.size() < suffix.size())
      return false;
    for (std::size_t i = 0; i < suffix.size(); ++i)
    {
      const char c = path[path.size() - suffix.size() + i];
      if ((c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c) != suffix[i])
        return false;
    }
    return true;
  };
  return endsWith(".mesh") || endsWith(".meshb");
}

int ParseInt(const std::string& flag, const char* value)
{
  char* end = nullptr;
  const long v = std::strtol(value, &end, 10);
  if (!end || *end || v < -1000000000L || v > 1000000000L)
    Fail(flag + " expects an integer, got '" + value + "'", 2);
  return static_cast<int>(v);
}

double ParseDouble(const std::string& flag, const char* value)
{
  char* end = nullptr;
  const double v = std::strtod(value, &end);
  if (!end || *end || !std::isfinite(v))
    Fail(flag + " expects a number, got '" + value + "'", 2);
  return v;
}

/// Exits with status 2 when a required option is missing or a value is out of range.
void CheckOptions(const Options& o)
{
  if (o.Metric.empty())
    Fail("--metric SPEC is required (or --sol FILE with a .mesh INPUT; see --help)", 2);
  if (o.OutputDir.empty() && o.MeditOutput.empty())
    Fail("--output-dir DIR (or -o FILE.mesh) is required", 2);
  if (o.FormatMedit && o.OutputDir.empty())
    Fail("--format medit writes into --output-dir DIR, which is missing", 2);
  if (o.Input.empty() && o.Metric.rfind("preset:", 0) != 0)
    Fail("an INPUT file is required unless --metric preset:NAME", 2);
  if (o.Sites < 1)
    Fail("--sites must be at least 1", 2);
  if (o.HMin < 0 || o.HMax < 0 || (o.HMin > 0 && o.HMax > 0 && o.HMin > o.HMax))
    Fail("--hmin and --hmax must be >= 0 and --hmin <= --hmax", 2);
  if (!(o.HGrad > 1.0 && o.HGrad <= 1000.0))
    Fail("--hgrad must be in (1, 1000]", 2);
  if (!(o.MinCellsAcross >= 0 && o.MinCellsAcross <= 100))
    Fail("--min-cells-across must be in [0, 100]", 2);
  if (o.SizeMode != "tensor" && o.SizeMode != "uniform" && o.SizeMode != "blend")
    Fail("--size-mode must be tensor, uniform or blend", 2);
  if (!(o.SizeBlend >= 0 && o.SizeBlend <= 1))
    Fail("--size-blend must be in [0, 1]", 2);
  if (o.Dim < 3 || o.Dim > 20)
    Fail("--dim must be in [3, 20]", 2);
  if (o.Iterations < 0 || o.SampleIterations < 0 || o.WarmupIterations < 0 ||
    o.MaxIterations < 0)
    Fail("iteration counts must be >= 0", 2);
  if (o.ElementMetric != "edges" && o.ElementMetric != "mean")
    Fail("--element-metric must be edges or mean", 2);
  if (o.Solver != "auto" && o.Solver != "direct" && o.Solver != "iterative")
    Fail("--solver must be auto, direct or iterative", 2);
  if (!(o.FeatureAngle > 0 && o.FeatureAngle <= 180))
    Fail("--feature-angle must be in (0, 180]", 2);
  if (!o.FeatureCorners.empty() && o.FeaturePatches.empty())
    Fail("--feature-corners needs --feature-patches", 2);
  if (!(o.Shrink > 0 && o.Shrink <= 1))
    Fail("--shrink must be in (0, 1]", 2);
  if (!(o.AdaptLength > 0 && o.AdaptLength <= 10))
    Fail("--adapt-length must be in (0, 10]", 2);
  if (o.RepairRounds < 0 || o.RepairRounds > 1000)
    Fail("--repair-rounds must be in [0, 1000]", 2);
  if (o.ImproveRounds < 0 || o.ImproveRounds > 10)
    Fail("--improve-rounds must be in [0, 10]", 2);
  if (!(o.MaxStretch == 0.0 || o.MaxStretch >= 1.0))
    Fail("--max-stretch must be 0 (no cap) or >= 1", 2);
  if (o.MeanSmoothingSweeps < 0 || o.MeanSmoothingSweeps > 10)
    Fail("--mean-smoothing must be in [0, 10]", 2);
  if (o.OdtIterations < 0 || o.OdtIterations > 20)
    Fail("--odt-iterations must be in [0, 20]", 2);
}

} // namespace

Options ParseCommandLine(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> const char*
    {
      if (i + 1 >= argc)
        Fail(a + " needs a value", 2);
      return argv[++i];
    };
    if (a == "--help" || a == "-h")
    {
      std::cout << Usage;
      std::exit(0);
    }
    else if (a == "--metric")
      o.Metric = next();
    else if (a == "--sol")
      o.Sol = next();
    else if (a == "--output-dir")
      o.OutputDir = next();
    else if (a == "-o")
    {
      const std::string path = next();
      (HasMeditMeshExtension(path) ? o.MeditOutput : o.OutputDir) = path;
    }
    else if (a == "--format")
    {
      const std::string format = next();
      if (format != "medit" && format != "vtk")
        Fail("--format expects medit or vtk, got '" + format + "'", 2);
      o.FormatMedit = format == "medit";
    }
    else if (a == "--step")
      o.Step = ParseInt(a, next());
    else if (a == "--resolution")
      o.Resolution = ParseInt(a, next());
    else if (a == "--sites")
    {
      o.Sites = ParseInt(a, next());
      o.SitesGiven = true;
    }
    else if (a == "--min-cells-across")
      o.MinCellsAcross = ParseDouble(a, next());
    else if (a == "--hmin" || a == "--hmax" || a == "--hgrad" || a == "--size-blend")
    {
      const double v = ParseDouble(a, next());
      (a == "--hmin" ? o.HMin : a == "--hmax" ? o.HMax : a == "--hgrad" ? o.HGrad : o.SizeBlend) =
        v;
      o.PrepareAsked = true;
    }
    else if (a == "--size-mode")
    {
      o.SizeMode = next();
      o.PrepareAsked = true;
    }
    else if (a == "--no-gradation")
      o.Gradation = false;
    else if (a == "--prepare-metric")
      o.PrepareAsked = true;
    else if (a == "--dim")
      o.Dim = ParseInt(a, next());
    else if (a == "--iterations")
      o.Iterations = ParseInt(a, next());
    else if (a == "--max-iterations")
      o.MaxIterations = ParseInt(a, next());
    else if (a == "--solver")
      o.Solver = next();
    else if (a == "--sample-iterations")
      o.SampleIterations = ParseInt(a, next());
    else if (a == "--warmup-iterations")
      o.WarmupIterations = ParseInt(a, next());
    else if (a == "--no-features")
      o.Features = false;
    else if (a == "--feature-angle")
      o.FeatureAngle = ParseDouble(a, next());
    else if (a == "--feature-patches")
      o.FeaturePatches = next();
    else if (a == "--feature-corners")
      o.FeatureCorners = next();
    else if (a == "--element-metric")
      o.ElementMetric = next();
    else if (a == "--double-solve")
      o.DoubleSolve = true;
    else if (a == "--no-separate-bodies")
      o.SeparateBodies = false;
    else if (a == "--seed")
      o.Seed = ParseInt(a, next());
    else if (a == "--refine")
      o.Refine = ParseInt(a, next());
    else if (a == "--adapt")
      o.Adapt = "always";
    else if (a == "--no-adapt")
      o.Adapt = "never";
    else if (a == "--adapt-length")
    {
      o.AdaptLength = ParseDouble(a, next());
      o.Adapt = "always";
    }
    else if (a == "--smooth")
      o.Smooth = ParseInt(a, next());
    else if (a == "--mu")
      o.Mu = ParseDouble(a, next());
    else if (a == "--scale-free-regularizer")
      o.ScaleFreeRegularizer = true;
    else if (a == "--shrink")
      o.Shrink = ParseDouble(a, next());
    else if (a == "--min-eigenvalue")
      o.MinEigenvalue = ParseDouble(a, next());
    else if (a == "--max-anisotropy")
      o.MaxAnisotropy = ParseDouble(a, next());
    else if (a == "--max-stretch")
      o.MaxStretch = ParseDouble(a, next());
    else if (a == "--tensor-as-metric")
      o.TensorAsMetric = true;
    else if (a == "--clamp")
      o.Clamp = true;
    else if (a == "--quiet")
      o.Quiet = true;
    else if (a == "--no-repair")
      o.Repair = false;
    else if (a == "--repair-rounds")
      o.RepairRounds = ParseInt(a, next());
    else if (a == "--improve-rounds")
      o.ImproveRounds = ParseInt(a, next());
    else if (a == "--odt-iterations")
      o.OdtIterations = ParseInt(a, next());
    else if (a == "--repair-nonmanifold") // the default; kept so older scripts still run
      o.RepairNonManifold = true;
    else if (a == "--no-repair-nonmanifold")
      o.RepairNonManifold = false;
    else if (a == "--no-valid-dual")
      o.ValidDual = false;
    else if (a == "--no-mesh-improvement")
      o.ImproveMesh = false;
    else if (a == "--no-boundary-improvement")
      o.ImproveBoundary = false;
    else if (a == "--mean-smoothing")
      o.MeanSmoothingSweeps = ParseInt(a, next());
    else if (a == "--keep-feature-sites")
      o.KeepFeatureSites = true;
    else if (a == "--no-boundary-notches")
      o.CloseBoundaryNotches = false;
    else if (!a.empty() && a[0] == '-')
      Fail("unknown option " + a + " (see --help)", 2);
    else if (o.Input.empty())
      o.Input = a;
    else
      Fail("more than one INPUT given ('" + o.Input + "', '" + a + "')", 2);
  }
  // MMG style: a .sol given with a .mesh is the metric (the reader names it "Metric").
  if (o.Metric.empty() && !o.Sol.empty() && HasMeditMeshExtension(o.Input))
    o.Metric = "metric:Metric";
  CheckOptions(o);
  return o;
}

void Fail(const std::string& message, int code)
{
  std::cerr << "anisovoronoi: error: " << message << std::endl;
  std::exit(code);
}

} // namespace avcli
