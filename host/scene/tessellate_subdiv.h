// tessellate_subdiv.h: RI 3.2 SubdivisionMesh "catmull-clark", "loop" (triangles only)
// and "bilinear" (its patches, faceted: no vertex normals) with the tags "crease",
// "corner", "hole" and "interpolateboundary", through OpenSubdiv (Far): the control cage
// is refined uniformly to `level`, every refined vertex is projected to the limit
// surface (Far::PrimvarRefiner::Limit) with limit tangents, and the refined quads are
// split into triangles. faceIndex = the base (control) face each triangle descends
// from; normals = normalize(limit dP/du x dP/dv), wound like the face's vertex order.
// Subdivision surfaces have no global (u,v): st is (0,0). Without "interpolateboundary"
// the boundary follows OpenSubdiv's VTX_BOUNDARY_NONE rule; "interpolateboundary" [1]
// (or no int arg) = edges and corners, [2] = edges only. Values given per point (shader
// parameters, colours, texture coordinates) are refined with the cage on request. Built
// without OpenSubdiv (RD_HAVE_OPENSUBDIV undefined) the function returns false with an
// error.
#pragma once
#include <string>
#include <vector>

#include "host/scene/tessellate_types.h"

namespace rd {

struct SubdivInput {
    std::string scheme = "catmull-clark";
    std::vector<int> nvertices, vertices;  // per face: vertex count; concatenated indices
    std::vector<std::string> tags;
    std::vector<int> nargs;                // 2 per tag: int count, float count
    std::vector<int> intargs;
    std::vector<float> floatargs;
    std::vector<glm::vec3> P;
    // Other values refined with the mesh (shader parameters given per point): "vertex"
    // ones one per control vertex, projected to the limit like P; "varying" ones one
    // per control vertex too, refined linearly (RI varying on a subdivision mesh).
    std::vector<std::vector<glm::vec3>> vertexValues, varyingValues;
    // "facevarying" ones, one per face-vertex (an asset's texture coordinates):
    // linearly within each face, through an OpenSubdiv face-varying channel each, the
    // output's vertices split where faces give a vertex different values (a seam).
    std::vector<std::vector<glm::vec3>> faceVaryingValues;
};

constexpr int kMaxSubdivLevel = 8;

// Checks the topology and tag arguments (sizes, index ranges).
bool validateSubdiv(const SubdivInput& in, std::string* err);

// `level` is clamped to [0, kMaxSubdivLevel] and lowered further when the refined mesh
// would exceed kMaxMeshVertices.
// `values`, when given, receives in.vertexValues, in.varyingValues, then
// in.faceVaryingValues refined, one value per vertex of `out` (its vertices from the
// first this call adds; a vertex split at a facevarying seam has its vertex's vertex and
// varying values on each side).
bool tessellateSubdivisionMesh(const SubdivInput& in, int level, SurfaceMesh& out,
                               std::string* err = nullptr,
                               std::vector<std::vector<glm::vec3>>* values = nullptr);

}  // namespace rd
