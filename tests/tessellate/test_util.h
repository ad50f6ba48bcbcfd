// test_util.h: shared checks for the tessellator tests.
#pragma once
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/tessellate_types.h"

namespace rd::test {

// Structural sanity: sizes agree, indices in range, normals unit and on the same side
// as the triangle winding.
inline void expectWellFormed(const SurfaceMesh& m, bool checkNormalWinding = true) {
    ASSERT_EQ(m.mesh.tris.size() % 3, 0u);
    ASSERT_EQ(m.faceIndex.size() * 3, m.mesh.tris.size());
    ASSERT_EQ(m.st.size(), m.mesh.p.size());
    if (!m.mesh.n.empty()) {
        ASSERT_EQ(m.mesh.n.size(), m.mesh.p.size());
    }
    for (int i : m.mesh.tris) ASSERT_TRUE(i >= 0 && i < int(m.mesh.p.size()));
    for (const auto& n : m.mesh.n) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
    if (!checkNormalWinding || m.mesh.n.empty()) return;
    int bad = 0;
    for (size_t k = 0; k < m.mesh.tris.size(); k += 3) {
        const auto& P = m.mesh.p;
        int a = m.mesh.tris[k], b = m.mesh.tris[k + 1], c = m.mesh.tris[k + 2];
        glm::vec3 g = glm::cross(P[b] - P[a], P[c] - P[a]);
        glm::vec3 n = m.mesh.n[a] + m.mesh.n[b] + m.mesh.n[c];
        if (glm::dot(g, n) <= 0.0f) ++bad;
    }
    EXPECT_EQ(bad, 0) << "triangles wound against their vertex normals";
}

}  // namespace rd::test
