"""The Hybrid Octree's VTK classes for Python (pvpython, pvbatch, or python3
with ParaView's VTK on the path).

    from hybrid_octree import vtkHybridOctreeFilter, vtkHybridOctreeVolumeMapper

All are ordinary VTK algorithms: connect them to VTK sources, readers and
renderers as in C++ (see the README).
"""
from .HybridOctreeFilters import (vtkHybridOctreeDepthImage, vtkHybridOctreeFilter, vtkHybridOctreePoints,
                                  vtkHybridOctreeZarrReader)
from .HybridOctreeRendering import vtkHybridOctreeVolumeMapper

__all__ = [
    "vtkHybridOctreeDepthImage",
    "vtkHybridOctreeFilter",
    "vtkHybridOctreePoints",
    "vtkHybridOctreeVolumeMapper",
    "vtkHybridOctreeZarrReader",
]
