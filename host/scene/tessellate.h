// tessellate.h: turns RenderMan surfaces without an exact intersector into triangles, in
// object space. Quadrics are diced finely enough that the chord error stays under a
// fraction of a pixel (viewpoint-aware, as RenderDrive did); issue 8 replaces them with
// exact quadric intersection.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rd {

struct TriMesh {
    std::vector<glm::vec3> p, n; // n empty when the mesh is faceted
    std::vector<int> tris;       // 3 indices per triangle
};

// A mesh with the per-vertex primitive variables shading can use; every vector other
// than p and tris may be empty (then: faceted, s,t = u,v, the attribute Cs and Os).
struct VertexData {
    std::vector<glm::vec3> p, n;
    std::vector<glm::vec2> st;
    std::vector<glm::vec3> cs, os;
    // Cs and Os when colours have more than three channels (ColorSamples n > 3, in the
    // first n; cs and os are then empty)
    using Channels = std::array<float, 15>;
    std::vector<Channels> csN, osN;
    std::vector<int> tris;
    // Primitive variables naming shader parameters, one value per vertex (float: x),
    // in object space; in the order RibBuilder::surfaceFor lists them (point_params.cpp)
    enum class Kind { Float, Color, Point, Vector, Normal };
    // A colour of n > 3 channels comes as ceil(n / 3) of them in a row, `piece` 0, 1, ...
    // holding its channels 3 piece .. 3 piece + 2 (rsl_abi.h, PER-POINT PARAMETERS).
    struct PointParam {
        std::string name;
        Kind kind = Kind::Float;
        int floats = 1;  // the variable's floats a value (a colour's: its channels)
        int piece = 0;
        std::vector<glm::vec3> v;
    };
    std::vector<PointParam> params;
};

// Segment count for a full circle of radius `radiusPixels` on screen so that the chord
// error stays below `tolPixels`; clamped to [8, 1024].
int circleSegments(float radiusPixels, float tolPixels);

// RI Sphere: radius, zmin, zmax, thetamax (degrees), with `nu` segments around a full
// turn and `nv` from pole to pole; partial sweeps get proportionally fewer.
// `st`, when given, receives the RI parametric (u, v) of every vertex.
TriMesh tessellateSphere(float radius, float zmin, float zmax, float thetamaxDeg, int nu,
                         int nv, std::vector<glm::vec2>* st = nullptr);

// Fan triangulation of a convex polygon given by vertex indices.
void triangulateConvex(const int* verts, int count, std::vector<int>& tris);

}  // namespace rd
