//! Slab integration: surface triangles into the slabs between the slices of each brick.
