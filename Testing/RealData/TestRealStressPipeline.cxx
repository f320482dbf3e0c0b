// SPDX-License-Identifier: BSD-3-Clause
// A real 3D stress field (CalculiX rotor under centrifugal load, quadratic hexahedra) through
// tensor -> metric -> embedding -> sites -> restricted Voronoi diagram (see the header).
#include "RealDataPipelineCheck.h"

int TestRealStressPipeline(int, char*[])
{
  return av_test::RunRealDataPipelineCheck({ "real:rotor", 2656, 368 }, 1500);
}
