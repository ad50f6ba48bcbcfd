// tessellate_nurbs.h: RI 3.2 NuPatch (non-uniform, optionally rational B-spline
// surfaces of any order) evaluated with Cox-de Boor basis functions, diced on a uniform
// (u,v) grid over [umin,umax] x [vmin,vmax], and trimmed by RI TrimCurve loops.
// st = (u,v) (the NURBS parameters themselves), faceIndex = the RI "uniform" index of
// the knot span the triangle lies in: spanV * (nu - uorder + 1) + spanU.
// Normals: dP/du x dP/dv. Trimming: a triangle is kept when its (u,v) centroid lies
// inside the trim loops by the even-odd rule (RI's default sense, "inside" kept; pass
// keepInside=false for the opposite sense); surfaces without loops are untouched.
// Triangles straddling a trim curve are split once into four before classification
// (halving the boundary error). Dropped triangles leave unreferenced vertices behind.
#pragma once
#include <string>
#include <vector>

#include "host/scene/tessellate_types.h"

namespace rd {

struct NuPatchInput {
    int nu = 0, uorder = 0;
    std::vector<float> uknot;  // nu + uorder values, non-decreasing
    float umin = 0, umax = 1;  // within [uknot[uorder-1], uknot[nu]], umin < umax
    int nv = 0, vorder = 0;
    std::vector<float> vknot;
    float vmin = 0, vmax = 1;
    bool rational = false;         // positions are "Pw" (x w, y w, z w, w) when true
    std::vector<float> positions;  // nu*nv*(3 or 4), u fastest
};

// RI TrimCurve arguments, verbatim.
struct TrimCurves {
    std::vector<int> ncurves;  // one per loop (nloops = ncurves.size())
    std::vector<int> order, n;  // one per curve
    std::vector<float> knot;    // sum(n + order)
    std::vector<float> min, max;  // one per curve
    std::vector<float> u, v, w;   // sum(n) homogeneous control points (u w, v w, w)
};

// Checks the knot vector: size n + order, order in [1, n], non-decreasing, finite and
// not all equal.
bool validateKnots(int n, int order, const std::vector<float>& knots, std::string* err);
bool validateNuPatch(const NuPatchInput& in, std::string* err);
bool validateTrimCurves(const TrimCurves& t, std::string* err);

// Evaluates the surface (with derivatives) at (u, v) in the valid parameter range.
SurfaceSample evalNuPatch(const NuPatchInput& in, float u, float v);

// Polylines (in u,v) of each trim loop, `segmentsPerSpan` samples per knot span.
bool trimLoopPolylines(const TrimCurves& t, int segmentsPerSpan,
                       std::vector<std::vector<glm::vec2>>& loops, std::string* err);
// Even-odd point-in-loops test.
bool insideLoops(const std::vector<std::vector<glm::vec2>>& loops, glm::vec2 p);

// NuPatch diced into segU x segV cells over [umin,umax] x [vmin,vmax], trimmed by `trim`
// when it is non-null and has loops.
bool tessellateNuPatch(const NuPatchInput& in, int segU, int segV, const TrimCurves* trim,
                       SurfaceMesh& out, std::string* err = nullptr,
                       bool keepInside = true);

}  // namespace rd
