// tessellate_curves_points.cpp: ribbons for RI Curves and discs for RI Points.
#include "host/scene/tessellate_curves_points.h"

#include <algorithm>
#include <cmath>

namespace rd {
namespace {

bool fail(std::string* err, const std::string& msg) {
    if (err) *err = msg;
    return false;
}

glm::vec3 anyPerpendicular(glm::vec3 t) {
    glm::vec3 a = std::fabs(t.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(t, a));
}

}  // namespace

int curveSegments(bool cubic, int nverts, bool periodic, int vstep) {
    if (!cubic) return nverts >= 2 ? (periodic ? nverts : nverts - 1) : -1;
    return patchCount(true, nverts, periodic, vstep);
}

int curveVaryingCount(bool cubic, int nverts, bool periodic, int vstep) {
    int s = curveSegments(cubic, nverts, periodic, vstep);
    return s < 0 ? -1 : periodic ? s : s + 1;
}

bool tessellateCurves(const CurvesInput& in, glm::vec3 viewDir, int samplesPerSegment,
                      SurfaceMesh& out, std::string* err) {
    int step = in.cubic ? in.vbasis.step : 1;
    size_t totalV = 0, totalVar = 0;
    for (int n : in.nvertices) {
        if (n > (1 << 24)) return fail(err, "Curves: nvertices too large");
        int var = curveVaryingCount(in.cubic, n, in.periodic, step);
        if (var < 0) return fail(err, "Curves: nvertices does not fit the type, wrap and vstep");
        totalV += size_t(n);
        totalVar += size_t(var);
    }
    if (totalV != in.P.size()) return fail(err, "Curves: P does not match sum(nvertices)");
    if (!in.width.empty() && in.width.size() != totalVar)
        return fail(err, "Curves: width must have one value per varying point");
    if (!in.N.empty() && in.N.size() != totalVar)
        return fail(err, "Curves: N must have one value per varying point");
    if (!std::isfinite(in.constantWidth) || !std::isfinite(viewDir.x) ||
        !std::isfinite(viewDir.y) || !std::isfinite(viewDir.z))
        return fail(err, "Curves: non-finite width or view direction");
    samplesPerSegment = std::clamp(samplesPerSegment, 1, 256);
    double verts = 0;
    for (int n : in.nvertices)
        verts += 2.0 * (double(curveSegments(in.cubic, n, in.periodic, step)) * samplesPerSegment + 1);
    if (verts + double(out.mesh.p.size()) > double(kMaxMeshVertices))
        return fail(err, "Curves: too many vertices at this density");
    glm::vec3 view = glm::length(viewDir) > 0.0f ? glm::normalize(viewDir) : glm::vec3(0, 0, 1);

    size_t p0 = 0, var0 = 0;
    for (size_t c = 0; c < in.nvertices.size(); ++c) {
        int n = in.nvertices[c];
        int segs = curveSegments(in.cubic, n, in.periodic, step);
        int nvar = curveVaryingCount(in.cubic, n, in.periodic, step);
        auto cp = [&](int k) { return in.P[p0 + size_t(k % n)]; };
        // Centre line, tangent (d/dv over the whole curve), width and N at v in [0,1].
        auto centre = [&](float v, glm::vec3& pos, glm::vec3& tan, float& w, glm::vec3& nrm) {
            float x = std::clamp(v, 0.0f, 1.0f) * float(segs);
            int s = std::min(int(x), segs - 1);
            float t = x - float(s);
            pos = tan = glm::vec3(0.0f);
            if (in.cubic) {
                float wt[4], dw[4];
                basisWeights(in.vbasis, t, wt, dw);
                for (int k = 0; k < 4; ++k) {
                    pos += wt[k] * cp(s * step + k);
                    tan += dw[k] * cp(s * step + k);
                }
            } else {
                pos = (1 - t) * cp(s) + t * cp(s + 1);
                tan = cp(s + 1) - cp(s);
            }
            tan *= float(segs);
            size_t a = var0 + size_t(s), b = var0 + size_t((s + 1) % nvar);
            w = in.width.empty() ? in.constantWidth : (1 - t) * in.width[a] + t * in.width[b];
            nrm = in.N.empty() ? glm::vec3(0.0f) : (1 - t) * in.N[a] + t * in.N[b];
        };
        auto eval = [&](float u, float v) {
            glm::vec3 pos, tan, nrm;
            float w;
            centre(v, pos, tan, w, nrm);
            glm::vec3 dir = tan;
            if (!(glm::length(dir) > 1e-12f)) {  // stalled parameterisation
                glm::vec3 a, b, n2;
                float w2;
                centre(std::min(v + 1e-3f, 1.0f), a, tan, w2, n2);
                centre(std::max(v - 1e-3f, 0.0f), b, tan, w2, n2);
                dir = a - b;
            }
            dir = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0, 0, 1);
            glm::vec3 side = in.N.empty() ? glm::cross(view, dir) : glm::cross(dir, nrm);
            side = glm::length(side) > 1e-6f ? glm::normalize(side) : anyPerpendicular(dir);
            SurfaceSample s;
            s.p = pos + (u - 0.5f) * w * side;
            s.dpdu = w * side;
            s.dpdv = glm::length(tan) > 0.0f ? tan : dir;
            return s;
        };
        if (!appendGrid(out, 1, segs * samplesPerSegment, eval, int(c)))
            return fail(err, "Curves: too many vertices at this density");
        p0 += size_t(n);
        var0 += size_t(nvar);
    }
    return true;
}

bool tessellatePoints(const std::vector<glm::vec3>& P, const std::vector<float>& width,
                      float constantWidth, glm::vec3 viewDir, int sides, SurfaceMesh& out,
                      std::string* err) {
    if (!width.empty() && width.size() != P.size())
        return fail(err, "Points: width must have one value per point");
    sides = std::clamp(sides, 3, 64);
    if (double(P.size()) * (sides + 1) + double(out.mesh.p.size()) > double(kMaxMeshVertices))
        return fail(err, "Points: too many points");
    if (!(glm::length(viewDir) > 0.0f) || !std::isfinite(glm::length(viewDir)))
        return fail(err, "Points: bad view direction");
    glm::vec3 n = -glm::normalize(viewDir);
    glm::vec3 e1 = anyPerpendicular(n), e2 = glm::cross(n, e1);
    bool withN = out.mesh.n.size() == out.mesh.p.size();
    for (size_t i = 0; i < P.size(); ++i) {
        float r = 0.5f * (width.empty() ? constantWidth : width[i]);
        int centre = int(out.mesh.p.size());
        out.mesh.p.push_back(P[i]);
        out.st.emplace_back(0.5f, 0.5f);
        for (int k = 0; k < sides; ++k) {
            float a = 2.0f * float(M_PI) * float(k) / float(sides);
            float c = std::cos(a), s = std::sin(a);
            out.mesh.p.push_back(P[i] + r * (c * e1 + s * e2));
            out.st.emplace_back(0.5f + 0.5f * c, 0.5f + 0.5f * s);
        }
        if (withN) out.mesh.n.insert(out.mesh.n.end(), size_t(sides + 1), n);
        for (int k = 0; k < sides; ++k) {
            out.mesh.tris.insert(out.mesh.tris.end(),
                                 {centre, centre + 1 + k, centre + 1 + (k + 1) % sides});
            out.faceIndex.push_back(int(i));
        }
    }
    return true;
}

}  // namespace rd
