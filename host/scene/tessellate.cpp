// tessellate.cpp: sphere dicing and polygon triangulation.
#include "tessellate.h"

#include <algorithm>
#include <cmath>

namespace rd {

int circleSegments(float radiusPixels, float tolPixels) {
    // The sagitta of a chord over angle 2*pi/n is r*(1 - cos(pi/n)) ~ r*pi^2/(2 n^2).
    if (!(radiusPixels > 0.0f)) return 8;
    float n = float(M_PI) * std::sqrt(radiusPixels / (2.0f * tolPixels));
    if (!std::isfinite(n)) return 1024;
    return std::clamp(static_cast<int>(std::ceil(n)), 8, 1024);
}

TriMesh tessellateSphere(float radius, float zmin, float zmax, float thetamaxDeg, int nu,
                         int nv, std::vector<glm::vec2>* st) {
    TriMesh m;
    float r = std::fabs(radius);
    if (r == 0.0f) return m;
    float lo = std::clamp(std::min(zmin, zmax) / r, -1.0f, 1.0f);
    float hi = std::clamp(std::max(zmin, zmax) / r, -1.0f, 1.0f);
    float phiMin = std::asin(lo), phiMax = std::asin(hi);
    float thetaMax = std::clamp(thetamaxDeg, -360.0f, 360.0f) * float(M_PI) / 180.0f;
    if (phiMax <= phiMin || thetaMax == 0.0f) return m;
    int su = std::max(3, int(std::ceil(nu * std::fabs(thetaMax) / (2 * M_PI))));
    int sv = std::max(2, int(std::ceil(nv * (phiMax - phiMin) / M_PI)));
    for (int j = 0; j <= sv; ++j) {
        float phi = phiMin + (phiMax - phiMin) * float(j) / float(sv);
        for (int i = 0; i <= su; ++i) {
            float theta = thetaMax * float(i) / float(su);
            glm::vec3 dir(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta),
                          std::sin(phi));
            m.p.push_back(radius * dir);
            m.n.push_back(radius < 0 ? -dir : dir);
            if (st) st->push_back({float(i) / float(su), float(j) / float(sv)});
        }
    }
    auto idx = [&](int i, int j) { return j * (su + 1) + i; };
    for (int j = 0; j < sv; ++j)
        for (int i = 0; i < su; ++i) {
            int a = idx(i, j), b = idx(i + 1, j), c = idx(i + 1, j + 1), d = idx(i, j + 1);
            // At a pole one triangle of the quad collapses to a line: leave it out.
            if (!(j == 0 && phiMin <= -float(M_PI) / 2 + 1e-6f))
                m.tris.insert(m.tris.end(), {a, b, c});
            if (!(j == sv - 1 && phiMax >= float(M_PI) / 2 - 1e-6f))
                m.tris.insert(m.tris.end(), {a, c, d});
        }
    return m;
}

void triangulateConvex(const int* verts, int count, std::vector<int>& tris) {
    for (int k = 1; k + 1 < count; ++k) tris.insert(tris.end(), {verts[0], verts[k], verts[k + 1]});
}

}  // namespace rd
