"""AnisoVoronoi: anisotropic Voronoi diagrams and meshes through a high-d embedding.

All VTK classes of the project (one module per pipeline stage, plus the readers and
writers) are importable from here:

    from anisovoronoi import vtkAnisoEmbedding
"""
# SPDX-License-Identifier: BSD-3-Clause
from .AnisoVoronoiFiltersBackgroundMesh import *  # noqa: F401,F403
from .AnisoVoronoiFiltersMetric import *  # noqa: F401,F403
from .AnisoVoronoiFiltersEmbedding import *  # noqa: F401,F403
from .AnisoVoronoiFiltersQuality import *  # noqa: F401,F403
from .AnisoVoronoiFiltersVoronoi import *  # noqa: F401,F403
from .AnisoVoronoiFiltersSampling import *  # noqa: F401,F403
from .AnisoVoronoiFiltersDelaunay import *  # noqa: F401,F403
from .AnisoVoronoiFiltersPipelines import *  # noqa: F401,F403
from .AnisoVoronoiIO import *  # noqa: F401,F403
