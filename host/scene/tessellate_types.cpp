// tessellate_types.cpp: the shared grid builder and helpers of the tessellators.
#include "host/scene/tessellate_types.h"

#include <algorithm>
#include <cmath>

namespace rd {

int clampSegments(int n, int lo) { return std::clamp(n, lo, kMaxGridSegments); }

static glm::vec3 sampleNormal(const SurfaceEval& eval, float u, float v) {
    SurfaceSample s = eval(u, v);
    glm::vec3 c = glm::cross(s.dpdu, s.dpdv);
    float scale = glm::length(s.dpdu) * glm::length(s.dpdv);
    if (glm::length(c) > 1e-6f * scale && scale > 0.0f) return glm::normalize(c);
    // Degenerate (pole, apex, collapsed edge): step a little towards the domain centre.
    for (float e : {1e-4f, 1e-3f, 1e-2f}) {
        float uu = u + (u < 0.5f ? e : -e), vv = v + (v < 0.5f ? e : -e);
        SurfaceSample t = eval(uu, vv);
        glm::vec3 d = glm::cross(t.dpdu, t.dpdv);
        float sc = glm::length(t.dpdu) * glm::length(t.dpdv);
        if (sc > 0.0f && glm::length(d) > 1e-6f * sc) return glm::normalize(d);
    }
    return glm::vec3(0.0f, 0.0f, 1.0f);
}

bool appendGrid(SurfaceMesh& out, int nu, int nv, const SurfaceEval& eval, int face,
                glm::vec2 st0, glm::vec2 st1) {
    nu = clampSegments(nu);
    nv = clampSegments(nv);
    long add = long(nu + 1) * long(nv + 1);
    if (long(out.mesh.p.size()) + add > kMaxMeshVertices) return false;
    int base = int(out.mesh.p.size());
    bool withNormals = out.mesh.n.size() == out.mesh.p.size();
    for (int j = 0; j <= nv; ++j) {
        float v = float(j) / float(nv);
        for (int i = 0; i <= nu; ++i) {
            float u = float(i) / float(nu);
            out.mesh.p.push_back(eval(u, v).p);
            if (withNormals) out.mesh.n.push_back(sampleNormal(eval, u, v));
            out.st.push_back(st0 + glm::vec2(u, v) * (st1 - st0));
        }
    }
    const auto& P = out.mesh.p;
    auto idx = [&](int i, int j) { return base + j * (nu + 1) + i; };
    auto emit = [&](int a, int b, int c) {
        glm::vec3 x = glm::cross(P[b] - P[a], P[c] - P[a]);
        float l = std::max({glm::length(P[b] - P[a]), glm::length(P[c] - P[a]),
                            glm::length(P[c] - P[b])});
        if (!(glm::length(x) > 1e-7f * l * l)) return;  // zero-area (pole/apex) triangle
        out.mesh.tris.insert(out.mesh.tris.end(), {a, b, c});
        out.faceIndex.push_back(face);
    };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            int a = idx(i, j), b = idx(i + 1, j), c = idx(i + 1, j + 1), d = idx(i, j + 1);
            emit(a, b, c);
            emit(a, c, d);
        }
    return true;
}

double meshArea(const TriMesh& m) {
    double a = 0.0;
    for (size_t k = 0; k + 2 < m.tris.size(); k += 3) {
        glm::dvec3 p0(m.p[m.tris[k]]), p1(m.p[m.tris[k + 1]]), p2(m.p[m.tris[k + 2]]);
        a += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    }
    return a;
}

}  // namespace rd
