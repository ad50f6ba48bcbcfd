// tessellate_patches.cpp: basis matrices, sub-patch enumeration and evaluation of RI
// bilinear/bicubic patches and patch meshes (rational when given Pw).
#include "host/scene/tessellate_patches.h"

#include <cmath>

namespace rd {
namespace {

CubicBasis makeBasis(std::initializer_list<double> v, double scale, int step) {
    CubicBasis b{};
    int k = 0;
    for (double x : v) {
        b.m[k / 4][k % 4] = x * scale;
        ++k;
    }
    b.step = step;
    return b;
}

bool fail(std::string* err, const std::string& msg) {
    if (err) *err = msg;
    return false;
}

}  // namespace

CubicBasis bezierBasis() {
    return makeBasis({-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0}, 1.0, 3);
}
CubicBasis bSplineBasis() {
    return makeBasis({-1, 3, -3, 1, 3, -6, 3, 0, -3, 0, 3, 0, 1, 4, 1, 0}, 1.0 / 6.0, 1);
}
CubicBasis catmullRomBasis() {
    return makeBasis({-1, 3, -3, 1, 2, -5, 4, -1, -1, 0, 1, 0, 0, 2, 0, 0}, 0.5, 1);
}
CubicBasis hermiteBasis() {
    return makeBasis({2, 1, -2, 1, -3, -2, 3, -1, 0, 1, 0, 0, 1, 0, 0, 0}, 1.0, 2);
}
CubicBasis powerBasis() {
    return makeBasis({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, 1.0, 4);
}

bool basisByName(const std::string& name, CubicBasis& out) {
    if (name == "bezier") out = bezierBasis();
    else if (name == "b-spline" || name == "bspline") out = bSplineBasis();
    else if (name == "catmull-rom" || name == "catmullrom") out = catmullRomBasis();
    else if (name == "hermite") out = hermiteBasis();
    else if (name == "power") out = powerBasis();
    else return false;
    return true;
}

bool basisFromMatrix(const float m16[16], int step, CubicBasis& out, std::string* err) {
    if (step < 1) return fail(err, "Basis: step must be >= 1");
    for (int k = 0; k < 16; ++k) {
        if (!std::isfinite(m16[k])) return fail(err, "Basis: non-finite matrix entry");
        out.m[k / 4][k % 4] = m16[k];
    }
    out.step = step;
    return true;
}

void basisWeights(const CubicBasis& b, float t, float w[4], float* dw) {
    double T[4] = {double(t) * t * t, double(t) * t, t, 1.0};
    double dT[4] = {3.0 * t * t, 2.0 * t, 1.0, 0.0};
    for (int i = 0; i < 4; ++i) {
        double s = 0.0, ds = 0.0;
        for (int r = 0; r < 4; ++r) {
            s += T[r] * b.m[r][i];
            ds += dT[r] * b.m[r][i];
        }
        w[i] = float(s);
        if (dw) dw[i] = float(ds);
    }
}

int positionFloats(PositionKind k) {
    return k == PositionKind::P ? 3 : k == PositionKind::Pz ? 1 : 4;
}

int patchCount(bool bicubic, int n, bool periodic, int step) {
    if (n < 1 || n > (1 << 24)) return -1;
    if (!bicubic) {
        if (periodic) return n >= 2 ? n : -1;
        return n >= 2 ? n - 1 : -1;
    }
    if (step < 1) return -1;
    if (periodic) return (n % step == 0 && n >= 4) ? n / step : -1;
    if (n < 4 || (n - 4) % step != 0) return -1;
    return (n - 4) / step + 1;
}

bool tessellatePatchMesh(const PatchMeshInput& in, int segU, int segV, SurfaceMesh& out,
                         std::string* err) {
    int stepU = in.bicubic ? in.ubasis.step : 1, stepV = in.bicubic ? in.vbasis.step : 1;
    int npu = patchCount(in.bicubic, in.nu, in.uperiodic, stepU);
    int npv = patchCount(in.bicubic, in.nv, in.vperiodic, stepV);
    if (npu < 0) return fail(err, "PatchMesh: nu does not fit the type, wrap and ustep");
    if (npv < 0) return fail(err, "PatchMesh: nv does not fit the type, wrap and vstep");
    size_t nverts = size_t(in.nu) * size_t(in.nv);
    int nf = positionFloats(in.kind);
    if (in.positions.size() != nverts * size_t(nf))
        return fail(err, "PatchMesh: position array has the wrong length");
    for (float x : in.positions)
        if (!std::isfinite(x)) return fail(err, "PatchMesh: non-finite position");
    segU = clampSegments(segU);
    segV = clampSegments(segV);
    if (double(npu) * npv * (segU + 1) * (segV + 1) + double(out.mesh.p.size()) >
        double(kMaxMeshVertices))
        return fail(err, "PatchMesh: mesh too large at this density");

    // Homogeneous control points; Pz gets x,y from the mesh parameters.
    std::vector<glm::vec4> cv(nverts);
    for (int j = 0; j < in.nv; ++j)
        for (int i = 0; i < in.nu; ++i) {
            size_t k = size_t(j) * in.nu + i;
            const float* f = &in.positions[k * nf];
            if (in.kind == PositionKind::P) cv[k] = glm::vec4(f[0], f[1], f[2], 1.0f);
            else if (in.kind == PositionKind::Pw) cv[k] = glm::vec4(f[0], f[1], f[2], f[3]);
            else
                cv[k] = glm::vec4(in.nu > 1 ? float(i) / float(in.nu - 1) : 0.0f,
                                  in.nv > 1 ? float(j) / float(in.nv - 1) : 0.0f, f[0], 1.0f);
        }

    int order = in.bicubic ? 4 : 2;
    SurfaceMesh result = out;
    for (int pv = 0; pv < npv; ++pv)
        for (int pu = 0; pu < npu; ++pu) {
            glm::vec4 g[4][4];  // [row v][col u]
            for (int b = 0; b < order; ++b)
                for (int a = 0; a < order; ++a) {
                    int iu = (pu * stepU + a) % in.nu, iv = (pv * stepV + b) % in.nv;
                    g[b][a] = cv[size_t(iv) * in.nu + iu];
                }
            auto eval = [&](float u, float v) {
                float wu[4], dwu[4], wv[4], dwv[4];
                if (in.bicubic) {
                    basisWeights(in.ubasis, u, wu, dwu);
                    basisWeights(in.vbasis, v, wv, dwv);
                } else {
                    wu[0] = 1 - u, wu[1] = u, dwu[0] = -1, dwu[1] = 1;
                    wv[0] = 1 - v, wv[1] = v, dwv[0] = -1, dwv[1] = 1;
                }
                glm::vec4 h(0.0f), hu(0.0f), hv(0.0f);
                for (int b = 0; b < order; ++b)
                    for (int a = 0; a < order; ++a) {
                        h += wu[a] * wv[b] * g[b][a];
                        hu += dwu[a] * wv[b] * g[b][a];
                        hv += wu[a] * dwv[b] * g[b][a];
                    }
                SurfaceSample s;
                float w = h.w != 0.0f ? h.w : 1e-30f;
                s.p = glm::vec3(h) / w;
                // quotient rule: d(x/w) = (dx - p dw) / w; scaled by 1/nup for global u
                s.dpdu = (glm::vec3(hu) - s.p * hu.w) / w * float(npu);
                s.dpdv = (glm::vec3(hv) - s.p * hv.w) / w * float(npv);
                return s;
            };
            glm::vec2 st0(float(pu) / npu, float(pv) / npv);
            glm::vec2 st1(float(pu + 1) / npu, float(pv + 1) / npv);
            if (!appendGrid(result, segU, segV, eval, pv * npu + pu, st0, st1))
                return fail(err, "PatchMesh: mesh too large at this density");
        }
    out = std::move(result);
    return true;
}

bool tessellatePatch(const std::string& type, PositionKind kind,
                     const std::vector<float>& positions, const CubicBasis& ubasis,
                     const CubicBasis& vbasis, int segU, int segV, SurfaceMesh& out,
                     std::string* err) {
    PatchMeshInput in;
    if (type == "bilinear") in.bicubic = false;
    else if (type == "bicubic") in.bicubic = true;
    else return fail(err, "Patch: unknown type \"" + type + "\"");
    in.nu = in.nv = in.bicubic ? 4 : 2;
    in.kind = kind;
    in.positions = positions;
    in.ubasis = ubasis;
    in.vbasis = vbasis;
    return tessellatePatchMesh(in, segU, segV, out, err);
}

}  // namespace rd
