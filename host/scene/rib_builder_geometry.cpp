// rib_builder_geometry.cpp: the RenderMan surfaces other than polygons. Quadrics are kept
// exact (quadric_shapes.h) unless Option "render" "exactquadrics" 0 asks for triangles;
// the rest is tessellated in object space at a density chosen from its size on screen
// (chord error about a tenth of a pixel for quadrics, a few pixels per patch segment),
// then added as triangles in world space like any mesh.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "rib_builder.h"
#include "teapot.h"
#include "tessellate_blobby.h"
#include "tessellate_curves_points.h"
#include "tessellate_polygons.h"
#include "tessellate_quadrics.h"
#include "tessellate_subdiv.h"

namespace rd {
namespace {

std::vector<glm::vec3> points3(const std::vector<float>& f) {
    std::vector<glm::vec3> p(f.size() / 3);
    for (size_t i = 0; i < p.size(); ++i) p[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    return p;
}

// Segments for a quadric of screen radius rpx around a full turn: 0.1 pixel chord error.
int turnSegments(float rpx) { return circleSegments(rpx, 0.1f); }

// Segments per patch: about one per 4 pixels of its size, within [4, 64].
int patchSegments(float rpx) { return std::clamp(int(std::ceil(rpx / 2.0f)), 4, 64); }

}  // namespace

float RibBuilder::screenRadius(const glm::vec3& centre, float radius) const {
    const glm::mat4 objToCam = m_world.camera.worldToCamera * m_attrStack.back().ctm;
    glm::vec3 c = glm::vec3(objToCam * glm::vec4(centre, 1.0f));
    float scale = std::cbrt(std::fabs(glm::determinant(glm::mat3(objToCam))));
    float r = std::fabs(radius) * scale;
    // A truly displaced surface is diced again to its ShadingRate (dice_displaced.h):
    // its tessellation need only follow its curvature.
    const float most = m_attrStack.back().displacesTruly() ? 1000.0f : 1e6f;
    if (c.z - r <= 0.0f) return most;  // reaches the camera plane: the finest dicing
    return std::min(r * pixelsPerUnit(c.z), most);
}

float RibBuilder::screenRadius(const std::vector<glm::vec3>& pts) const {
    if (pts.empty()) return 0.0f;
    glm::vec3 lo = pts[0], hi = pts[0];
    for (const glm::vec3& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return screenRadius(0.5f * (lo + hi), 0.5f * glm::length(hi - lo));
}

void RibBuilder::addSurface(L loc, const char* what, bool ok, const SurfaceMesh& m,
                            const std::string& err,
                            const std::function<void(VertexData&)>& perPoint) {
    if (!ok) {  // (the tessellators' messages may name the request themselves)
        m_diag.error(loc, err.rfind(what, 0) == 0 ? err : std::string(what) + ": " + err);
        return;
    }
    VertexData mesh;
    mesh.p = m.mesh.p, mesh.n = m.mesh.n, mesh.tris = m.mesh.tris;
    if (m.st.size() == m.mesh.p.size()) mesh.st = m.st;
    // a diced quadric's per-point parameters: bilinear in its corner values at each
    // vertex's (u, v), which the dicer gave as st
    static const std::set<std::string> quadrics = {"Cylinder", "Cone", "Disk", "Paraboloid",
                                                   "Hyperboloid", "Torus"};
    if (m_primVars && quadrics.count(what) && mesh.st.size() == mesh.p.size())
        cornerPointParams(*m_primVars, mesh, /*withStandard=*/true);
    // TextureCoordinates: s, t bilinear over the parametric (u, v) the dicer gave as st
    const Attributes& a = m_attrStack.back();
    for (glm::vec2& st : mesh.st) {
        const float u = st.x, v = st.y;
        const float w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
        st = glm::vec2(0.0f);
        for (int k = 0; k < 4; ++k) st += w[k] * glm::vec2(a.texS[k], a.texT[k]);
    }
    if (perPoint) perPoint(mesh);
    // Cs, Os and st given per point came through the same interpolation as the
    // parameters (given st replaces the (u, v) mapped by TextureCoordinates)
    takeStandardPointValues(mesh, m_world.colors.slots());
    addMesh(loc, mesh);
}

void RibBuilder::addQuadric(L loc, const char* what, QuadricShape shape,
                            const rib::ParamList& params, const glm::mat4& placement) {
    if (!shape.error.empty()) {
        m_diag.error(loc, std::string(what) + ": " + shape.error);
        return;
    }
    if (m_attrStack.back().displacesTruly())  // (only in a solid: its members stay exact)
        m_diag.warning(loc,
                       std::string(what) +
                           " in a solid stays exact: its displacement is a bump map");
    Quadric& q = shape.q;
    quadricTextureCoordinates(q, params, placement);
    if (m_motion.active && m_motion.count++ > 0) {
        // a quadric's keys with other parameters: only the first is used
        if (m_motion.count == 2)
            m_diag.warning(loc, std::string(what) + ": motion of quadric parameters is not "
                                                    "supported; the first key is used");
        return;
    }
    if (m_defining) {
        // keep it in the object's space: its matrices map it there; instances compose
        glm::mat4 toObject = glm::inverse(m_definingCtm) * m_attrStack.back().ctm;
        if (!placeQuadric(q, toObject)) {
            m_diag.warning(loc, std::string(what) + ": singular transform, left out");
            return;
        }
        m_defining->quadrics.push_back(shape);
        m_defining->quadricParams.push_back(params);  // each instance reads them
        return;
    }
    if (!placeQuadric(q, eyeRelative(m_attrStack.back().ctm, placement))) {
        m_diag.warning(loc, std::string(what) + ": singular or non-finite transform, left out");
        return;
    }
    quadricMaterial(q, params, placement);
    const int leaf = solidLeafForSurface(loc);
    uint32_t index = uint32_t(m_world.quadrics.size());
    if (leaf >= 0) {
        q.flags |= RT_QF_CSG_MEMBER;
        m_solidNodes[leaf].members.push_back(RT_OBJECT_BIT | index);
        m_solidNodes[leaf].memberWhat.push_back(std::string(what) + " at " + loc.str());
    }
    addObjectRecord(loc, what, q, shape.lo, shape.hi, placement);
}

// s and t at a quadric's (u, v) corners: TextureCoordinates (not for an instance's copy),
// else varying "st" or "s" and "t" given with the request.
void RibBuilder::quadricTextureCoordinates(Quadric& q, const rib::ParamList& params,
                                           const glm::mat4& placement) const {
    if (placement ==
        glm::mat4(1.0f)) {  // not an instance's copy: TextureCoordinates apply
        const Attributes& current = m_attrStack.back();
        q.st_s = {current.texS[0], current.texS[1], current.texS[2], current.texS[3]};
        q.st_t = {current.texT[0], current.texT[1], current.texT[2], current.texT[3]};
    }
    // varying s, t: one value per (u, v) corner
    const rib::Param* st = params.find("st");
    const rib::Param* ps = params.find("s");
    const rib::Param* pt = params.find("t");
    if (st && st->floats.size() == 8) {
        q.st_s = {st->floats[0], st->floats[2], st->floats[4], st->floats[6]};
        q.st_t = {st->floats[1], st->floats[3], st->floats[5], st->floats[7]};
    } else if (ps && pt && ps->floats.size() == 4 && pt->floats.size() == 4) {
        q.st_s = {ps->floats[0], ps->floats[1], ps->floats[2], ps->floats[3]};
        q.st_t = {pt->floats[0], pt->floats[1], pt->floats[2], pt->floats[3]};
    }
}

// A quadric's material (constant or uniform Cs and Os, its per-point shader parameters)
// and its varying Cs and Os, one per corner, in the quadric primvar buffer.
void RibBuilder::quadricMaterial(Quadric& q, const rib::ParamList& params,
                                 const glm::mat4& placement) {
    // (in the scene's colour channels, k floats a colour)
    Attributes& attrs = m_attrStack.back();
    const size_t k = size_t(m_world.colors.slots());
    const Attributes saved = attrs;
    const rib::Param* cs = params.find("Cs");
    const rib::Param* os = params.find("Os");
    if (cs && cs->floats.size() == k) std::copy_n(cs->floats.begin(), k, attrs.color);
    if (os && os->floats.size() == k) std::copy_n(os->floats.begin(), k, attrs.opacity);
    // per-point shader parameters at the (u, v) corners, when this request gives them
    q.point_params = quadricPointParams(params, m_attrStack.back().ctm * placement);
    for (const rib::Param* p : pointParamsOf(&params))
        m_carriedPointParams.push_back({p->name, p->components()});
    q.material = currentMaterial();
    m_carriedPointParams.clear();
    if (m_attrStack.back().insideOut) q.flags ^= RT_QF_FLIP;  // the normal transform keeps mirrors
    const bool varyingCs = cs && cs->floats.size() == 4 * k;
    const bool varyingOs = os && os->floats.size() == 4 * k;
    q.primvars = RT_NO_QUADRIC_PRIMVARS;
    if (varyingCs || varyingOs) {  // Cs then Os at the four corners, each in chunks
        q.primvars = uint32_t(m_world.quadricPrimvars.size());
        const size_t chunks = size_t(m_world.colors.lanes() / 4);
        for (size_t c = 0; c < 8; ++c) {
            const bool opacity = c >= 4;
            const rib::Param* p = opacity ? (varyingOs ? os : nullptr) : (varyingCs ? cs : nullptr);
            const float* v = p         ? &p->floats[k * (c % 4)]
                             : opacity ? attrs.opacity
                                       : attrs.color;
            float lanes[16] = {};
            std::copy_n(v, k, lanes);
            for (size_t j = 0; j < chunks; ++j)
                m_world.quadricPrimvars.push_back(
                    {lanes[4 * j], lanes[4 * j + 1], lanes[4 * j + 2], lanes[4 * j + 3]});
        }
    }
    std::copy_n(saved.color, ColorSamples::kMaxChannels, attrs.color);
    std::copy_n(saved.opacity, ColorSamples::kMaxChannels, attrs.opacity);
}

glm::mat4 RibBuilder::eyeRelative(const glm::mat4& ctm, const glm::mat4& placement) const {
    // camera-relative world, composed in double like meshes (see worldBegin)
    glm::dmat4 d = glm::dmat4(ctm) * glm::dmat4(placement);
    d[3] -= glm::dvec4(m_origin, 0.0);
    return glm::mat4(d);
}

void RibBuilder::addObjectRecord(L loc, const char* what, Quadric q, glm::vec3 lo, glm::vec3 hi,
                                 const glm::mat4& placement) {
    const Attributes& at = m_attrStack.back();
    Aabb bounds = quadricWorldBounds(q, lo, hi);
    if (at.moving) {  // motion blur: the last key's placement, interpolated by ray time
        Quadric last = q;
        if (!placeQuadric(last, eyeRelative(at.ctmEnd, placement))) {
            m_diag.warning(loc, std::string(what) + ": singular motion key, left still");
        } else {
            q.flags |= RT_QF_MOVING;
            q.motion = uint32_t(m_world.quadricMotion.size());
            // the keys between after the last, counted in its row 1's w (quadric.h)
            std::vector<Quadric> between;
            for (const auto& [t, key] : at.between) {
                Quadric k = q;
                if (placeQuadric(k, eyeRelative(key, placement))) {
                    k.center.w = t;
                    between.push_back(k);
                }
            }
            rt_float4 c = last.center, r0 = last.to_world[0], r1 = last.to_world[1];
            c.w = at.t0;
            r0.w = at.t1;
            r1.w = float(between.size());
            for (const rt_float4& v : {c, r0, r1, last.to_world[2]})
                m_world.quadricMotion.push_back(v);
            bounds.grow(quadricWorldBounds(last, lo, hi));
            for (const Quadric& k : between) {
                for (const rt_float4& v :
                     {k.center, k.to_world[0], k.to_world[1], k.to_world[2]})
                    m_world.quadricMotion.push_back(v);
                bounds.grow(quadricWorldBounds(k, lo, hi));
            }
        }
    }
    m_world.quadrics.push_back(q);
    m_world.quadricBounds.push_back(bounds);
}

void RibBuilder::cylinder(L loc, float radius, float zmin, float zmax, float thetamax, P params) {
    if (!shown(loc, "Cylinder")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall([=, loc = rib::SourceLoc(loc), params = rib::ParamList(params)] {
            cylinder(loc, radius, zmin, zmax, thetamax, params);
        });
    if (exactQuadrics())
        return addQuadric(loc, "Cylinder", makeCylinder(radius, zmin, zmax, thetamax), params);
    SurfaceMesh m;
    std::string err;
    float rpx = screenRadius({0, 0, 0.5f * (zmin + zmax)},
                             std::max(std::fabs(radius), 0.5f * std::fabs(zmax - zmin)));
    const auto [nu, nv] = keySegments(turnSegments(rpx), 1);
    bool ok = tessellateCylinder(radius, zmin, zmax, thetamax, nu, nv, m, &err);
    addSurface(loc, "Cylinder", ok, m, err);
}

void RibBuilder::cone(L loc, float height, float radius, float thetamax, P params) {
    if (!shown(loc, "Cone")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall([=, loc = rib::SourceLoc(loc), params = rib::ParamList(params)] {
            cone(loc, height, radius, thetamax, params);
        });
    if (exactQuadrics())
        return addQuadric(loc, "Cone", makeCone(height, radius, thetamax), params);
    SurfaceMesh m;
    std::string err;
    float rpx = screenRadius({0, 0, 0.5f * height}, std::max(std::fabs(radius), std::fabs(height)));
    const int n = turnSegments(rpx);
    const auto [nu, nv] = keySegments(n, std::max(1, n / 8));
    bool ok = tessellateCone(height, radius, thetamax, nu, nv, m, &err);
    addSurface(loc, "Cone", ok, m, err);
}

void RibBuilder::disk(L loc, float height, float radius, float thetamax, P params) {
    if (!shown(loc, "Disk")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall([=, loc = rib::SourceLoc(loc), params = rib::ParamList(params)] {
            disk(loc, height, radius, thetamax, params);
        });
    if (exactQuadrics())
        return addQuadric(loc, "Disk", makeDisk(height, radius, thetamax), params);
    SurfaceMesh m;
    std::string err;
    const auto [nu, nv] =
        keySegments(turnSegments(screenRadius({0, 0, height}, radius)), 1);
    bool ok = tessellateDisk(height, radius, thetamax, nu, nv, m, &err);
    addSurface(loc, "Disk", ok, m, err);
}

void RibBuilder::torus(L loc, float majorRadius, float minorRadius, float phiMin, float phiMax,
                       float thetamax, P params) {
    if (!shown(loc, "Torus")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall([=, loc = rib::SourceLoc(loc), params = rib::ParamList(params)] {
            torus(loc, majorRadius, minorRadius, phiMin, phiMax, thetamax, params);
        });
    if (exactQuadrics())
        return addQuadric(loc, "Torus",
                          makeTorus(majorRadius, minorRadius, phiMin, phiMax, thetamax), params);
    SurfaceMesh m;
    std::string err;
    float rpx = screenRadius({0, 0, 0}, std::fabs(majorRadius) + std::fabs(minorRadius));
    const auto [nu, nv] = keySegments(
        turnSegments(rpx),
        turnSegments(rpx * std::fabs(minorRadius) /
                     std::max(1e-20f, std::fabs(majorRadius) + std::fabs(minorRadius))));
    bool ok = tessellateTorus(majorRadius, minorRadius, phiMin, phiMax, thetamax, nu, nv, m, &err);
    addSurface(loc, "Torus", ok, m, err);
}

void RibBuilder::paraboloid(L loc, float rmax, float zmin, float zmax, float thetamax,
                            P params) {
    if (!shown(loc, "Paraboloid")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall([=, loc = rib::SourceLoc(loc), params = rib::ParamList(params)] {
            paraboloid(loc, rmax, zmin, zmax, thetamax, params);
        });
    if (exactQuadrics())
        return addQuadric(loc, "Paraboloid", makeParaboloid(rmax, zmin, zmax, thetamax), params);
    SurfaceMesh m;
    std::string err;
    const int n = turnSegments(screenRadius(
        {0, 0, 0.5f * (zmin + zmax)}, std::max(std::fabs(rmax), std::fabs(zmax - zmin))));
    const auto [nu, nv] = keySegments(n, std::max(2, n / 4));
    bool ok = tessellateParaboloid(rmax, zmin, zmax, thetamax, nu, nv, m, &err);
    addSurface(loc, "Paraboloid", ok, m, err);
}

void RibBuilder::hyperboloid(L loc, const float p1[3], const float p2[3], float thetamax,
                             P params) {
    if (!shown(loc, "Hyperboloid")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall(
            [=, loc = rib::SourceLoc(loc), params = rib::ParamList(params),
             a = std::array<float, 6>{p1[0], p1[1], p1[2], p2[0], p2[1], p2[2]}] {
                hyperboloid(loc, a.data(), a.data() + 3, thetamax, params);
            });
    if (exactQuadrics())
        return addQuadric(loc, "Hyperboloid",
                          makeHyperboloid({p1[0], p1[1], p1[2]}, {p2[0], p2[1], p2[2]}, thetamax),
                          params);
    SurfaceMesh m;
    std::string err;
    glm::vec3 a(p1[0], p1[1], p1[2]), b(p2[0], p2[1], p2[2]);
    float r = std::max(glm::length(glm::vec2(a)), glm::length(glm::vec2(b)));
    const int n = turnSegments(
        screenRadius(0.5f * (a + b), std::max(r, 0.5f * glm::length(b - a))));
    const auto [nu, nv] = keySegments(n, std::max(2, n / 4));
    bool ok = tessellateHyperboloid(a, b, thetamax, nu, nv, m, &err);
    addSurface(loc, "Hyperboloid", ok, m, err);
}

void RibBuilder::generalPolygon(L loc, Ints nverts, P params) {
    if (!shown(loc, "GeneralPolygon")) return;
    const rib::Param* Pp = params.find("P");
    if (!Pp) return m_diag.error(loc, "GeneralPolygon needs \"P\"");
    SurfaceMesh m;
    std::string err;
    bool ok = tessellateGeneralPolygon(nverts, points3(Pp->floats), m, &err);
    addSurface(loc, "GeneralPolygon", ok, m, err, [&](VertexData& mesh) {
        std::vector<int> verts(mesh.p.size());  // one polygon: its points in order
        for (size_t i = 0; i < verts.size(); ++i) verts[i] = int(i);
        generalPolygonPointParams(params, {int(nverts.size())}, nverts, verts, m.faceIndex, mesh);
    });
}

void RibBuilder::pointsGeneralPolygons(L loc, Ints nloops, Ints nverts, Ints verts, P params) {
    if (!shown(loc, "PointsGeneralPolygons")) return;
    const rib::Param* Pp = params.find("P");
    if (!Pp) return m_diag.error(loc, "PointsGeneralPolygons needs \"P\"");
    SurfaceMesh m;
    std::string err;
    bool ok = tessellatePointsGeneralPolygons(nloops, nverts, verts, points3(Pp->floats), m, &err);
    addSurface(loc, "PointsGeneralPolygons", ok, m, err, [&](VertexData& mesh) {
        generalPolygonPointParams(params, nloops, nverts, verts, m.faceIndex, mesh);
    });
}

void RibBuilder::basis(L loc, S, const float ubasis[16], int ustep, S, const float vbasis[16],
                       int vstep) {
    std::string err;
    Attributes& a = m_attrStack.back();
    if (!basisFromMatrix(ubasis, ustep, a.ubasis, &err) ||
        !basisFromMatrix(vbasis, vstep, a.vbasis, &err))
        m_diag.error(loc, "Basis: " + err);
}

namespace {
// "P" (3 floats), "Pz" (1) or "Pw" (4): the positions a patch was given.
bool patchPositions(const rib::ParamList& params, PositionKind& kind, std::vector<float>& pos) {
    if (const rib::Param* p = params.find("P")) kind = PositionKind::P, pos = p->floats;
    else if (const rib::Param* pw = params.find("Pw")) kind = PositionKind::Pw, pos = pw->floats;
    else if (const rib::Param* pz = params.find("Pz")) kind = PositionKind::Pz, pos = pz->floats;
    else return false;
    return true;
}
std::vector<glm::vec3> controlHull(PositionKind kind, const std::vector<float>& pos) {
    if (kind == PositionKind::P) return points3(pos);
    std::vector<glm::vec3> out;
    if (kind == PositionKind::Pw)
        for (size_t i = 0; i + 3 < pos.size(); i += 4)
            out.push_back(glm::vec3(pos[i], pos[i + 1], pos[i + 2]) / (pos[i + 3] ? pos[i + 3] : 1));
    else
        for (size_t i = 0; i < pos.size(); ++i) out.push_back({0, 0, pos[i]});
    return out;
}
}  // namespace

void RibBuilder::patch(L loc, S type, P params) {
    if (!shown(loc, "Patch")) return;
    PositionKind kind;
    std::vector<float> pos;
    if (!patchPositions(params, kind, pos)) return m_diag.error(loc, "Patch needs \"P\"");
    SurfaceMesh m;
    std::string err;
    int seg = patchSegments(screenRadius(controlHull(kind, pos)));
    const Attributes& a = m_attrStack.back();
    bool ok = tessellatePatch(type, kind, pos, a.ubasis, a.vbasis, seg, seg, m, &err);
    PatchGrid grid;
    grid.bicubic = type == "bicubic";
    grid.nu = grid.nv = grid.bicubic ? 4 : 2;
    grid.ubasis = a.ubasis, grid.vbasis = a.vbasis;
    addSurface(loc, "Patch", ok, m, err, [&](VertexData& mesh) {
        patchPointParams(params, grid, m.st, m.faceIndex, mesh);
    });
}

void RibBuilder::patchMesh(L loc, S type, int nu, S uwrap, int nv, S vwrap, P params) {
    if (!shown(loc, "PatchMesh")) return;
    PatchMeshInput in;
    if (!patchPositions(params, in.kind, in.positions))
        return m_diag.error(loc, "PatchMesh needs \"P\"");
    in.bicubic = type == "bicubic";
    in.nu = nu, in.nv = nv;
    in.uperiodic = uwrap == "periodic", in.vperiodic = vwrap == "periodic";
    in.ubasis = m_attrStack.back().ubasis, in.vbasis = m_attrStack.back().vbasis;
    int patches = std::max(1, patchCount(in.bicubic, nu, in.uperiodic, in.ubasis.step) *
                                  patchCount(in.bicubic, nv, in.vperiodic, in.vbasis.step));
    int seg = std::max(2, int(patchSegments(screenRadius(controlHull(in.kind, in.positions))) /
                              std::sqrt(float(patches))));
    SurfaceMesh m;
    std::string err;
    bool ok = tessellatePatchMesh(in, seg, seg, m, &err);
    PatchGrid grid;
    grid.bicubic = in.bicubic, grid.uperiodic = in.uperiodic, grid.vperiodic = in.vperiodic;
    grid.nupatches = std::max(1, patchCount(in.bicubic, nu, in.uperiodic, in.ubasis.step));
    grid.nvpatches = std::max(1, patchCount(in.bicubic, nv, in.vperiodic, in.vbasis.step));
    grid.ubasis = in.ubasis, grid.vbasis = in.vbasis;
    grid.nu = nu, grid.nv = nv;
    addSurface(loc, "PatchMesh", ok, m, err, [&](VertexData& mesh) {
        patchPointParams(params, grid, m.st, m.faceIndex, mesh);
    });
}

// Newell's teapot as PRMan draws it: 32 Bezier patches whatever the current Basis, with
// the request's parameters (constant ones; each patch checks the rest as a Patch would).
void RibBuilder::geometry(L loc, S type, P params) {
    if (type != "teapot")
        return m_diag.warning(
            loc, "Geometry \"" + type +
                     "\": unknown type (RayDrive draws \"teapot\"), skipped");
    Attributes& a = m_attrStack.back();
    const CubicBasis ubasis = a.ubasis, vbasis = a.vbasis;
    a.ubasis = a.vbasis = bezierBasis();
    rib::ParamList patchParams = params;
    patchParams.params.erase(
        std::remove_if(patchParams.params.begin(), patchParams.params.end(),
                       [](const rib::Param& p) {
                           return p.name == "P" || p.name == "Pw" || p.name == "Pz";
                       }),
        patchParams.params.end());
    rib::Param P;
    P.name = "P", P.type = rib::ParamType::Point, P.storage = rib::StorageClass::Vertex;
    patchParams.params.push_back(P);
    for (int k = 0; k < kTeapotPatches; ++k) {
        patchParams.params.back().floats = teapotPatch(k);
        patch(loc, "bicubic", patchParams);
    }
    a.ubasis = ubasis, a.vbasis = vbasis;
}

void RibBuilder::trimCurve(L loc, Ints ncurves, Ints order, Floats knot, Floats min, Floats max,
                           Ints n, Floats u, Floats v, Floats w) {
    auto t = std::make_shared<TrimCurves>();
    t->ncurves = ncurves, t->order = order, t->knot = knot, t->min = min, t->max = max;
    t->n = n, t->u = u, t->v = v, t->w = w;
    std::string err;
    if (!validateTrimCurves(*t, &err)) return m_diag.error(loc, "TrimCurve: " + err);
    m_attrStack.back().trim = t;
}

void RibBuilder::nuPatch(L loc, int nu, int uorder, Floats uknot, float umin, float umax,
                         int nv, int vorder, Floats vknot, float vmin, float vmax, P params) {
    if (!shown(loc, "NuPatch")) return;
    NuPatchInput in;
    in.nu = nu, in.uorder = uorder, in.uknot = uknot, in.umin = umin, in.umax = umax;
    in.nv = nv, in.vorder = vorder, in.vknot = vknot, in.vmin = vmin, in.vmax = vmax;
    PositionKind kind;
    if (!patchPositions(params, kind, in.positions) || kind == PositionKind::Pz)
        return m_diag.error(loc, "NuPatch needs \"P\" or \"Pw\"");
    in.rational = kind == PositionKind::Pw;
    int seg = std::clamp(int(std::ceil(screenRadius(controlHull(kind, in.positions)) / 2.0f)),
                         8, 256);
    SurfaceMesh m;
    std::string err;
    bool ok = tessellateNuPatch(in, seg, seg, m_attrStack.back().trim.get(), m, &err);
    PatchGrid grid;  // varying values on the knot spans' corners
    grid.nupatches = std::max(1, nu - uorder + 1), grid.nvpatches = std::max(1, nv - vorder + 1);
    grid.uorder = uorder, grid.vorder = vorder, grid.uknot = uknot, grid.vknot = vknot;
    grid.nu = nu, grid.nv = nv;
    if (in.rational)
        for (size_t i = 3; i < in.positions.size(); i += 4)
            grid.weights.push_back(in.positions[i]);
    addSurface(loc, "NuPatch", ok, m, err, [&](VertexData& mesh) {
        patchPointParams(params, grid, m.st, m.faceIndex, mesh);
    });
}

void RibBuilder::subdivisionMesh(L loc, S scheme, Ints nverts, Ints verts, Strings tags,
                                 Ints nargs, Ints intargs, Floats floatargs, P params) {
    if (!shown(loc, "SubdivisionMesh")) return;
    const rib::Param* Pp = params.find("P");
    if (!Pp) return m_diag.error(loc, "SubdivisionMesh needs \"P\"");
    SubdivInput in;
    in.scheme = scheme, in.nvertices = nverts, in.vertices = verts, in.tags = tags;
    in.nargs = nargs, in.intargs = intargs, in.floatargs = floatargs;
    in.P = points3(Pp->floats);
    // One refinement level per halving of the faces' size on screen, down to ~4 pixels.
    float faces = float(std::max<size_t>(1, nverts.size()));
    float facePx = 2.0f * screenRadius(in.P) / std::sqrt(faces);
    int level = std::clamp(int(std::ceil(std::log2(std::max(1.0f, facePx / 4.0f)))), 1, 5);
    SurfaceMesh m;
    std::string err;
    std::vector<std::vector<glm::vec3>> refined;  // per-point parameters, refined
    const bool carried = subdivPointParamsIn(params, in);
    bool ok = tessellateSubdivisionMesh(in, level, m, &err, carried ? &refined : nullptr);
    addSurface(loc, "SubdivisionMesh", ok, m, err, [&](VertexData& mesh) {
        if (carried) subdivPointParams(params, refined, m.faceIndex, mesh);
    });
}

void RibBuilder::curves(L loc, S type, Ints nvertices, S wrap, P params) {
    if (!shown(loc, "Curves")) return;
    const rib::Param* Pp = params.find("P");
    if (!Pp) return m_diag.error(loc, "Curves needs \"P\"");
    CurvesInput in;
    in.cubic = type == "cubic";
    in.periodic = wrap == "periodic";
    in.nvertices = nvertices;
    in.P = points3(Pp->floats);
    in.vbasis = m_attrStack.back().vbasis;
    if (const rib::Param* w = params.find("width")) in.width = w->floats;
    in.constantWidth = params.getFloat("constantwidth", 1.0f);
    if (const rib::Param* n = params.find("N")) in.N = points3(n->floats);
    // Ribbons face the camera: its direction seen from the curves, in object space.
    glm::mat4 worldToObj = glm::inverse(m_attrStack.back().ctm);
    glm::vec3 eye = glm::vec3(worldToObj * glm::inverse(m_world.camera.worldToCamera) *
                              glm::vec4(0, 0, 0, 1));
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : in.P) centre += p / float(std::max<size_t>(1, in.P.size()));
    SurfaceMesh m;
    std::string err;
    bool ok = tessellateCurves(in, glm::normalize(centre - eye), 8, m, &err);
    addSurface(loc, "Curves", ok, m, err, [&](VertexData& mesh) {
        curvesPointParams(params, in, m.st, m.faceIndex, mesh);
    });
}

void RibBuilder::points(L loc, P params) {
    if (!shown(loc, "Points")) return;
    const rib::Param* Pp = params.find("P");
    if (!Pp) return m_diag.error(loc, "Points needs \"P\"");
    std::vector<glm::vec3> P = points3(Pp->floats);
    std::vector<float> width;
    if (const rib::Param* w = params.find("width")) width = w->floats;
    glm::mat4 worldToObj = glm::inverse(m_attrStack.back().ctm);
    glm::vec3 eye = glm::vec3(worldToObj * glm::inverse(m_world.camera.worldToCamera) *
                              glm::vec4(0, 0, 0, 1));
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : P) centre += p / float(std::max<size_t>(1, P.size()));
    SurfaceMesh m;
    std::string err;
    bool ok = tessellatePoints(P, width, params.getFloat("constantwidth", 1.0f),
                               glm::normalize(centre - eye), 12, m, &err);
    addSurface(loc, "Points", ok, m, err, [&](VertexData& mesh) {
        pointsPointParams(params, m.faceIndex, mesh);
    });
}

// Blobby: the implicit surface polygonised in object space (tessellate_blobby.h), up to
// 128 cells a side; per-blob (vertex, varying) values blended over it as the blobs are.
void RibBuilder::blobby(L loc, int, const std::vector<int>& code,
                        const std::vector<float>& floats, const std::vector<std::string>&,
                        const rib::ParamList& params) {
    if (!shown(loc, "Blobby")) return;
    const bool perBlob = !pointParamsOf(&params, /*withStandard=*/true).empty();
    SurfaceMesh m;
    BlobbyLeafWeights weights;
    std::string err, note;
    const bool ok =
        tessellateBlobby(code, floats, 128, m, &err, &note, perBlob ? &weights : nullptr);
    if (!note.empty()) m_diag.warning(loc, "Blobby: " + note);
    if (ok && m.mesh.tris.empty()) return;
    addSurface(loc, "Blobby", ok, m, err, [&](VertexData& mesh) {
        if (perBlob) blobbyPointParams(params, weights, mesh);
    });
}

}  // namespace rd
