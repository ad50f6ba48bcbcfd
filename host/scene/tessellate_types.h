// tessellate_types.h: the mesh type shared by the host-side tessellators (quadrics,
// patches, NURBS, subdivision, general polygons, curves and points) plus the small grid
// helper they use. Everything is in object space.
//
// Normal convention (all tessellators): the per-vertex normal is the RI geometric normal
// normalize(dP/du x dP/dv) computed with the ordinary cross-product formula on the
// coordinates as given, and triangles are wound so that (b-a) x (c-a) points the same
// way. For the quadrics with positive radius/height and thetamax and increasing v this
// is the outward normal of RI 3.2 section 5.3; a negative radius or thetamax flips it
// (inside out), exactly as the formula does. Orientation/handedness flips ("inside",
// left-handed current transform) are the caller's job: reverse the winding and negate n.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host/scene/tessellate.h"

namespace rd {

struct SurfaceMesh {
    TriMesh mesh;                // p, n (per vertex, may be empty), tris
    std::vector<glm::vec2> st;   // per-vertex (s,t); RI defaults = (u,v)
    std::vector<int> faceIndex;  // per triangle: the RI face/patch it came from
};

// Caps that keep every tessellator's allocation bounded.
constexpr int kMaxGridSegments = 4096;       // per parametric direction
constexpr long kMaxMeshVertices = 1L << 24;  // per call

// Clamp a requested segment count into [lo, kMaxGridSegments].
int clampSegments(int n, int lo = 1);

// One surface sample: position and the two parametric derivatives.
struct SurfaceSample {
    glm::vec3 p, dpdu, dpdv;
};

// Appends an (nu+1) x (nv+1) grid over (u,v) in [0,1]^2 to `out`: vertices from `eval`,
// st = (s0 + u*(s1-s0), t0 + v*(t1-t0)), normals normalize(dPdu x dPdv) (re-evaluated a
// little inside the domain where the derivatives degenerate, e.g. at poles and apexes),
// two triangles per cell wound along dPdu x dPdv, zero-area triangles dropped, each
// tagged with `face`. Returns false (appending nothing) if the vertex cap would be hit.
using SurfaceEval = std::function<SurfaceSample(float u, float v)>;
bool appendGrid(SurfaceMesh& out, int nu, int nv, const SurfaceEval& eval, int face,
                glm::vec2 st0 = glm::vec2(0.0f), glm::vec2 st1 = glm::vec2(1.0f));

// Sum of triangle areas (used by tests and by callers choosing densities).
double meshArea(const TriMesh& m);

}  // namespace rd
