// tessellate_patches.h: RI 3.2 Patch ("bilinear" 4 points, "bicubic" 16) and PatchMesh
// (nu uwrap nv vwrap) with the current Basis/step, positions as "P", "Pz" (height field:
// x,y are the mesh's parameters) or "Pw" (homogeneous). Each sub-patch is diced into a
// (nu x nv)-segment grid (appendGrid), st = (u,v) over the whole mesh (sub-patch k of
// nupatches covers u in [k/nupatches, (k+1)/nupatches], which is what RI's bilinear
// "varying" interpolation of the default st gives), faceIndex = the sub-patch index
// (u fastest), i.e. the "uniform" primvar index. Normals: dP/du x dP/dv.
#pragma once
#include <string>
#include <vector>

#include "host/scene/tessellate_types.h"

namespace rd {

// An RI cubic basis: P(t) = [t^3 t^2 t 1] * m * [P0 P1 P2 P3]^T, m[row][col] in the RI
// (row-major) order of RiBezierBasis etc.; `step` is the RI basis step.
struct CubicBasis {
    double m[4][4];
    int step;
};
CubicBasis bezierBasis();      // step 3
CubicBasis bSplineBasis();     // step 1
CubicBasis catmullRomBasis();  // step 1
CubicBasis hermiteBasis();     // step 2 (P0, T0, P1, T1)
CubicBasis powerBasis();       // step 4
// "bezier", "b-spline", "catmull-rom", "hermite", "power"; false for other names.
bool basisByName(const std::string& name, CubicBasis& out);
// An explicit RIB basis matrix (16 floats, row-major) with its step (must be >= 1).
bool basisFromMatrix(const float m16[16], int step, CubicBasis& out,
                     std::string* err = nullptr);
// The four basis weights (and, if `dw` is given, their derivatives) at t.
void basisWeights(const CubicBasis& b, float t, float w[4], float* dw = nullptr);

enum class PositionKind { P, Pz, Pw };
int positionFloats(PositionKind k);  // 3, 1 or 4

struct PatchMeshInput {
    bool bicubic = false;                  // "bicubic" / "bilinear"
    int nu = 0, nv = 0;                    // control points in u and v
    bool uperiodic = false, vperiodic = false;
    PositionKind kind = PositionKind::P;
    std::vector<float> positions;          // nu*nv*positionFloats(kind), u fastest
    CubicBasis ubasis = bezierBasis(), vbasis = bezierBasis();
};

// Sub-patches along one direction: bicubic (n-4)/step+1 nonperiodic (needs n >= 4 and
// (n-4) % step == 0), n/step periodic (needs n % step == 0); bilinear n-1 / n. Returns -1
// when n, step do not describe a valid mesh.
int patchCount(bool bicubic, int n, bool periodic, int step);

// PatchMesh. `segU`, `segV`: grid segments per sub-patch (clamped to [1, 4096]; total
// vertices capped by kMaxMeshVertices).
bool tessellatePatchMesh(const PatchMeshInput& in, int segU, int segV, SurfaceMesh& out,
                         std::string* err = nullptr);
// Patch "bilinear"/"bicubic": 4 or 16 control points (a 2x2 / 4x4 nonperiodic mesh).
bool tessellatePatch(const std::string& type, PositionKind kind,
                     const std::vector<float>& positions, const CubicBasis& ubasis,
                     const CubicBasis& vbasis, int segU, int segV, SurfaceMesh& out,
                     std::string* err = nullptr);

}  // namespace rd
