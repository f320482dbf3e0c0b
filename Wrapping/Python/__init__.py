"""AnisoVoronoi: anisotropic Voronoi diagrams and meshes through a high-d embedding.

All VTK classes of the project (filters, readers, writers) are importable from here:

    from anisovoronoi import vtkAnisoEmbedding
"""
try:
    from .AnisoVoronoiIO import *  # noqa: F401,F403
except ImportError:  # built without the IO module
    pass
from .AnisoVoronoiFilters import *  # noqa: F401,F403
