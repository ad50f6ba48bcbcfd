// tessellate_blobby.h: RiBlobby implicit surfaces (RI 3.2 section 5.6) made triangles.
// The code's primitive fields (constant, ellipsoid, segment blob) and operators (add,
// multiply, maximum, minimum, subtract, divide, negate, identity) give a field whose
// 0.5 level set is the surface, polygonised by marching tetrahedra over a grid that
// covers every bounded primitive.
#pragma once
#include <string>
#include <vector>

#include "host/scene/tessellate_types.h"

namespace rd {

// Each ellipsoid and segment blob's field is Wyvill's soft-object polynomial of its
// squared distance r^2 (from the centre, or from the segment, in the space of its matrix,
// over the segment's radius squared): 1 - 22/9 r^2 + 17/9 r^4 - 4/9 r^6 inside r < 1, so
// that a lone blob's surface is a sphere of radius 0.5 under its matrix. A repelling
// plane (opcode 1003) needs a depth file RayDrive does not read: its field is 0 and
// `note` says so, as it does when no primitive reaches anywhere (an empty surface).
// `cells` bounds the grid's cells per axis. Returns false with `err` when the surface
// would pass the vertex cap. With `weights`, also where each vertex's values come from
// (BlobbyLeafWeights).
struct BlobbyLeafWeights;
bool tessellateBlobby(const std::vector<int>& code, const std::vector<float>& floats,
                      int cells, SurfaceMesh& out, std::string* err, std::string* note,
                      BlobbyLeafWeights* weights = nullptr);

// RI gives a Blobby's vertex and varying values one a leaf (its primitive fields, in code
// order from 0, constants and repelling planes counted). A surface point's value is
// their mean weighted by each ellipsoid's and segment blob's own field there (as the
// blobs blend, so do their values; PRMan's appnote 31), the eight strongest where more
// reach it: for vertex i, the leaves leaf[start[i] .. start[i + 1]) with weights summing
// to 1. A point no blob reaches (a level set at the very edge of their reach) takes the
// plain mean of every leaf, or 0 past eight leaves.
struct BlobbyLeafWeights {
    std::vector<size_t> start;
    std::vector<int> leaf;
    std::vector<float> weight;
};

}  // namespace rd
