// rib_builder_mesh.cpp: meshes into the scene: object-space vertices placed in the
// (eye-relative) world, degenerate triangles reported at their request, per-vertex
// normals and primitive variables, triangles that move during the shutter, and objects
// (ObjectBegin/ObjectInstance): a prototype shared by its instances, or copies.
#include <algorithm>
#include <array>
#include <cfloat>
#include <cstring>

#include "rib_builder.h"
#include "rib_builder_util.h"
#include "triangle_motion.h"

namespace rd {

namespace {

// The corners of triangle k of `tris` over `p`, sorted (x, then y, then z), -0 as +0: one
// key for a triangle however its corners are ordered.
std::array<float, 9> sortedCorners(const std::vector<int>& tris, const std::vector<glm::vec3>& p,
                                   size_t k) {
    std::array<glm::vec3, 3> c{p[size_t(tris[3 * k])], p[size_t(tris[3 * k + 1])],
                               p[size_t(tris[3 * k + 2])]};
    std::sort(c.begin(), c.end(), [](const glm::vec3& u, const glm::vec3& v) {
        return u.x != v.x ? u.x < v.x : u.y != v.y ? u.y < v.y : u.z < v.z;
    });
    std::array<float, 9> key{c[0].x, c[0].y, c[0].z, c[1].x, c[1].y, c[1].z, c[2].x, c[2].y, c[2].z};
    for (float& f : key) f += 0.0f;  // (-0 + 0 is +0)
    return key;
}

// What is wrong with a triangle of a request, if anything.
enum class Defect : uint8_t { None, Nonfinite, NonfiniteEnd, ZeroArea, Coincident };

// Later copies of a kept triangle (the same corners, in any order) within the request are
// marked Coincident. By a sort of the corners' hashes and the triangles' indices rather
// than a set of corners: a set's node and bucket per triangle missed the cache twice an
// insert (half of reading a 300k-triangle mesh, perf).
void markCoincident(const std::vector<int>& tris, const std::vector<glm::vec3>& p,
                    std::vector<Defect>& defects) {
    std::vector<std::pair<uint64_t, uint32_t>> byHash;  // (hash of the corners, triangle)
    byHash.reserve(defects.size());
    for (size_t k = 0; k < defects.size(); ++k) {
        if (defects[k] != Defect::None) continue;
        uint64_t h = 1469598103934665603ull;
        for (float f : sortedCorners(tris, p, k)) {
            uint32_t bits;
            std::memcpy(&bits, &f, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        byHash.push_back({h, uint32_t(k)});
    }
    std::sort(byHash.begin(), byHash.end());
    for (size_t i = 0; i < byHash.size();) {
        size_t j = i + 1;
        while (j < byHash.size() && byHash[j].first == byHash[i].first) ++j;
        // a run of one hash (in triangle order): each is a copy of an earlier equal one
        for (size_t b = i + 1; b < j; ++b) {
            const std::array<float, 9> key = sortedCorners(tris, p, byHash[b].second);
            for (size_t e = i; e < b; ++e)
                if (defects[byHash[e].second] == Defect::None &&
                    sortedCorners(tris, p, byHash[e].second) == key) {
                    defects[byHash[b].second] = Defect::Coincident;
                    break;
                }
        }
        i = j;
    }
}

// Whether m is a rotation (or reflection) times a uniform scale: m^T m = s^2 I, to
// 1e-5 of s^2.
bool isSimilarity(const glm::mat3& m) {
    const glm::mat3 g = glm::transpose(m) * m;
    const float s2 = (g[0][0] + g[1][1] + g[2][2]) / 3.0f;
    if (!(s2 > 0.0f) || !std::isfinite(s2)) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::fabs(g[i][j] - (i == j ? s2 : 0.0f)) > 1e-5f * s2) return false;
    return true;
}

// What is wrong with each triangle of a mesh at world points wp: a moving one (`keys`,
// else null) must be finite at every key and not degenerate at all of them; later copies
// of a kept triangle are Coincident.
std::vector<Defect> triangleDefects(const std::vector<int>& tris,
                                    const std::vector<glm::vec3>& wp,
                                    const std::vector<std::vector<glm::vec3>>* keys) {
    const size_t count = tris.size() / 3;
    std::vector<Defect> defects(count, Defect::None);
    for (size_t k = 0; k < count; ++k) {
        const int i0 = tris[3 * k], i1 = tris[3 * k + 1], i2 = tris[3 * k + 2];
        const glm::vec3 &a = wp[size_t(i0)], &b = wp[size_t(i1)], &c = wp[size_t(i2)];
        glm::vec3 cr = glm::cross(b - a, c - a);
        if (keys) {
            bool finite = true;
            for (const std::vector<glm::vec3>& key : *keys) {
                const glm::vec3 &ea = key[size_t(i0)], &eb = key[size_t(i1)],
                                &ec = key[size_t(i2)];
                glm::vec3 ce = glm::cross(eb - ea, ec - ea);
                finite = finite && finite3(ea) && finite3(eb) && finite3(ec);
                if (glm::dot(ce, ce) > 0.0f && !(glm::dot(cr, cr) > 0.0f)) cr = ce;
            }
            if (!finite) {
                defects[k] = Defect::NonfiniteEnd;
                continue;
            }
        }
        if (!finite3(a) || !finite3(b) || !finite3(c))
            defects[k] = Defect::Nonfinite;
        else if (!(glm::dot(cr, cr) > 0.0f))
            defects[k] = Defect::ZeroArea;
    }
    markCoincident(tris, wp, defects);
    return defects;
}

// The triangles a request left out or patched, as its warning says them ("" if none).
struct DefectCounts {
    int nonfinite = 0, zeroArea = 0, duplicate = 0, badNormal = 0;
};
std::string describeDefects(const DefectCounts& d) {
    std::string what;
    auto add = [&](int n, const char* text) {
        if (n) what += (what.empty() ? "" : ", ") + std::to_string(n) + text;
    };
    add(d.nonfinite, " triangle(s) with a NaN or Inf vertex left out");
    add(d.zeroArea, " zero-area (collinear) triangle(s) left out");
    add(d.duplicate, " coincident (duplicate) triangle(s) left out");
    add(d.badNormal,
        " triangle(s) with a zero or non-finite normal shaded with the geometric normal");
    return what;
}

// Whether a triangle with this defect is left out, counted in `counts` (and, where it
// is degenerate, in `degenerate`, the builder's count over the frame).
bool leftOut(Defect d, DefectCounts& counts, int& degenerate) {
    switch (d) {
        case Defect::None:
            return false;
        case Defect::NonfiniteEnd:
            ++counts.nonfinite;
            break;
        case Defect::Nonfinite:
            ++degenerate, ++counts.nonfinite;
            break;
        case Defect::ZeroArea:
            ++degenerate, ++counts.zeroArea;
            break;
        case Defect::Coincident:
            ++counts.duplicate;
            break;
    }
    return true;
}

// A corner's colour, `chunks` float4s: more than three channels fill 8 or 16 floats
// (RSL_COLOR_LANES), zero past the channels; zero where the mesh gives none.
void pushCornerColor(std::vector<rt_float4>& buf, size_t chunks, bool given,
                     const std::vector<glm::vec3>& rgb,
                     const std::vector<VertexData::Channels>& channels, int k) {
    if (chunks == 1) {
        buf.push_back(given ? f4(rgb[size_t(k)]) : f4(0, 0, 0));
        return;
    }
    float c[16] = {};
    if (given) std::copy(channels[size_t(k)].begin(), channels[size_t(k)].end(), c);
    for (size_t q = 0; q < chunks; ++q)
        buf.push_back(f4(c[4 * q], c[4 * q + 1], c[4 * q + 2], c[4 * q + 3]));
}

// A primitive variable (bit) first seen now: the earlier triangles get placeholders.
void startPrimvar(Scene& w, uint32_t primvars, uint32_t bit, std::vector<rt_float4>& buf,
                  size_t per) {
    if ((primvars & bit) && !(w.primvarsUsed & bit)) {
        buf.assign(3 * w.triangles.size() * per, f4(0, 0, 0));
        w.primvarsUsed |= bit;
    }
}

}  // namespace

void RibBuilder::addMesh(L loc, const VertexData& mesh) {
    if (m_defining) {
        // Inside ObjectBegin: keep the piece in the object's own space; instances place it.
        glm::mat4 toObject = glm::inverse(m_definingCtm) * m_attrStack.back().ctm;
        glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(toObject)));
        VertexData piece = mesh;
        for (VertexData::PointParam& p : piece.params)
            p.v = pointParamToWorld(toObject, p, false);
        for (glm::vec3& v : piece.p) v = xformPoint(toObject, v);
        for (glm::vec3& v : piece.n) v = nm * v;
        m_defining->meshes.push_back(std::move(piece));
        return;
    }
    if (m_motion.active) {  // a key of a deforming mesh: added at MotionEnd
        m_motion.meshKeys.push_back(mesh);
        return;
    }
    const Attributes& a = m_attrStack.back();
    if (a.moving) return addMovingMesh(loc, {mesh}, {});
    appendTriangles(loc, mesh, worldPoints(a.ctm, mesh.p), nullptr);
}

std::vector<glm::vec3> RibBuilder::worldPoints(const glm::mat4& ctm,
                                               const std::vector<glm::vec3>& p) const {
    std::vector<glm::vec3> wp(p.size());
    const glm::dmat4 dctm(ctm);
    for (size_t i = 0; i < p.size(); ++i)  // camera-relative, in double (see worldBegin)
        wp[i] = glm::vec3(glm::dvec3(dctm * glm::dvec4(glm::dvec3(p[i]), 1.0)) - m_origin);
    return wp;
}

void RibBuilder::addMovingMesh(L loc, const std::vector<VertexData>& keys,
                               const std::vector<float>& times) {
    for (const VertexData& k : keys)
        if (k.p.size() != keys.front().p.size() || k.tris != keys.front().tris) {
            m_diag.error(loc, "MotionBegin: the mesh keys differ in topology");
            return;
        }
    const Attributes& at = m_attrStack.back();
    MeshMotion motion;
    std::vector<glm::vec3> first;
    if (keys.size() == 1) {  // still points under the transform's keys
        motion.times.push_back(at.t0);
        first = worldPoints(at.ctm, keys[0].p);
        std::vector<glm::mat4> later;  // the keys after the first
        for (const auto& [t, key] : at.between) {
            later.push_back(key);
            motion.times.push_back(t);
        }
        later.push_back(at.ctmEnd);
        motion.times.push_back(at.t1);
        for (const glm::mat4& key : later)
            motion.keys.push_back(worldPoints(key, keys[0].p));
        // Vertex normals under keys that are not similarities of the first: each key's
        // own, by its inverse transpose. (A triangle's motion carries them exactly only
        // through similarities: it cannot tell how the map shears its normal.)
        const bool similar =
            std::all_of(later.begin(), later.end(), [&](const glm::mat4& k) {
                return isSimilarity(glm::mat3(k) * glm::inverse(glm::mat3(at.ctm)));
            });
        if (keys[0].n.size() == keys[0].p.size() && !similar)
            for (const glm::mat4& key : later) {
                const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(key)));
                std::vector<glm::vec3>& n = motion.normals.emplace_back(keys[0].n);
                for (glm::vec3& v : n) v = nm * v;
            }
    } else {  // a deformation: each key placed by the transform at its time
        first = worldPoints(ctmAt(at, times[0]), keys[0].p);
        motion.times = times;
        for (size_t k = 1; k < keys.size(); ++k)
            motion.keys.push_back(worldPoints(ctmAt(at, times[k]), keys[k].p));
        // each key's own normals, where every key gives them: a bending surface's
        // normals turn with its neighbours, which its triangles' motion does not tell
        const size_t np = keys[0].p.size();
        if (std::all_of(keys.begin(), keys.end(),
                        [&](const VertexData& k) { return k.n.size() == np; }))
            for (size_t k = 1; k < keys.size(); ++k) {
                const glm::mat3 nm =
                    glm::transpose(glm::inverse(glm::mat3(ctmAt(at, times[k]))));
                std::vector<glm::vec3>& n = motion.normals.emplace_back(keys[k].n);
                for (glm::vec3& v : n) v = nm * v;
            }
    }
    appendTriangles(loc, keys[0], first, &motion);
}

// The last triangle's vertex normals at its keys after the first (MeshMotion::normals),
// in the motion buffer, three a key, where its first corner's normal's w finds them
// (1 + their start; cl/lib/shade_common.clh rd_key_normal). Only the keys its vertices
// keep (addTriangleMotion leaves the middle ones out past 2^24 float4s); none where a
// key's normal is zero or not finite: the first key's then turn with the triangle.
void RibBuilder::addKeyNormals(const MeshMotion& motion,
                               const std::array<int, 3>& corners) {
    const bool middles = m_world.trianglesEnd.back().v2.w > 0.0f;
    const size_t first = middles ? 0 : motion.normals.size() - 1;
    const size_t at = m_world.quadricMotion.size();
    if (at + 3 * (motion.normals.size() - first) >= (size_t(1) << 24)) return;
    for (size_t k = first; k < motion.normals.size(); ++k)
        for (int c : corners) {
            const glm::vec3& n = motion.normals[k][size_t(c)];
            const float len2 = glm::dot(n, n);
            if (!finite3(n) || !(len2 > 0.0f) || !std::isfinite(len2)) return;
        }
    for (size_t k = first; k < motion.normals.size(); ++k)
        for (int c : corners)
            m_world.quadricMotion.push_back(
                f4(glm::normalize(motion.normals[k][size_t(c)])));
    m_world.normals[m_world.normals.size() - 3].w = float(at + 1);
}

struct RibBuilder::MeshSetUp {
    bool prototype = false;
    int leaf = -1;       // the solid leaf its triangles belong to, else -1
    glm::mat3 nm{1.0f};  // object-to-world for normals
    // per-point shader parameters, in the order its surface variant takes them
    std::vector<std::vector<glm::vec3>> pointParams;
    uint32_t material = 0;
    bool flipNormals = false, smooth = false, cs = false, os = false;
    uint32_t primvars = 0;
    size_t chunks = 1;   // float4s a colour
    uint32_t flags = 0;  // the attribute record's flags
};

RibBuilder::MeshSetUp RibBuilder::meshSetUp(L loc, const VertexData& mesh,
                                            uint32_t extraFlags) {
    MeshSetUp m;
    const size_t np = mesh.p.size();
    // a prototype stays in its object space (normals too) and belongs to no solid
    m.prototype = extraFlags & RT_QF_PROTOTYPE;
    m.leaf = m.prototype ? -1 : solidLeafForSurface(loc);
    const glm::mat4& ctm = m_attrStack.back().ctm;
    m.nm = m.prototype ? glm::mat3(1.0f) : glm::transpose(glm::inverse(glm::mat3(ctm)));
    // Per-point shader parameters: their surface variant gets them in the same order
    // (a prototype's, in its object space, are laid out for its instances' surfaces)
    for (const VertexData::PointParam& p : mesh.params) {
        m.pointParams.push_back(m.prototype ? p.v : pointParamToWorld(ctm, p));
        if (p.piece == 0 && !m.prototype)
            m_carriedPointParams.push_back({p.name, p.floats});
    }
    if (!m.pointParams.empty()) startTrianglePointParams();
    m.material = currentMaterial();
    m_carriedPointParams.clear();
    // RI's geometric normal: the world-space cross product, reversed for inside-out
    // primitives and mirrored transforms (prototypes: their object space, unmirrored)
    m.flipNormals = m.prototype ? m_attrStack.back().insideOut : flipWorldNormals();
    m.smooth = mesh.n.size() == np;
    m.cs = mesh.cs.size() == np || mesh.csN.size() == np;
    m.os = mesh.os.size() == np || mesh.osN.size() == np;
    m.primvars = (mesh.st.size() == np ? RT_PRIMVAR_ST : 0u) |
                 (m.cs ? RT_PRIMVAR_CS : 0u) | (m.os ? RT_PRIMVAR_OS : 0u);
    if (m.smooth) m_world.anySmoothNormals = true;
    m.chunks = size_t(m_world.colors.lanes() / 4);
    startPrimvar(m_world, m.primvars, RT_PRIMVAR_ST, m_world.vertexSt, 1);
    startPrimvar(m_world, m.primvars, RT_PRIMVAR_CS, m_world.vertexCs, m.chunks);
    startPrimvar(m_world, m.primvars, RT_PRIMVAR_OS, m_world.vertexOs, m.chunks);
    m.flags = (m.leaf >= 0 ? uint32_t(RT_QF_CSG_MEMBER) : 0u) | extraFlags |
              (m.flipNormals ? uint32_t(RT_QF_FLIP) : 0u);
    return m;
}

void RibBuilder::appendTriangles(L loc, const VertexData& mesh,
                                 const std::vector<glm::vec3>& wp,
                                 const MeshMotion* motion, uint32_t extraFlags) {
    const MeshSetUp m = meshSetUp(loc, mesh, extraFlags);
    // Degenerate input is left out (or, for normals, replaced by the geometric normal)
    // and reported once per request, at its file:line.
    DefectCounts counts;
    const std::vector<Defect> defects =
        triangleDefects(mesh.tris, wp, motion ? &motion->keys : nullptr);
    for (size_t k = 0; k < defects.size(); ++k) {
        if (leftOut(defects[k], counts, m_degenerate)) continue;
        const std::array<int, 3> corners{mesh.tris[3 * k], mesh.tris[3 * k + 1],
                                         mesh.tris[3 * k + 2]};
        if (!appendTriangle(loc, m, mesh, wp, motion, corners)) ++counts.badNormal;
    }
    const std::string what = describeDefects(counts);
    if (!what.empty() && m_warnedAt.insert({loc.file, loc.line}).second)
        m_diag.warning(loc, "degenerate geometry: " + what);
}

bool RibBuilder::appendTriangle(L loc, const MeshSetUp& m, const VertexData& mesh,
                                const std::vector<glm::vec3>& wp,
                                const MeshMotion* motion,
                                const std::array<int, 3>& corners) {
    const auto [i0, i1, i2] = corners;
    const glm::vec3 &a = wp[i0], &b = wp[i1], &c = wp[i2];
    if (m.leaf >= 0) {
        m_solidNodes[m.leaf].members.push_back(uint32_t(m_world.triangles.size()));
        m_solidNodes[m.leaf].memberWhat.push_back("mesh at " + loc.str());
    }
    m_world.triangles.push_back({f4(a), f4(b), f4(c)});
    if (!m_world.triangleParams.empty() || !m.pointParams.empty()) {
        startTrianglePointParams();
        m_world.triangleParams.back() = m.pointParams.empty()
                                            ? RT_NO_POINT_PARAMS
                                            : uint32_t(m_world.pointParamValues.size());
        for (int k : corners)
            for (const std::vector<glm::vec3>& v : m.pointParams)
                m_world.pointParamValues.push_back(f4(v[size_t(k)]));
    }
    if (int light = m_attrStack.back().areaLight; light >= 0 && !m.prototype)
        m_world.areaLightTriangles[uint32_t(light)].push_back(
            m.flipNormals ? std::array<glm::vec3, 3>{a, c, b}
                          : std::array<glm::vec3, 3>{a, b, c});
    m_world.attrs.push_back({m.material, m.smooth ? 1u : 0u, m.primvars, m.flags});
    if (motion) {
        std::vector<Triangle> keys;
        for (const std::vector<glm::vec3>& key : motion->keys)
            keys.push_back(
                {f4(key[size_t(i0)]), f4(key[size_t(i1)]), f4(key[size_t(i2)])});
        addTriangleMotion(m_world, keys, motion->times);
    }
    const bool normalsOk = appendCorners(m, mesh, corners);
    if (motion && m.smooth && normalsOk && !motion->normals.empty())
        addKeyNormals(*motion, corners);
    return normalsOk;
}

// The corners' normals (all three zero where one is zero or not finite: the device then
// uses Ng) and primitive variables.
bool RibBuilder::appendCorners(const MeshSetUp& m, const VertexData& mesh,
                               const std::array<int, 3>& corners) {
    bool normalsOk = true;
    for (int k : corners) {
        glm::vec3 n = m.smooth ? m.nm * mesh.n[k] : glm::vec3(1.0f);
        normalsOk = normalsOk && finite3(n) && glm::dot(n, n) > 0.0f &&
                    std::isfinite(glm::dot(n, n));
    }
    for (int k : corners) {
        m_world.normals.push_back(
            m.smooth && normalsOk ? f4(glm::normalize(m.nm * mesh.n[k])) : f4(0, 0, 0));
        if (m_world.primvarsUsed & RT_PRIMVAR_ST)
            m_world.vertexSt.push_back((m.primvars & RT_PRIMVAR_ST)
                                           ? f4(mesh.st[k].x, mesh.st[k].y, 0)
                                           : f4(0, 0, 0));
        if (m_world.primvarsUsed & RT_PRIMVAR_CS)
            pushCornerColor(m_world.vertexCs, m.chunks, m.cs, mesh.cs, mesh.csN, k);
        if (m_world.primvarsUsed & RT_PRIMVAR_OS)
            pushCornerColor(m_world.vertexOs, m.chunks, m.os, mesh.os, mesh.osN, k);
    }
    return normalsOk;
}

std::optional<std::vector<std::pair<std::string, int>>> RibBuilder::sharedPointParams(
    const ObjectDef& def) {
    std::optional<std::vector<std::pair<std::string, int>>> list;
    for (const VertexData& piece : def.meshes) {
        if (piece.params.empty()) continue;
        std::vector<std::pair<std::string, int>> own;
        for (const VertexData::PointParam& p : piece.params) {
            if (p.kind != VertexData::Kind::Float && p.kind != VertexData::Kind::Color)
                return std::nullopt;
            if (p.piece == 0) own.push_back({p.name, p.floats});
        }
        if (list && *list != own) return std::nullopt;
        list = std::move(own);
    }
    return list ? list : std::vector<std::pair<std::string, int>>{};
}

void RibBuilder::addInstance(
    L loc, const std::string& handle, const ObjectDef& def,
    const std::vector<std::pair<std::string, int>>& pointParams) {
    if (def.meshes.empty()) return;
    auto [it, fresh] = m_prototypes.try_emplace(handle, uint32_t(m_world.prototypes.size()));
    if (fresh) {
        Scene::Prototype p;
        p.firstTriangle = uint32_t(m_world.triangles.size());
        p.lo = glm::vec3(FLT_MAX);
        p.hi = glm::vec3(-FLT_MAX);
        for (const VertexData& piece : def.meshes) {
            appendTriangles(loc, piece, piece.p, nullptr, RT_QF_PROTOTYPE);
            for (const glm::vec3& v : piece.p)
                if (finite3(v)) p.lo = glm::min(p.lo, v), p.hi = glm::max(p.hi, v);
        }
        p.triangleCount = uint32_t(m_world.triangles.size()) - p.firstTriangle;
        m_world.prototypes.push_back(p);
    }
    const Scene::Prototype& p = m_world.prototypes[it->second];
    if (p.triangleCount == 0) return;
    Quadric q{};
    q.kind = RT_Q_INSTANCE;
    q.first_member = it->second;  // the renderer replaces it with the prototype's BVH root
    q.primvars = RT_NO_QUADRIC_PRIMVARS;
    q.point_params = RT_NO_POINT_PARAMS;
    // the prototype's per-point values are laid out as this surface takes them
    m_carriedPointParams = pointParams;
    q.material = currentMaterial();
    m_carriedPointParams.clear();
    if (!placeQuadric(q, eyeRelative(m_attrStack.back().ctm, glm::mat4(1.0f)))) {
        m_diag.warning(loc, "ObjectInstance: singular or non-finite transform, left out");
        return;
    }
    addObjectRecord(loc, "ObjectInstance", q, p.lo, p.hi, glm::mat4(1.0f));
}

static_assert(std::tuple_size<VertexData::Channels>::value == ColorSamples::kMaxChannels);

void RibBuilder::readVertexNormals(const rib::ParamList& params, size_t np,
                                   VertexData& mesh) {
    const rib::Param* q = params.find("N");
    if (!q || q->floats.size() != 3 * np) return;
    mesh.n.resize(np);
    for (size_t i = 0; i < np; ++i)
        mesh.n[i] = {q->floats[3 * i], q->floats[3 * i + 1], q->floats[3 * i + 2]};
}

// Like every begin-end pair but TransformBegin and MotionBegin, an object block saves
// and restores the attributes, the transform with them (RI 3.2, section 4).
void RibBuilder::objectBegin(L loc, const std::string& handle) {
    m_attrStack.push_back(m_attrStack.back());
    if (m_defining) {
        m_diag.error(loc, "ObjectBegin inside ObjectBegin");
        return;
    }
    m_defining = &m_objects[handle];
    *m_defining = ObjectDef();
    m_definingCtm = m_attrStack.back().ctm;
}

void RibBuilder::objectEnd(L) {
    m_defining = nullptr;
    if (m_attrStack.size() > 1) m_attrStack.pop_back();
}

void RibBuilder::objectInstance(L loc, const std::string& handle) {
    auto it = m_objects.find(handle);
    if (it == m_objects.end() || m_defining) {
        m_diag.error(loc, m_defining
                              ? "ObjectInstance inside ObjectBegin"
                              : "ObjectInstance of undefined object \"" + handle + "\"");
        return;
    }
    // Each instance is placed by the current transform with the current shading
    // attributes. Meshes are shared (a prototype under its own BVH, reached through
    // the instance's record), except inside a solid, with per-point values that each
    // instance moves, or truly displaced, where they are copied; quadrics are one record
    // each anyway. (A displaced instance's copy is diced and displaced where it is, with
    // its own object space, as a shader that reads P or "object" space needs: a shared
    // prototype would be displaced once for every instance.)
    if (m_attrStack.back().lodHidden) return;  // (DetailRange)
    const ObjectDef& def = it->second;
    if (const auto shared = sharedPointParams(def);
        m_solidStack.empty() && shared && !m_attrStack.back().displacesTruly()) {
        addInstance(loc, handle, def, *shared);
    } else {
        for (const VertexData& piece : def.meshes) addMesh(loc, piece);
    }
    if (m_attrStack.back().displacesTruly()) {
        // its quadrics made again where the instance stands: diced, then displaced
        Attributes& a = m_attrStack.back();
        const Placement saved = a;
        for (const auto& [toObject, call] : def.quadricCalls) {
            a.ctm = saved.ctm * toObject;
            a.ctmEnd = saved.ctmEnd * toObject;
            for (size_t k = 0; k < a.between.size(); ++k)
                a.between[k].second = saved.between[k].second * toObject;
            call();
        }
        static_cast<Placement&>(a) = saved;
        return;
    }
    for (size_t i = 0; i < def.quadrics.size(); ++i) {
        const QuadricShape& q = def.quadrics[i];
        addQuadric(loc, quadricKindName(q.q.kind), q, def.quadricParams[i],
                   quadricPlacement(q.q));
    }
}

void RibBuilder::keepQuadricCall(std::function<void()> call) {
    // (a quadric that is not exact here, under MotionBegin for one, is a mesh of the
    // object already)
    if (!m_defining || !exactQuadrics()) return;
    m_defining->quadricCalls.push_back(
        {glm::inverse(m_definingCtm) * m_attrStack.back().ctm, std::move(call)});
}

}  // namespace rd
