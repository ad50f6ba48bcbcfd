// true_displacement.cpp: running the displacement shaders at the diced vertices and
// moving the diced surfaces (true_displacement.h).
#include "true_displacement.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "device_scene.h"
#include "host/scene/triangle_motion.h"

namespace rd {

namespace {

glm::vec3 v3(const rt_float4& f) {
    return glm::vec3(f.x, f.y, f.z);
}

// Normals of the moved surface: the shader's N at each vertex (as a REYES renderer
// shades with the N its displacement leaves: calculatenormal(P) of the moved points, or
// a bump on top), else, where it is not usable, the pieces' normals about the vertex
// weighted by their areas; turned to the side the surface's own normal was on.
void remakeNormals(Scene& s, const DicedSurfaces& d, const std::vector<rt_float4>& moved,
                   const std::vector<rt_float4>& shaderN) {
    std::vector<glm::dvec3> sum(moved.size(), glm::dvec3(0.0));
    const size_t pieces = d.cornerVertex.size() / 3;
    for (size_t i = 0; i < pieces; ++i) {
        const uint32_t* v = &d.cornerVertex[3 * i];
        const glm::dvec3 a = v3(moved[v[0]]), b = v3(moved[v[1]]), c = v3(moved[v[2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k) sum[v[k]] += n;
    }
    for (size_t i = 0; i < pieces; ++i)
        for (int k = 0; k < 3; ++k) {
            rt_float4& stored = s.normals[3 * (d.firstTriangle + i) + size_t(k)];
            const uint32_t v = d.cornerVertex[3 * i + size_t(k)];
            glm::dvec3 n = glm::dvec3(v3(shaderN[v]));
            if (!(glm::length(n) > 0.5) || !std::isfinite(glm::length(n))) n = sum[v];
            const double len = glm::length(n);
            if (!(len > 0.0) || !std::isfinite(len))
                continue;  // keep the undisplaced one
            n /= len;
            if (glm::dot(n, glm::dvec3(v3(stored))) < 0.0) n = -n;
            stored = {float(n.x), float(n.y), float(n.z), 0.0f};
        }
}

// The linear map that takes a triangle's first key to another: its edges to the key's
// edges and its normal (as long as an edge) to the key's. Exact for rigid motion and
// uniform scaling, which is what transform motion blur gives; the identity for a
// degenerate key.
glm::mat3 keyMap(const Triangle& from, const Triangle& to) {
    const glm::vec3 e1 = v3(from.v1) - v3(from.v0), e2 = v3(from.v2) - v3(from.v0);
    const glm::vec3 f1 = v3(to.v1) - v3(to.v0), f2 = v3(to.v2) - v3(to.v0);
    const glm::vec3 n = glm::cross(e1, e2), m = glm::cross(f1, f2);
    const float ln = glm::length(n), lm = glm::length(m);
    if (!(ln > 0.0f) || !(lm > 0.0f) || !std::isfinite(ln) || !std::isfinite(lm))
        return glm::mat3(1.0f);
    const glm::mat3 a(e1, e2, n / std::sqrt(ln)), b(f1, f2, m / std::sqrt(lm));
    const float det = glm::determinant(a);
    if (!(std::fabs(det) > 0.0f)) return glm::mat3(1.0f);
    const glm::mat3 map = b * glm::inverse(a);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(map[c][r])) return glm::mat3(1.0f);
    return map;
}

// The diced pieces of moving surfaces. The shader ran on their first key
// (displace_vertices.cl); each vertex's offset is carried to the later keys by the
// motion from the first key to each (keyMap of the piece's original triangle), as a
// REYES renderer moves a grid it displaced at shutter open. A vertex's places on the keys
// are computed once, from its first corner, and given to every piece that shares it, so
// the surface stays closed at every key. Called before the pieces' first keys move (the
// offsets are taken from them).
void moveKeys(Scene& s, const DicedSurfaces& d, const std::vector<rt_float4>& moved,
              const std::vector<uint8_t>& left) {
    const size_t pieces = d.cornerVertex.size() / 3;
    auto isMoving = [&](size_t piece) {
        return (s.attrs[piece].flags & RT_QF_MOVING) && piece < s.trianglesEnd.size();
    };
    auto cornerOf = [](const Triangle& t, uint32_t c) {
        return v3(c == 0 ? t.v0 : c == 1 ? t.v1 : t.v2);
    };
    std::map<uint32_t, std::vector<glm::mat3>> maps;  // by original triangle, every key
    auto mapsOf = [&](uint32_t source) -> const std::vector<glm::mat3>& {
        auto [it, fresh] = maps.try_emplace(source);
        if (fresh)
            for (const Triangle& key : triangleKeys(s, source).keys)
                it->second.push_back(keyMap(s.triangles[source], key));
        return it->second;
    };
    // each vertex's places on the keys after the first
    std::vector<std::vector<glm::vec3>> places(moved.size());
    for (size_t v = 0; v < moved.size(); ++v) {
        const uint32_t piece = d.vertexCorner[v][0], corner = d.vertexCorner[v][1];
        if (!isMoving(piece)) continue;
        const std::vector<glm::mat3>& m = mapsOf(d.pieceSource[piece - d.firstTriangle]);
        const std::vector<Triangle> keys = triangleKeys(s, piece).keys;
        if (keys.size() != m.size()) continue;
        const glm::vec3 offset =
            left[v] ? glm::vec3(0.0f)
                    : v3(moved[v]) - cornerOf(s.triangles[piece], corner);
        for (size_t j = 0; j < keys.size(); ++j)
            places[v].push_back(cornerOf(keys[j], corner) + m[j] * offset);
    }
    for (size_t i = 0; i < pieces; ++i) {
        const size_t piece = d.firstTriangle + i;
        if (!isMoving(piece)) continue;
        std::vector<Triangle> keys = triangleKeys(s, piece).keys;
        for (int c = 0; c < 3; ++c) {
            const std::vector<glm::vec3>& at = places[d.cornerVertex[3 * i + size_t(c)]];
            if (at.size() != keys.size()) continue;  // (welded to a still vertex)
            for (size_t j = 0; j < keys.size(); ++j) {
                rt_float4& p = c == 0 ? keys[j].v0 : c == 1 ? keys[j].v1 : keys[j].v2;
                p.x = at[j].x, p.y = at[j].y, p.z = at[j].z;
            }
        }
        setTriangleKeys(s, piece, keys);
    }
}

// The moving pieces' boxes over their displaced keys.
void refitMotionBounds(Scene& s, const DicedSurfaces& d) {
    const size_t pieces = d.cornerVertex.size() / 3;
    for (size_t q = 0; q < s.quadrics.size(); ++q)
        if (s.quadrics[q].kind == RT_Q_MOVING_TRIANGLE &&
            s.quadrics[q].first_member >= d.firstTriangle &&
            s.quadrics[q].first_member - d.firstTriangle < pieces)
            s.quadricBounds[q] = triangleMotionBounds(s, s.quadrics[q].first_member);
}

// The displacement shaders' passes over the diced vertices: each pass runs the vertices
// still pending, and those whose texture tiles missed run again once the tiles are in
// (a vertex whose tiles keep missing, a cache too small for one vertex's lookups, is
// given up after kMaxPasses). Leaves each vertex's moved place and shader normal; the
// ones given up on are listed in `unresolved`.
struct DisplacementPasses {
    std::vector<rt_float4> moved, shaderN;
    std::vector<uint32_t> unresolved;
    size_t passes = 0;
};

DisplacementPasses runDisplacementPasses(const ClContext& ctx, cl_program program,
                                         Profiler& prof, const DeviceScene& ds,
                                         const DicedSurfaces& diced, const Features& f,
                                         TextureSet& textures, const DicingView& view,
                                         float eyeWidth) {
    constexpr size_t kMaxPasses = 256;
    DisplacementPasses out;
    const size_t nv = diced.vertexCorner.size();
    std::vector<cl_uint2> corners(nv);
    std::vector<uint32_t> pending(nv);
    for (size_t i = 0; i < nv; ++i) {
        corners[i] = {{diced.vertexCorner[i][0], diced.vertexCorner[i][1]}};
        pending[i] = uint32_t(i);
    }
    DeviceBuffer<cl_uint2> cornerBuf(ctx, corners);
    DeviceBuffer<rt_float4> movedBuf(ctx, nv), normalBuf(ctx, nv);
    DeviceBuffer<uint32_t> listA(ctx, pending), listB(ctx, nv + 1);
    Kernel displace(ctx, program, "displace_vertices", prof);
    const rt_float4 eye = {view.eye.x, view.eye.y, view.eye.z, 0.0f};
    const std::vector<std::string> names = {"displacement"};
    size_t count = nv;
    while (count > 0) {
        const uint32_t zero = 0;
        listB.uploadRange(0, &zero, 1);
        displace.launch(count, cl_uint(count), listA, cornerBuf, movedBuf, normalBuf, eye,
                        eyeWidth, ds.triangles, ds.attrs, ds.normals, ds.vertexSt,
                        ds.vertexCs, ds.vertexOs, ds.materials, ds.materialChannels,
                        ds.quadrics, ds.quadricPrimvars, ds.quadricMotion,
                        ds.trianglesEnd, ds.params, ds.triangleParams,
                        ds.pointParamValues, ds.pointParamLayout, textures.infoBuf,
                        textures.pageBuf, textures.tileBuf, textures.requestBuf,
                        textures.counterBuf, textures.usedBuf, listB);
        ++out.passes;
        count = listB.downloadFirst(1)[0];
        if (f.textures) {
            const uint32_t asked = textures.counterBuf.downloadFirst(1)[0];
            if (asked > 0) {
                std::vector<TexRequest> req = textures.requestBuf.downloadFirst(
                    std::min<size_t>(asked, TextureSet::kMaxRequests));
                textures.counterBuf.uploadRange(0, &zero, 1);
                textures.serve(req, names);
            }
        }
        if (count == 0) break;
        // the vertices to run again, from the list's second entry on
        std::vector<uint32_t> again = listB.downloadFirst(count + 1);
        if (out.passes >= kMaxPasses) {
            out.unresolved.assign(again.begin() + 1, again.end());
            break;
        }
        listA.uploadRange(0, again.data() + 1, count);
    }
    displace.collectActive();
    out.moved = movedBuf.download();
    out.shaderN = normalBuf.download();
    return out;
}

// Vertices given up on (and never written) or moved to NaN stay where they were: marked
// in the result (1), counted in the report by their displacement shader.
std::vector<uint8_t> keepBadVertices(const Scene& scene, const DicedSurfaces& diced,
                                     DisplacementPasses& d, DisplacementReport& r) {
    const size_t nv = diced.vertexCorner.size();
    std::vector<uint8_t> left(nv, 0);
    for (uint32_t v : d.unresolved) left[v] = 1;
    for (size_t i = 0; i < nv; ++i) {
        const Triangle& t = scene.triangles[diced.vertexCorner[i][0]];
        const uint32_t k = diced.vertexCorner[i][1];
        const rt_float4& p = k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
        const rt_float4& m = d.moved[i];
        if (!left[i] &&
            !(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z))) {
            ++r.nonFinite;
            const Material& mat =
                scene.materials[scene.attrs[diced.vertexCorner[i][0]].material];
            ++r.nonFiniteBy[((mat.flags & RT_MATERIAL_DISPLACEMENT_MASK) >>
                             RT_MATERIAL_DISPLACEMENT_SHIFT) -
                            1];
            left[i] = 1;
        }
        if (left[i]) d.moved[i] = {p.x, p.y, p.z, 0.0f}, d.shaderN[i] = {0, 0, 0, 0};
    }
    return left;
}

}  // namespace

DisplacementReport displaceDicedSurfaces(const ClContext& ctx, cl_program program,
                                         Profiler& prof, Scene& scene,
                                         const DicedSurfaces& diced, const Features& f,
                                         const ShadingSetup& shading,
                                         TextureSet& textures, const DicingView& view,
                                         float eyeWidth) {
    DisplacementReport r;
    const size_t nv = diced.vertexCorner.size();
    if (nv == 0) return r;
    // The scene's arrays as the shade stage reads them (no tree: nothing is traced).
    DeviceScene ds(ctx, scene, SceneBvh{}, f, shading);
    if (!shading.prepares.empty()) {  // the shaders' uniform work, as for shading
        Kernel prepare(ctx, program, "rd_prepare_uniforms", prof);
        prepare.launch(shading.prepares.size(), cl_uint(shading.prepares.size()),
                       ds.params);
        prepare.collectActive();
    }
    DisplacementPasses d =
        runDisplacementPasses(ctx, program, prof, ds, diced, f, textures, view, eyeWidth);
    r.passes = d.passes;
    r.unresolved = d.unresolved.size();
    const std::vector<uint8_t> left = keepBadVertices(scene, diced, d, r);
    r.vertices = nv - size_t(std::count(left.begin(), left.end(), uint8_t(1)));
    moveKeys(scene, diced, d.moved, left);
    for (size_t i = 0; i < diced.cornerVertex.size() / 3; ++i) {
        Triangle& t = scene.triangles[diced.firstTriangle + i];
        t.v0 = d.moved[diced.cornerVertex[3 * i]];
        t.v1 = d.moved[diced.cornerVertex[3 * i + 1]];
        t.v2 = d.moved[diced.cornerVertex[3 * i + 2]];
    }
    remakeNormals(scene, diced, d.moved, d.shaderN);
    refitMotionBounds(scene, diced);
    return r;
}

namespace {
rib::SourceLoc displacementLoc(const Scene& scene) {
    return scene.displacements.empty() ? rib::SourceLoc{scene.sourceFile, 0}
                                       : scene.displacements.front().loc;
}
}  // namespace

void reportDicing(const DicedSurfaces& d, const Scene& scene, rib::Diagnostics& diag) {
    const rib::SourceLoc loc = displacementLoc(scene);
    if (d.skipped > 0)
        diag.warning(loc, std::to_string(d.skipped) +
                              " truly displaced triangle(s) in a solid: "
                              "bump mapped instead");
    if (d.coarsening > 1.0f)
        diag.warning(loc, "true displacement diced " + std::to_string(int(d.coarsening)) +
                              "x coarser than ShadingRate asks, to stay within " +
                              std::to_string(d.budget) +
                              " triangles (Option \"limits\" \"dicedtriangles\")");
    if (d.truncated)
        diag.warning(loc,
                     "true displacement: the dicing budget ran out; some surfaces are "
                     "left undisplaced");
}

void reportDisplacement(const DisplacementReport& r, const Scene& scene,
                        rib::Diagnostics& diag) {
    const rib::SourceLoc loc = displacementLoc(scene);
    for (const auto& [index, count] : r.nonFiniteBy)
        diag.warning(
            index < scene.displacements.size() ? scene.displacements[index].loc : loc,
            "displacement moved " + std::to_string(count) +
                " vertices to NaN or Inf; they are left in place");
    if (r.unresolved > 0)
        diag.warning(loc, "displacement: the texture cache could not hold what " +
                              std::to_string(r.unresolved) +
                              " vertices look up; they are left in place");
}

}  // namespace rd
