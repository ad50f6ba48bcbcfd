// dice_displaced.cpp: cutting truly displaced surfaces into micropolygons
// (dice_displaced.h).
#include "dice_displaced.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include "triangle_motion.h"

namespace rd {

bool DicingView::inView(const glm::vec3& p) const {
    if (halfX <= 0.0f) return true;
    const glm::vec3 c = glm::vec3(worldToCamera * glm::vec4(p, 1.0f));
    if (!perspective) return std::fabs(c.x) <= halfX && std::fabs(c.y) <= halfY;
    return c.z > 0.0f && std::fabs(c.x) <= halfX * c.z && std::fabs(c.y) <= halfY * c.z;
}

float DicingView::pixels(const glm::vec3& a, const glm::vec3& b) const {
    const float len = glm::length(b - a);
    const float scale = inView(a) || inView(b) ? 1.0f : 1.0f / offscreen;
    if (!perspective) return scale * len / pixelWidth;
    const float d =
        std::max(std::min(glm::length(a - eye), glm::length(b - eye)), nearest);
    return scale * len / (pixelSpread * d);
}

DicingView dicingViewOf(const Camera& c) {
    DicingView v;
    v.eye =
        glm::vec3(c.camera_to_world[0].w, c.camera_to_world[1].w, c.camera_to_world[2].w);
    v.perspective = c.perspective != 0;
    const float across =
        std::fabs(c.screen[1] - c.screen[0]) / float(std::max(c.width, 1));
    v.pixelSpread = std::max(across * c.tan_half_fov, 1e-12f);
    v.pixelWidth = std::max(across, 1e-12f);
    v.nearest = std::max(c.clip_near, 1e-4f);
    glm::mat4 toWorld(1.0f);
    for (int r = 0; r < 3; ++r) {
        const rt_float4& row = c.camera_to_world[r];
        toWorld[0][r] = row.x, toWorld[1][r] = row.y, toWorld[2][r] = row.z,
        toWorld[3][r] = row.w;
    }
    v.worldToCamera = glm::inverse(toWorld);
    const float sx = std::max(std::fabs(c.screen[0]), std::fabs(c.screen[1])),
                sy = std::max(std::fabs(c.screen[2]), std::fabs(c.screen[3]));
    const float unit = v.perspective ? c.tan_half_fov : 1.0f;
    v.halfX = 1.1f * sx * unit, v.halfY = 1.1f * sy * unit;
    if (!std::isfinite(v.halfX) || !std::isfinite(v.halfY)) v.halfX = v.halfY = 0.0f;
    return v;
}

bool hasTrueDisplacement(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) {
                           return (m.flags & RT_MATERIAL_TRUE_DISPLACEMENT) &&
                                  (m.flags & RT_MATERIAL_DISPLACEMENT_MASK);
                       });
}

namespace {

// A corner of a piece: its place, and its barycentric (u, v) in the original triangle.
struct Corner {
    glm::vec3 p;
    glm::vec2 b;
};

Corner midpoint(const Corner& x, const Corner& y) {
    // (x + y) * 0.5 is the same bits whichever end comes first: neighbours agree
    return {(x.p + y.p) * 0.5f, (x.b + y.b) * 0.5f};
}

// How deep the cutting goes at most: the edge rule's limit changes along a surface
// (with distance, and off screen), so cutting one edge can make a shorter one that must
// be cut and so on without end near the change; past this depth a piece is kept (a
// neighbour may cut the edge it shares once more: a crack of 2^-24 of the edge).
constexpr int kMaxDiceDepth = 24;

// Cuts one triangle by the pattern of its edges longer than `limit` pixels, down to
// pieces with none, handing each piece to `emit`; false once `emit` says stop.
template <class Emit>
bool dice(const DicingView& view, float limit, const Corner& a, const Corner& b,
          const Corner& c, Emit& emit, int depth = 0) {
    const bool ab = view.pixels(a.p, b.p) > limit, bc = view.pixels(b.p, c.p) > limit,
               ca = view.pixels(c.p, a.p) > limit;
    const int cuts = depth >= kMaxDiceDepth ? 0 : int(ab) + int(bc) + int(ca);
    if (cuts == 0) return emit(a, b, c);
    auto next = [&](const Corner& p, const Corner& q, const Corner& r) {
        return dice(view, limit, p, q, r, emit, depth + 1);
    };
    if (cuts == 3) {
        const Corner mab = midpoint(a, b), mbc = midpoint(b, c), mca = midpoint(c, a);
        return next(a, mab, mca) && next(mab, b, mbc) && next(mca, mbc, c) &&
               next(mab, mbc, mca);
    }
    // turned (keeping the winding) so that x-y is cut, and with two cuts z-x is the other
    const Corner *x = &a, *y = &b, *z = &c;
    if (cuts == 1 ? bc : !ca)
        x = &b, y = &c, z = &a;
    else if (cuts == 1 ? ca : !ab)
        x = &c, y = &a, z = &b;
    const Corner mxy = midpoint(*x, *y);
    if (cuts == 1) return next(*x, mxy, *z) && next(mxy, *y, *z);
    // the corner x on its own, the quad left split along its shorter diagonal (both
    // pieces come from this triangle, so the choice is no neighbour's)
    const Corner mzx = midpoint(*z, *x);
    if (!next(*x, mxy, mzx)) return false;
    if (glm::length(y->p - mzx.p) <= glm::length(z->p - mxy.p))
        return next(mxy, *y, mzx) && next(*y, *z, mzx);
    return next(mxy, *y, *z) && next(mxy, *z, mzx);
}

// Whether a triangle is diced: truly displaced and not in a solid (a truly displaced
// instance is a copy of its object, rib_builder.cpp objectInstance). (A
// moving one is diced at its first key, and its pieces move as it does.)
bool isDiced(const Scene& s, size_t t) {
    const TriangleAttr& a = s.attrs[t];
    if (a.material >= s.materials.size()) return false;
    const Material& m = s.materials[a.material];
    return (m.flags & RT_MATERIAL_TRUE_DISPLACEMENT) &&
           (m.flags & RT_MATERIAL_DISPLACEMENT_MASK) &&
           !(a.flags & (RT_QF_CSG_MEMBER | RT_QF_PROTOTYPE | RT_QF_DICED));
}

glm::vec3 v3(const rt_float4& f) {
    return glm::vec3(f.x, f.y, f.z);
}
rt_float4 f4(const glm::vec3& v) {
    return {v.x, v.y, v.z, 0.0f};
}

rt_float4 blend(const rt_float4* corners, const glm::vec2& b) {
    const float w0 = 1.0f - b.x - b.y;
    return {w0 * corners[0].x + b.x * corners[1].x + b.y * corners[2].x,
            w0 * corners[0].y + b.x * corners[1].y + b.y * corners[2].y,
            w0 * corners[0].z + b.x * corners[1].z + b.y * corners[2].z,
            w0 * corners[0].w + b.x * corners[1].w + b.y * corners[2].w};
}

// A corner's place on each of a moving triangle's keys after the first.
std::vector<Triangle> keysAt(const std::vector<Triangle>& keys, const glm::vec2& a,
                             const glm::vec2& b, const glm::vec2& c) {
    std::vector<Triangle> out;
    for (const Triangle& k : keys) {
        const rt_float4 corners[3] = {k.v0, k.v1, k.v2};
        out.push_back({blend(corners, a), blend(corners, b), blend(corners, c)});
    }
    return out;
}

// The vertices met so far, found by place: a corner is an earlier vertex when it is of
// the same material, within `cell` of it and of nearly the same normal. The tolerance
// welds what a tessellator computed twice (a sphere's seam, cos 0 against cos 2 pi; its
// poles), so the displaced surface stays closed there, whatever (s, t) each side has
// (a texture seam takes one side's); creases (normals apart) keep their vertices apart,
// and so crack open as they do in a REYES renderer.
// A hash map from 64-bit keys to vertex indices, open addressing: the node-based
// std::unordered_map spent a fifth of a 3.4M-piece dicing in its lookups.
class FlatIndex {
public:
    explicit FlatIndex(size_t expected) {
        size_t cap = 16;
        while (cap < 2 * expected) cap *= 2;
        m_keys.assign(cap, kEmpty);
        m_vals.assign(cap, 0);
    }
    // The value under `key`, or nullptr.
    const uint32_t* find(uint64_t key) const {
        for (size_t i = slot(key);; i = (i + 1) & (m_keys.size() - 1)) {
            if (m_keys[i] == kEmpty) return nullptr;
            if (m_keys[i] == key) return &m_vals[i];
        }
    }
    // The value under `key`, made `fresh` when there was none.
    uint32_t& at(uint64_t key, uint32_t fresh) {
        if (2 * (m_used + 1) > m_keys.size()) grow();
        size_t i = slot(key);
        for (; m_keys[i] != kEmpty; i = (i + 1) & (m_keys.size() - 1))
            if (m_keys[i] == key) return m_vals[i];
        ++m_used;
        m_keys[i] = key;
        m_vals[i] = fresh;
        return m_vals[i];
    }

private:
    static constexpr uint64_t kEmpty = ~uint64_t(0);
    size_t slot(uint64_t key) const {
        return size_t((key * 0x9e3779b97f4a7c15ull) >> 17) & (m_keys.size() - 1);
    }
    void grow() {
        std::vector<uint64_t> keys = std::move(m_keys);
        std::vector<uint32_t> vals = std::move(m_vals);
        m_keys.assign(2 * keys.size(), kEmpty);
        m_vals.assign(2 * keys.size(), 0);
        m_used = 0;
        for (size_t i = 0; i < keys.size(); ++i)
            if (keys[i] != kEmpty) at(keys[i], vals[i]);
    }
    std::vector<uint64_t> m_keys;
    std::vector<uint32_t> m_vals;
    size_t m_used = 0;
};

class VertexWeld {
public:
    // tol: how far apart two corners may be and be one vertex
    VertexWeld(float tol, size_t expected)
        : m_tol(tol > 0.0f ? tol : 1e-30f), m_exact(expected), m_cells(expected) {
        m_vertices.reserve(expected);
    }
    // The vertex of this corner: an earlier one, or `fresh` (added).
    uint32_t find(const glm::vec3& p, const glm::vec3& n, uint32_t material,
                  uint32_t fresh) {
        // most corners repeat a vertex bit for bit (neighbours compute shared midpoints
        // alike): one look in the map of exact places first
        const uint64_t exact = key(glm::floatBitsToInt(p), material);
        if (const uint32_t* head = m_exact.find(exact))
            for (uint32_t v = *head; v != kNone; v = m_vertices[v].nextExact)
                if (matches(m_vertices[v], p, n, material)) return m_vertices[v].id;
        // else the cells (twice the tolerance wide) a vertex within it may lie in: two a
        // side
        const double c = 2.0 * double(m_tol);
        const glm::dvec3 lo = glm::floor((glm::dvec3(p) - double(m_tol)) / c),
                         hi = glm::floor((glm::dvec3(p) + double(m_tol)) / c);
        for (double z = lo.z; z <= hi.z; ++z)
            for (double y = lo.y; y <= hi.y; ++y)
                for (double x = lo.x; x <= hi.x; ++x) {
                    const uint32_t* head =
                        m_cells.find(key(glm::ivec3(int(x), int(y), int(z)), material));
                    for (uint32_t v = head ? *head : kNone; v != kNone;
                         v = m_vertices[v].nextInCell)
                        if (matches(m_vertices[v], p, n, material))
                            return m_vertices[v].id;
                }
        const uint32_t index = uint32_t(m_vertices.size());
        const glm::ivec3 own(glm::floor(glm::dvec3(p) / c));
        uint32_t& cellHead = m_cells.at(key(own, material), kNone);
        const uint32_t nextInCell = cellHead;
        cellHead = index;
        uint32_t& exactHead = m_exact.at(exact, kNone);
        m_vertices.push_back({p, n, material, fresh, nextInCell, exactHead});
        exactHead = index;
        return fresh;
    }

private:
    static constexpr uint32_t kNone = ~0u;
    struct Vertex {
        glm::vec3 p, n;
        uint32_t material, id, nextInCell, nextExact;
    };
    bool matches(const Vertex& w, const glm::vec3& p, const glm::vec3& n,
                 uint32_t material) const {
        return w.material == material && glm::length(w.p - p) <= m_tol &&
               glm::dot(w.n, n) > 0.999f;
    }
    static uint64_t key(const glm::ivec3& c, uint32_t material) {
        uint64_t h = 1469598103934665603ull;
        for (uint32_t x : {uint32_t(c.x), uint32_t(c.y), uint32_t(c.z), material})
            h = (h ^ x) * 1099511628211ull;
        return h;  // (a collision only costs a look at another cell's vertices)
    }
    float m_tol;
    FlatIndex m_exact, m_cells;  // the chains' first vertices
    std::vector<Vertex> m_vertices;
};

// The triangles to dice (truly displaced, not yet diced, not in a solid: isDiced); the
// others that would be and stay whole are counted in out.skipped.
std::vector<size_t> trianglesToDice(const Scene& s, DicedSurfaces& out) {
    std::vector<size_t> diced;
    for (size_t t = 0; t < s.triangles.size(); ++t) {
        if (isDiced(s, t))
            diced.push_back(t);
        else if (s.attrs[t].material < s.materials.size() &&
                 (s.materials[s.attrs[t].material].flags &
                  RT_MATERIAL_TRUE_DISPLACEMENT) &&
                 !(s.attrs[t].flags & RT_QF_DICED))
            ++out.skipped;
    }
    return diced;
}

// The dicing of one source triangle: its corners and its edge limit in pixels.
std::array<Corner, 3> cornersOf(const Scene& s, size_t t) {
    const Triangle& tr = s.triangles[t];
    return {Corner{v3(tr.v0), {0, 0}}, Corner{v3(tr.v1), {1, 0}},
            Corner{v3(tr.v2), {0, 1}}};
}
float limitOf(const Scene& s, size_t t, float coarsening) {
    const uint32_t m = s.attrs[t].material;
    const float d = m < s.materialDicing.size() ? s.materialDicing[m] : 1.0f;
    return (d > 0.0f ? d : 1.0f) * coarsening;
}
// A moving piece counts three against the budget: its motion record, box and last key
// cost twice a still piece's arrays again.
size_t weightOf(const Scene& s, size_t t) {
    return s.attrs[t].flags & RT_QF_MOVING ? 3 : 1;
}

// Counts the pieces, coarser while over the budget (a bounded number of tries: each
// doubles the edge limit, out.coarsening). Returns the pieces of the dicing that fits.
size_t countWithinBudget(const Scene& s, const DicingView& view,
                         const std::vector<size_t>& diced, size_t maxTriangles,
                         DicedSurfaces& out) {
    size_t counted = 0, weighed = 0;  // the pieces, and weighted
    for (int tries = 0;; ++tries) {
        counted = weighed = 0;
        size_t weight = 1;
        auto counter = [&](const Corner&, const Corner&, const Corner&) {
            ++counted;
            return (weighed += weight) <= maxTriangles;
        };
        bool fits = true;
        for (size_t t : diced) {
            const auto c = cornersOf(s, t);
            weight = weightOf(s, t);
            if (!dice(view, limitOf(s, t, out.coarsening), c[0], c[1], c[2], counter)) {
                fits = false;
                break;
            }
        }
        if (fits || tries >= 40) return counted;
        out.coarsening *= 2.0f;
    }
}

// The weld's tolerance: a millionth of the diced surfaces' extent.
float weldTolerance(const Scene& s, const std::vector<size_t>& diced) {
    glm::vec3 lo(std::numeric_limits<float>::max()),
        hi(-std::numeric_limits<float>::max());
    for (size_t t : diced)
        for (const rt_float4* v :
             {&s.triangles[t].v0, &s.triangles[t].v1, &s.triangles[t].v2})
            lo = glm::min(lo, v3(*v)), hi = glm::max(hi, v3(*v));
    return glm::length(hi - lo) * 1e-6f;
}

// Writes the pieces of the source triangles after the scene's triangles, in every
// per-triangle array (normals, st, per-point colours and shader parameters, motion),
// and the vertices to displace: begin(t) for each source, then the pieces dice() gives.
class PieceWriter {
public:
    PieceWriter(Scene& s, DicedSurfaces& out, size_t n, size_t counted, float tolerance)
        : m_s(s),
          m_out(out),
          m_csChunks(s.vertexCs.size() / (3 * std::max<size_t>(n, 1))),
          m_osChunks(s.vertexOs.size() / (3 * std::max<size_t>(n, 1))),
          m_params(!s.triangleParams.empty()),
          m_weld(tolerance, counted / 2 + 16) {
        s.triangles.reserve(n + counted);
        s.attrs.reserve(n + counted);
        s.normals.reserve(3 * (n + counted));
        s.vertexSt.reserve(3 * (n + counted));
        out.cornerVertex.reserve(3 * counted);
        s.normals.resize(3 * n, rt_float4{0, 0, 0, 0});
        if (s.vertexSt.empty()) s.vertexSt.assign(3 * n, rt_float4{0, 0, 0, 0});
        s.primvarsUsed |= RT_PRIMVAR_ST;
        s.anySmoothNormals = true;  // the pieces carry the moved surface's normals
        if (m_params) s.triangleParams.resize(n, RT_NO_POINT_PARAMS);
        // the motion records of moving triangles, which their pieces' records replace
        m_motionRecord.assign(n, ~0u);
        for (size_t q = 0; q < s.quadrics.size(); ++q)
            if (s.quadrics[q].kind == RT_Q_MOVING_TRIANGLE &&
                s.quadrics[q].first_member < n)
                m_motionRecord[s.quadrics[q].first_member] = uint32_t(q);
    }
    // The source triangle t's values at its corners, which its pieces blend.
    void begin(size_t t) {
        m_t = t;
        m_attr = m_s.attrs[t];
        const Triangle tr = m_s.triangles[t];
        m_moving = (m_attr.flags & RT_QF_MOVING) && t < m_s.trianglesEnd.size();
        m_motion = m_moving ? triangleKeys(m_s, t) : TriangleKeys{};
        const glm::vec3 face =
            glm::normalize(glm::cross(v3(tr.v1) - v3(tr.v0), v3(tr.v2) - v3(tr.v0)));
        bool smooth = m_attr.has_normals != 0;
        for (int k = 0; k < 3; ++k) {
            const rt_float4 nk = m_nrm[k] = m_s.normals[3 * t + size_t(k)];
            smooth = smooth && (nk.x != 0.0f || nk.y != 0.0f || nk.z != 0.0f);
            m_st[k] = (m_attr.primvars & RT_PRIMVAR_ST)
                          ? m_s.vertexSt[3 * t + size_t(k)]
                          : rt_float4{k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f, 0, 0};
        }
        if (!smooth)
            for (rt_float4& v : m_nrm) v = f4(face);
        // per-point shader parameters: K values a corner
        m_paramCount = 0;
        m_firstParam = m_params ? m_s.triangleParams[t] : RT_NO_POINT_PARAMS;
        if (m_firstParam != RT_NO_POINT_PARAMS) {
            const uint32_t shader = m_s.materials[m_attr.material].shader;
            if (shader < m_s.surfaceRefs.size())
                for (const auto& [name, floats] : m_s.surfaceRefs[shader].pointParams)
                    m_paramCount += size_t(pointParamEntries(floats));
        }
    }
    // Marks the source diced (and its motion record).
    void end() {
        m_s.attrs[m_t].flags |= RT_QF_DICED;
        if (m_moving && m_motionRecord[m_t] != ~0u)
            m_s.quadrics[m_motionRecord[m_t]].flags |= RT_QF_DICED;
    }
    void piece(const Corner& a, const Corner& b, const Corner& c) {
        const uint32_t index = uint32_t(m_s.triangles.size());
        m_s.triangles.push_back({f4(a.p), f4(b.p), f4(c.p)});
        m_s.attrs.push_back({m_attr.material, 1u, m_attr.primvars | RT_PRIMVAR_ST,
                             (m_attr.flags & ~uint32_t(RT_QF_MOVING)) | RT_QF_DISPLACED});
        m_out.pieceSource.push_back(uint32_t(m_t));
        if (m_moving)
            addTriangleMotion(m_s, keysAt(m_motion.keys, a.b, b.b, c.b), m_motion.times);
        int k = 0;
        for (const Corner* q : {&a, &b, &c}) corner(*q, index, k++);
        if (m_params) params(a, b, c);
    }

private:
    void corner(const Corner& q, uint32_t index, int k) {
        rt_float4 nq = blend(m_nrm, q.b);
        const float len = std::sqrt(nq.x * nq.x + nq.y * nq.y + nq.z * nq.z);
        // (w: 0, not the source's blended key-normal index, shade_common.clh)
        nq = len > 0.0f ? rt_float4{nq.x / len, nq.y / len, nq.z / len, 0.0f}
                        : rt_float4{nq.x, nq.y, nq.z, 0.0f};
        m_s.normals.push_back(nq);
        m_s.vertexSt.push_back(blend(m_st, q.b));
        for (auto [buf, chunks, bit] :
             {std::make_tuple(&m_s.vertexCs, m_csChunks, RT_PRIMVAR_CS),
              std::make_tuple(&m_s.vertexOs, m_osChunks, RT_PRIMVAR_OS)})
            for (size_t ch = 0; ch < chunks; ++ch) {
                rt_float4 c3[3];
                for (size_t j = 0; j < 3; ++j)
                    c3[j] = (*buf)[(3 * m_t + j) * chunks + ch];
                buf->push_back((m_attr.primvars & bit) ? blend(c3, q.b)
                                                       : rt_float4{0, 0, 0, 0});
            }
        const uint32_t fresh = uint32_t(m_out.vertexCorner.size());
        const uint32_t v = m_weld.find(q.p, v3(nq), m_attr.material, fresh);
        if (v == fresh) m_out.vertexCorner.push_back({index, uint32_t(k)});
        m_out.cornerVertex.push_back(v);
    }
    void params(const Corner& a, const Corner& b, const Corner& c) {
        if (m_firstParam == RT_NO_POINT_PARAMS) {
            m_s.triangleParams.push_back(RT_NO_POINT_PARAMS);
            return;
        }
        m_s.triangleParams.push_back(uint32_t(m_s.pointParamValues.size()));
        for (const Corner* q : {&a, &b, &c})
            for (size_t e = 0; e < m_paramCount; ++e) {
                rt_float4 p3[3];
                for (size_t j = 0; j < 3; ++j)
                    p3[j] = m_s.pointParamValues[m_firstParam + j * m_paramCount + e];
                m_s.pointParamValues.push_back(blend(p3, q->b));
            }
    }
    Scene& m_s;
    DicedSurfaces& m_out;
    size_t m_csChunks, m_osChunks;
    bool m_params;
    VertexWeld m_weld;
    std::vector<uint32_t> m_motionRecord;
    // the source triangle
    size_t m_t = 0;
    TriangleAttr m_attr{};
    bool m_moving = false;
    TriangleKeys m_motion;
    rt_float4 m_nrm[3]{}, m_st[3]{};
    uint32_t m_firstParam = RT_NO_POINT_PARAMS;
    size_t m_paramCount = 0;
};

}  // namespace

DicedSurfaces diceDisplacedSurfaces(Scene& s, const DicingView& view,
                                    size_t maxTriangles) {
    DicedSurfaces out;
    out.budget = maxTriangles;
    const size_t n = s.triangles.size();
    const std::vector<size_t> diced = trianglesToDice(s, out);
    out.firstTriangle = uint32_t(n);
    if (diced.empty()) return out;
    const size_t counted =
        std::min(countWithinBudget(s, view, diced, maxTriangles, out), maxTriangles);
    PieceWriter writer(s, out, n, counted, weldTolerance(s, diced));
    size_t used = 0;  // weighted, as counted
    for (size_t t : diced) {
        const size_t weight = weightOf(s, t);
        writer.begin(t);
        auto emit = [&](const Corner& a, const Corner& b, const Corner& c) {
            writer.piece(a, b, c);
            return (used += weight) < maxTriangles;
        };
        const auto c = cornersOf(s, t);
        const bool whole =
            dice(view, limitOf(s, t, out.coarsening), c[0], c[1], c[2], emit);
        writer.end();
        ++out.diced;
        if (!whole) {  // (only where even the coarsest limit could not fit)
            out.truncated = true;
            break;
        }
    }
    if (!s.trianglesEnd.empty()) s.trianglesEnd.resize(s.triangles.size());
    return out;
}

}  // namespace rd
