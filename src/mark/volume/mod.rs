//! Kinds drawing 3-D scalar fields (slices, isosurfaces, direct volume rendering) belong here.
