// tessellate.h: turns RenderMan surfaces without an exact intersector into triangles, in
// object space. Quadrics are diced finely enough that the chord error stays under a
// fraction of a pixel (viewpoint-aware, as RenderDrive did); issue 8 replaces them with
// exact quadric intersection.
#pragma once
#include <vector>

#include <glm/glm.hpp>

namespace rd {

struct TriMesh {
    std::vector<glm::vec3> p, n; // n empty when the mesh is faceted
    std::vector<int> tris;       // 3 indices per triangle
};

// Segment count for a full circle of radius `radiusPixels` on screen so that the chord
// error stays below `tolPixels`; clamped to [8, 1024].
int circleSegments(float radiusPixels, float tolPixels);

// RI Sphere: radius, zmin, zmax, thetamax (degrees), with `nu` segments around a full
// turn and `nv` from pole to pole; partial sweeps get proportionally fewer.
TriMesh tessellateSphere(float radius, float zmin, float zmax, float thetamaxDeg, int nu,
                         int nv);

// Fan triangulation of a convex polygon given by vertex indices.
void triangulateConvex(const int* verts, int count, std::vector<int>& tris);

}  // namespace rd
