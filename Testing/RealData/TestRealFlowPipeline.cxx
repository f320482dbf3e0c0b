// SPDX-License-Identifier: BSD-3-Clause
// A real CFD strain rate (OpenFOAM simpleFoam squareBend, hexahedra) through tensor -> metric ->
// embedding -> sites -> restricted Voronoi diagram (see the header).
#include "RealDataPipelineCheck.h"

int TestRealFlowPipeline(int, char*[])
{
  return av_test::RunRealDataPipelineCheck({ "real:squarebend", 17061, 14000 }, 2000);
}
