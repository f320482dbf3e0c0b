// SPDX-License-Identifier: BSD-3-Clause
// A real CFD strain rate (OpenFOAM SRFSimpleFoam mixer, hexahedra) through tensor -> metric ->
// embedding -> sites -> restricted Voronoi diagram (see the header). The mixer is the case on
// which the sampler put two particles on one vertex and the RVD stopped being a partition.
#include "RealDataPipelineCheck.h"

int TestRealFlowPipeline(int, char*[])
{
  return av_test::RunRealDataPipelineCheck({ "real:mixer", 8750, 7200 }, 2000);
}
