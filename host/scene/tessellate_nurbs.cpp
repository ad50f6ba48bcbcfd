// tessellate_nurbs.cpp: Cox-de Boor evaluation of NURBS surfaces and trim curves, grid
// dicing and even-odd trimming.
#include "host/scene/tessellate_nurbs.h"

#include <algorithm>
#include <cmath>

namespace rd {
namespace {

constexpr int kMaxOrder = 32;

bool fail(std::string* err, const std::string& msg) {
    if (err) *err = msg;
    return false;
}

// Knot span index i in [order-1, n-1] with U[i] <= t < U[i+1] (t at the end of the range
// goes to the last non-empty span).
int findSpan(int n, int order, const float* U, double t) {
    int p = order - 1;
    if (t >= U[n]) {
        int i = n - 1;
        while (i > p && U[i] >= U[n]) --i;
        return i;
    }
    if (t <= U[p]) {
        int i = p;
        while (i < n - 1 && U[i + 1] <= U[p]) ++i;
        return i;
    }
    int lo = p, hi = n;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (t < U[mid]) hi = mid;
        else lo = mid;
    }
    return lo;
}

// Non-zero basis functions N[0..p] (functions span-p..span) at t, and their first
// derivatives dN[0..p] (The NURBS Book A2.2 plus the derivative recurrence).
void basisFuns(int span, double t, int order, const float* U, double* N, double* dN) {
    int p = order - 1;
    double left[kMaxOrder + 1], right[kMaxOrder + 1], Nm[kMaxOrder + 1];
    N[0] = 1.0;
    for (int j = 1; j <= p; ++j) {
        if (j == p)
            for (int k = 0; k < p; ++k) Nm[k] = N[k];  // degree p-1 values
        left[j] = t - U[span + 1 - j];
        right[j] = U[span + j] - t;
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            double den = right[r + 1] + left[j - r];
            double tmp = den != 0.0 ? N[r] / den : 0.0;
            N[r] = saved + right[r + 1] * tmp;
            saved = left[j - r] * tmp;
        }
        N[j] = saved;
    }
    if (!dN) return;
    if (p == 0) {
        dN[0] = 0.0;
        return;
    }
    for (int j = 0; j <= p; ++j) {
        int k = span - p + j;
        double a = 0.0, b = 0.0;
        if (j >= 1) {
            double d = double(U[k + p]) - U[k];
            if (d != 0.0) a = Nm[j - 1] / d;
        }
        if (j <= p - 1) {
            double d = double(U[k + p + 1]) - U[k + 1];
            if (d != 0.0) b = Nm[j] / d;
        }
        dN[j] = p * (a - b);
    }
}

double clampParam(double t, const std::vector<float>& U, int n, int order) {
    return std::clamp(t, double(U[order - 1]), double(U[n]));
}

}  // namespace

bool validateKnots(int n, int order, const std::vector<float>& knots, std::string* err) {
    if (order < 1 || order > kMaxOrder) return fail(err, "NURBS: order must be in [1, 32]");
    if (n < order) return fail(err, "NURBS: fewer control points than the order");
    if (knots.size() != size_t(n) + size_t(order))
        return fail(err, "NURBS: knot vector length must be n + order");
    for (size_t i = 0; i < knots.size(); ++i) {
        if (!std::isfinite(knots[i])) return fail(err, "NURBS: non-finite knot");
        if (i > 0 && knots[i] < knots[i - 1])
            return fail(err, "NURBS: knot vector is not non-decreasing");
    }
    if (!(knots[n] > knots[order - 1])) return fail(err, "NURBS: empty parameter range");
    return true;
}

bool validateNuPatch(const NuPatchInput& in, std::string* err) {
    if (!validateKnots(in.nu, in.uorder, in.uknot, err)) return false;
    if (!validateKnots(in.nv, in.vorder, in.vknot, err)) return false;
    if (double(in.nu) * in.nv > double(kMaxMeshVertices))
        return fail(err, "NuPatch: too many control points");
    size_t nf = in.rational ? 4 : 3;
    if (in.positions.size() != size_t(in.nu) * size_t(in.nv) * nf)
        return fail(err, "NuPatch: position array has the wrong length");
    for (float x : in.positions)
        if (!std::isfinite(x)) return fail(err, "NuPatch: non-finite position");
    for (float x : {in.umin, in.umax, in.vmin, in.vmax})
        if (!std::isfinite(x)) return fail(err, "NuPatch: non-finite parameter range");
    double u0 = clampParam(in.umin, in.uknot, in.nu, in.uorder);
    double u1 = clampParam(in.umax, in.uknot, in.nu, in.uorder);
    double v0 = clampParam(in.vmin, in.vknot, in.nv, in.vorder);
    double v1 = clampParam(in.vmax, in.vknot, in.nv, in.vorder);
    if (!(u0 < u1) || !(v0 < v1)) return fail(err, "NuPatch: empty [min, max] range");
    return true;
}

SurfaceSample evalNuPatch(const NuPatchInput& in, float uf, float vf) {
    double u = clampParam(uf, in.uknot, in.nu, in.uorder);
    double v = clampParam(vf, in.vknot, in.nv, in.vorder);
    int su = findSpan(in.nu, in.uorder, in.uknot.data(), u);
    int sv = findSpan(in.nv, in.vorder, in.vknot.data(), v);
    double Nu[kMaxOrder], dNu[kMaxOrder], Nv[kMaxOrder], dNv[kMaxOrder];
    basisFuns(su, u, in.uorder, in.uknot.data(), Nu, dNu);
    basisFuns(sv, v, in.vorder, in.vknot.data(), Nv, dNv);
    int nf = in.rational ? 4 : 3;
    glm::dvec4 h(0.0), hu(0.0), hv(0.0);
    for (int b = 0; b < in.vorder; ++b) {
        int j = sv - in.vorder + 1 + b;
        for (int a = 0; a < in.uorder; ++a) {
            int i = su - in.uorder + 1 + a;
            const float* f = &in.positions[(size_t(j) * in.nu + i) * nf];
            glm::dvec4 c(f[0], f[1], f[2], in.rational ? f[3] : 1.0f);
            h += Nu[a] * Nv[b] * c;
            hu += dNu[a] * Nv[b] * c;
            hv += Nu[a] * dNv[b] * c;
        }
    }
    double w = h.w != 0.0 ? h.w : 1e-300;
    glm::dvec3 p = glm::dvec3(h) / w;
    SurfaceSample s;
    s.p = glm::vec3(p);
    s.dpdu = glm::vec3((glm::dvec3(hu) - p * hu.w) / w);
    s.dpdv = glm::vec3((glm::dvec3(hv) - p * hv.w) / w);
    return s;
}

bool validateTrimCurves(const TrimCurves& t, std::string* err) {
    size_t curves = 0;
    for (int c : t.ncurves) {
        if (c < 1) return fail(err, "TrimCurve: a loop needs at least one curve");
        curves += size_t(c);
        if (curves > (1u << 20)) return fail(err, "TrimCurve: too many curves");
    }
    if (t.order.size() != curves || t.n.size() != curves || t.min.size() != curves ||
        t.max.size() != curves)
        return fail(err, "TrimCurve: order/n/min/max counts do not match ncurves");
    size_t knots = 0, cps = 0;
    for (size_t c = 0; c < curves; ++c) {
        if (t.order[c] < 1 || t.n[c] < t.order[c] || t.n[c] > (1 << 20))
            return fail(err, "TrimCurve: bad order or n");
        knots += size_t(t.n[c]) + t.order[c];
        cps += size_t(t.n[c]);
    }
    if (t.knot.size() != knots) return fail(err, "TrimCurve: knot array has the wrong length");
    if (t.u.size() != cps || t.v.size() != cps || t.w.size() != cps)
        return fail(err, "TrimCurve: u/v/w arrays have the wrong length");
    size_t ko = 0;
    for (size_t c = 0; c < curves; ++c) {
        std::vector<float> k(t.knot.begin() + ko, t.knot.begin() + ko + t.n[c] + t.order[c]);
        if (!validateKnots(t.n[c], t.order[c], k, err)) return false;
        ko += k.size();
    }
    return true;
}

bool trimLoopPolylines(const TrimCurves& t, int segmentsPerSpan,
                       std::vector<std::vector<glm::vec2>>& loops, std::string* err) {
    if (!validateTrimCurves(t, err)) return false;
    segmentsPerSpan = std::clamp(segmentsPerSpan, 1, 256);
    loops.clear();
    size_t c = 0, ko = 0, co = 0, total = 0;
    for (int nc : t.ncurves) {
        std::vector<glm::vec2> loop;
        for (int k = 0; k < nc; ++k, ++c) {
            int n = t.n[c], order = t.order[c];
            const float* U = &t.knot[ko];
            double lo = std::clamp(double(t.min[c]), double(U[order - 1]), double(U[n]));
            double hi = std::clamp(double(t.max[c]), double(U[order - 1]), double(U[n]));
            int samples = segmentsPerSpan * (n - order + 1) * std::max(1, order - 1);
            samples = std::min(samples, 1 << 14);
            total += size_t(samples);
            if (total > size_t(kMaxMeshVertices)) return fail(err, "TrimCurve: too many samples");
            for (int s = 0; s <= samples; ++s) {
                if (s == samples && k + 1 < nc) break;  // next curve starts here
                double x = lo + (hi - lo) * s / samples;
                int span = findSpan(n, order, U, x);
                double N[kMaxOrder];
                basisFuns(span, x, order, U, N, nullptr);
                glm::dvec3 h(0.0);
                for (int a = 0; a < order; ++a) {
                    size_t i = co + size_t(span - order + 1 + a);
                    h += N[a] * glm::dvec3(t.u[i], t.v[i], t.w[i]);
                }
                double w = h.z != 0.0 ? h.z : 1e-300;
                loop.emplace_back(float(h.x / w), float(h.y / w));
            }
            ko += size_t(n + order);
            co += size_t(n);
        }
        loops.push_back(std::move(loop));
    }
    return true;
}

bool insideLoops(const std::vector<std::vector<glm::vec2>>& loops, glm::vec2 p) {
    bool in = false;
    for (const auto& L : loops) {
        size_t m = L.size();
        for (size_t i = 0, j = m ? m - 1 : 0; i < m; j = i++) {
            glm::vec2 a = L[i], b = L[j];
            if ((a.y > p.y) != (b.y > p.y) &&
                p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
                in = !in;
        }
    }
    return in;
}

bool tessellateNuPatch(const NuPatchInput& in, int segU, int segV, const TrimCurves* trim,
                       SurfaceMesh& out, std::string* err, bool keepInside) {
    if (!validateNuPatch(in, err)) return false;
    std::vector<std::vector<glm::vec2>> loops;
    if (trim && !trim->ncurves.empty() && !trimLoopPolylines(*trim, 16, loops, err))
        return false;
    float u0 = float(clampParam(in.umin, in.uknot, in.nu, in.uorder));
    float u1 = float(clampParam(in.umax, in.uknot, in.nu, in.uorder));
    float v0 = float(clampParam(in.vmin, in.vknot, in.nv, in.vorder));
    float v1 = float(clampParam(in.vmax, in.vknot, in.nv, in.vorder));
    auto eval = [&](float a, float b) {
        SurfaceSample s = evalNuPatch(in, u0 + a * (u1 - u0), v0 + b * (v1 - v0));
        s.dpdu *= (u1 - u0);
        s.dpdv *= (v1 - v0);
        return s;
    };
    SurfaceMesh g;
    if (!appendGrid(g, segU, segV, eval, 0, glm::vec2(u0, v0), glm::vec2(u1, v1)))
        return fail(err, "NuPatch: mesh too large at this density");
    auto spanIndex = [&](glm::vec2 uv) {
        int su = findSpan(in.nu, in.uorder, in.uknot.data(), uv.x) - (in.uorder - 1);
        int sv = findSpan(in.nv, in.vorder, in.vknot.data(), uv.y) - (in.vorder - 1);
        return sv * (in.nu - in.uorder + 1) + su;
    };
    auto keep = [&](glm::vec2 c) { return loops.empty() || insideLoops(loops, c) == keepInside; };
    std::vector<int> tris;
    std::vector<int> faces;
    auto addVertex = [&](glm::vec2 uv) {
        float a = (uv.x - u0) / (u1 - u0), b = (uv.y - v0) / (v1 - v0);
        SurfaceSample s = eval(a, b);
        g.mesh.p.push_back(s.p);
        glm::vec3 c = glm::cross(s.dpdu, s.dpdv);
        g.mesh.n.push_back(glm::length(c) > 0.0f ? glm::normalize(c) : glm::vec3(0, 0, 1));
        g.st.push_back(uv);
        return int(g.mesh.p.size()) - 1;
    };
    for (size_t k = 0; k < g.mesh.tris.size(); k += 3) {
        int t[3] = {g.mesh.tris[k], g.mesh.tris[k + 1], g.mesh.tris[k + 2]};
        glm::vec2 uv[3] = {g.st[t[0]], g.st[t[1]], g.st[t[2]]};
        glm::vec2 c = (uv[0] + uv[1] + uv[2]) / 3.0f;
        bool k0 = keep(uv[0]), k1 = keep(uv[1]), k2 = keep(uv[2]);
        if (!loops.empty() && !(k0 == k1 && k1 == k2)) {
            // Straddles a trim curve: split into four and classify the children.
            glm::vec2 m01 = 0.5f * (uv[0] + uv[1]), m12 = 0.5f * (uv[1] + uv[2]),
                      m20 = 0.5f * (uv[2] + uv[0]);
            int a = addVertex(m01), b = addVertex(m12), d = addVertex(m20);
            int sub[4][3] = {{t[0], a, d}, {a, t[1], b}, {d, b, t[2]}, {a, b, d}};
            for (auto& s : sub) {
                glm::vec2 cc = (g.st[s[0]] + g.st[s[1]] + g.st[s[2]]) / 3.0f;
                if (!keep(cc)) continue;
                tris.insert(tris.end(), {s[0], s[1], s[2]});
                faces.push_back(spanIndex(cc));
            }
            continue;
        }
        if (!keep(c)) continue;
        tris.insert(tris.end(), {t[0], t[1], t[2]});
        faces.push_back(spanIndex(c));
    }
    int base = int(out.mesh.p.size());
    for (int& i : tris) i += base;
    out.mesh.p.insert(out.mesh.p.end(), g.mesh.p.begin(), g.mesh.p.end());
    out.mesh.n.insert(out.mesh.n.end(), g.mesh.n.begin(), g.mesh.n.end());
    out.st.insert(out.st.end(), g.st.begin(), g.st.end());
    out.mesh.tris.insert(out.mesh.tris.end(), tris.begin(), tris.end());
    out.faceIndex.insert(out.faceIndex.end(), faces.begin(), faces.end());
    return true;
}

}  // namespace rd
