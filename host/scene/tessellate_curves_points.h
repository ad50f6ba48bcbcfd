// tessellate_curves_points.h: RI 3.2 Curves ("linear"/"cubic", with the current v basis
// and vstep, "nonperiodic"/"periodic") as flat ribbons and Points as camera-facing discs.
// Ribbons: u runs across the width (0 at P - side*w/2, 1 at P + side*w/2), v along the
// whole curve in [0,1]; st = (u,v); faceIndex = the curve index. With "N" the ribbon
// lies perpendicular to N (its normal follows N); without it the ribbon faces the
// camera: its normal is the part of -viewDir orthogonal to the tangent. Widths come
// from "width" (varying) or "constantwidth" (default 1). Points: `sides`-gon discs of
// diameter width facing -viewDir, faceIndex = the point index, st on the unit disc
// mapped to [0,1]^2. viewDir is the direction from the eye towards the primitive, in
// object space (for orthographic views, or per primitive for perspective).
#pragma once
#include <string>
#include <vector>

#include "host/scene/tessellate_patches.h"
#include "host/scene/tessellate_types.h"

namespace rd {

struct CurvesInput {
    bool cubic = false;
    bool periodic = false;
    std::vector<int> nvertices;
    std::vector<glm::vec3> P;
    CubicBasis vbasis = bezierBasis();  // cubic only; vbasis.step is vstep
    std::vector<float> width;           // varying, or empty
    float constantWidth = 1.0f;
    std::vector<glm::vec3> N;           // varying, or empty (camera-facing)
};

// Segments of one curve (cubic: patchCount rules with vstep; linear: n-1 / n), -1 when
// invalid; varying values per curve: segments+1 nonperiodic, segments periodic.
int curveSegments(bool cubic, int nverts, bool periodic, int vstep);
int curveVaryingCount(bool cubic, int nverts, bool periodic, int vstep);

// `samplesPerSegment` ribbon quads per curve segment (clamped to [1, 256]).
bool tessellateCurves(const CurvesInput& in, glm::vec3 viewDir, int samplesPerSegment,
                      SurfaceMesh& out, std::string* err = nullptr);

// Points: widths per point or empty (then constantWidth); sides clamped to [3, 64].
bool tessellatePoints(const std::vector<glm::vec3>& P, const std::vector<float>& width,
                      float constantWidth, glm::vec3 viewDir, int sides, SurfaceMesh& out,
                      std::string* err = nullptr);

}  // namespace rd
