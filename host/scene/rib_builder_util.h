// rib_builder_util.h: small conversions the RibBuilder's files share.
#pragma once
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "cl/include/compat.h"

namespace rd {

// A plane (a point, its normal) moved by m.
std::array<glm::vec3, 2> transformPlane(const glm::mat4& m,
                                        const std::array<glm::vec3, 2>& p);

inline rt_float4 f4(float x, float y, float z, float w = 0.0f) { return {x, y, z, w}; }
inline rt_float4 f4(const glm::vec3& v, float w = 0.0f) { return {v.x, v.y, v.z, w}; }

// RIB matrices are written row-major for row vectors (p' = p M); glm uses column vectors,
// so the same 16 numbers read column-major are already the transposed, glm-ready matrix.
inline glm::mat4 ribMatrix(const float m[16]) { return glm::make_mat4(m); }

inline glm::vec3 xformPoint(const glm::mat4& m, const glm::vec3& p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
}

inline bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace rd
