// rib_builder.cpp: the Ri state machine turning RIB requests into Scenes: frames and
// worlds, options and attributes, the camera's requests. Shaders and materials are in
// rib_builder_shading.cpp, geometry in rib_builder_geometry.cpp and rib_builder_mesh.cpp.
#include "rib_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "rib_builder_util.h"
#include "shaders/shader_path.h"
#include "shaders/shader_set.h"
#include "tessellate.h"

namespace rd {

RibBuilder::RibBuilder(rib::Diagnostics& diag, const std::string& sourceFile) : m_diag(diag) {
    m_options.sourceFile = sourceFile;
    m_attrStack.emplace_back();
    // Until a Surface is given: RenderMan's defaultsurface.
    m_attrStack.back().surface.name = "defaultsurface";
}

bool RibBuilder::inWorld(L loc, const char* request) {
    if (m_inWorld || m_defining) return true;
    m_diag.error(loc, std::string(request) + " is only valid inside WorldBegin/WorldEnd");
    return false;
}

// A frame saves the options and restores them at its end (RI 3.2): a frame's Display,
// its secondary displays and its other options are its own.
void RibBuilder::frameBegin(L, int) {
    m_attrStack.push_back(m_attrStack.back());
    m_frameOptions.push_back(m_options);
}
void RibBuilder::frameEnd(L) {
    if (m_attrStack.size() > 1) m_attrStack.pop_back();
    if (!m_frameOptions.empty()) {
        m_options = std::move(m_frameOptions.back());
        m_frameOptions.pop_back();
    }
}

void RibBuilder::worldBegin(L loc) {
    // The transform current at WorldBegin is the camera's; world space starts as identity.
    const Attributes& camera = m_attrStack.back();
    if (camera.moving && camera.between.size() > RT_CAMERA_MAX_BETWEEN)
        m_diag.warning(loc, "the camera moves through its first " +
                                std::to_string(RT_CAMERA_MAX_BETWEEN + 2) +
                                " motion keys of " +
                                std::to_string(camera.between.size() + 2) +
                                " (then straight to its last)");
    m_options.camera.worldToCamera = camera.ctm;
    m_options.camera.moving = camera.moving;  // MotionBegin around the camera transform
    m_options.camera.worldToCameraEnd = camera.moving ? camera.ctmEnd : camera.ctm;
    m_options.camera.worldToCameraBetween =
        camera.moving ? camera.between : decltype(camera.between){};
    m_options.camera.motionTimes[0] = camera.t0;
    m_options.camera.motionTimes[1] = camera.t1;
    m_world = m_options;
    // clipping planes and lights given before the world: from camera space to the world
    for (auto& plane : m_world.clipPlanes)
        plane = transformPlane(glm::inverse(camera.ctm), plane);
    for (ShaderRef& light : m_world.lights)
        light.shaderToWorld = glm::inverse(camera.ctm) * light.shaderToWorld;
    // Camera-relative world: what reaches the device is world space moved so the eye is
    // at the origin (in double here), so a scene far from the origin keeps the float
    // precision it has near the eye. Applied to triangles as they come, to the camera,
    // lights and shader spaces at WorldEnd.
    m_origin = glm::dvec3(glm::inverse(glm::dmat4(m_options.camera.worldToCamera)) *
                          glm::dvec4(0.0, 0.0, 0.0, 1.0));
    if (!finite3(glm::vec3(m_origin))) m_origin = glm::dvec3(0.0);
    m_inWorld = true;
    m_materialKeys.clear();
    m_attributeSetIndex.clear();
    m_surfaceVariants.clear();
    m_atmosphereKeys.clear();
    m_interiorKeys.clear();
    m_exteriorKeys.clear();
    m_displacementKeys.clear();
    m_readsObjectSpace.clear();
    m_objectSpaces.clear();
    m_lastScopedSystems.clear();
    m_degenerate = 0;
    m_solidNodes.clear();
    m_solidStack.clear();
    m_prototypes.clear();
    m_lightHandles = m_optionLightHandles;  // (the lights given before the world)
    m_attrStack.push_back(m_attrStack.back());
    m_attrStack.back().ctm = glm::mat4(1.0f);
    m_attrStack.back().moving = false;
    m_attrStack.back().between.clear();
}

void RibBuilder::worldEnd(L loc) {
    if (!m_inWorld) return;
    (void)loc;  // degenerate geometry is reported where it was given (addMesh)
    const glm::dmat4 toOrigin = glm::translate(glm::dmat4(1.0), -m_origin);
    for (ShaderRef& r : m_world.lights) r.shaderToWorld = glm::mat4(toOrigin * glm::dmat4(r.shaderToWorld));
    for (auto* refs : {&m_world.surfaceRefs, &m_world.displacements, &m_world.atmospheres,
                       &m_world.interiors, &m_world.exteriors})
        for (ShaderRef& r : *refs) {
            r.shaderToWorld = glm::mat4(toOrigin * glm::dmat4(r.shaderToWorld));
            if (r.objectToWorld)
                r.objectToWorld = glm::mat4(toOrigin * glm::dmat4(*r.objectToWorld));
        }
    // the deepest limit any object has bounds the kernels' (RT_MAX_SPECULAR_DEPTH)
    if (!m_world.materialSpecularDepth.empty())
        m_world.maxSpecularDepth = *std::max_element(
            m_world.materialSpecularDepth.begin(), m_world.materialSpecularDepth.end());
    for (const auto* systems : {&m_lastScopedSystems, &m_coordSystems})  // (global last)
        for (const auto& [name, toWorld] : *systems)
            m_world.coordinateSystems[name] = glm::mat4(toOrigin * glm::dmat4(toWorld));
    m_world.camera.worldToCamera = glm::mat4(glm::dmat4(m_world.camera.worldToCamera) *
                                             glm::translate(glm::dmat4(1.0), m_origin));
    m_world.camera.worldToCameraEnd = glm::mat4(glm::dmat4(m_world.camera.worldToCameraEnd) *
                                                glm::translate(glm::dmat4(1.0), m_origin));
    for (auto& key : m_world.camera.worldToCameraBetween)
        key.second =
            glm::mat4(glm::dmat4(key.second) * glm::translate(glm::dmat4(1.0), m_origin));
    m_world.worldOrigin = m_origin;
    for (auto& plane : m_world.clipPlanes)
        plane[0] = glm::vec3(glm::dvec3(plane[0]) - m_origin);
    if (!m_world.trianglesEnd.empty()) m_world.trianglesEnd.resize(m_world.triangles.size());
    m_inWorld = false;
    if (m_attrStack.size() > 1) m_attrStack.pop_back();
    m_scenes.push_back(std::move(m_world));
    m_world = Scene();
}

void RibBuilder::attribute(L loc, const std::string& name, const rib::ParamList& params) {
    setMessageValues(loc, name, params, m_attrStack.back().messages,
                     &m_attrStack.back().ctm);
    if (name == "visibility") visibilityAttribute(loc, params);
    if (name == "shade") shadeAttribute(loc, params);
    if (name == "displacementbound") displacementBoundAttribute(loc, params);
    if (name == "render") renderAttribute(loc, params);
    if (name == "trace") traceAttribute(params);
}

// PRMan: "int camera", "int trace" (or, later, "int diffuse" and "int specular"
// together), "int transmission" / "string transmission"
void RibBuilder::visibilityAttribute(L loc, const rib::ParamList& params) {
    uint32_t& v = m_attrStack.back().visibility;
    auto set = [&](uint32_t flag, int on) {
        if (on == 0)
            v |= flag;
        else if (on > 0)
            v &= ~flag;
    };
    set(RT_MATERIAL_NO_CAMERA, params.getInt("camera", -1));
    // "trace": both kinds of traced rays; "specular": trace() and gather()'s,
    // "diffuse": occlusion()'s and indirectdiffuse()'s
    set(RT_MATERIAL_NO_TRACE | RT_MATERIAL_NO_DIFFUSE, params.getInt("trace", -1));
    set(RT_MATERIAL_NO_TRACE, params.getInt("specular", -1));
    set(RT_MATERIAL_NO_DIFFUSE, params.getInt("diffuse", -1));
    // transmission: 0 or "transparent" cast no shadow; 1 or "Os" one by their
    // opacity Os (their shader's Oi under "shade" "transmissionhitmode" "shader");
    // "opaque" a full one whatever their Os; "shader" one by their shader's Oi
    const std::string transmission = params.getString("transmission", "");
    const int on = transmission.empty() ? params.getInt("transmission", -1) : -1;
    if (transmission == "transparent" || on == 0)
        setShadowMode(RT_MATERIAL_NO_TRANSMISSION);
    else if (transmission == "opaque")
        setShadowMode(RT_MATERIAL_OPAQUE_SHADOW);
    else if (transmission == "shader")
        setShadowMode(RT_MATERIAL_SHADER_SHADOW);
    else if (!transmission.empty() || on > 0)
        setShadowMode(m_attrStack.back().shadowHitShader ? RT_MATERIAL_SHADER_SHADOW
                                                         : 0u);
    if (!transmission.empty() && transmission != "transparent" &&
        transmission != "opaque" && transmission != "Os" && transmission != "shader")
        m_diag.warning(loc, "Attribute \"visibility\" \"string transmission\" \"" +
                                transmission +
                                "\": not transparent, opaque, Os or shader; taken as Os");
}

// PRMan: what a shadow ray's hit sees, the shader or Os
void RibBuilder::shadeAttribute(L loc, const rib::ParamList& params) {
    const std::string mode = params.getString("transmissionhitmode", "");
    const uint32_t now = m_attrStack.back().visibility & RT_MATERIAL_SHADOW_MASK;
    if (mode == "shader" || mode == "primitive") {
        m_attrStack.back().shadowHitShader = mode == "shader";
        if (now == 0u || now == RT_MATERIAL_SHADER_SHADOW)
            setShadowMode(mode == "shader" ? RT_MATERIAL_SHADER_SHADOW : 0u);
    } else if (!mode.empty())
        m_diag.warning(loc, "Attribute \"shade\" \"transmissionhitmode\" \"" + mode +
                                "\": not shader or primitive; ignored");
}

// PRMan: "float sphere", "string coordinatesystem"
void RibBuilder::displacementBoundAttribute(L loc, const rib::ParamList& params) {
    const float r = params.getFloat("sphere", 0.0f);
    if (!(r >= 0.0f) || !std::isfinite(r))
        m_diag.warning(loc,
                       "Attribute \"displacementbound\" \"sphere\" must be finite "
                       "and not negative; ignored");
    else
        m_attrStack.back().displacementBound = r;
}

// BMRT: "int truedisplacement" 1 moves the surface; "string casts_shadows" is what
// shadow rays see of it
void RibBuilder::renderAttribute(L loc, const rib::ParamList& params) {
    const int on = params.getInt("truedisplacement", -1);
    if (on >= 0) m_attrStack.back().trueDisplacement = on > 0 ? 1 : 0;
    const std::string casts = params.getString("casts_shadows", "");
    if (casts == "none")
        setShadowMode(RT_MATERIAL_NO_TRANSMISSION);
    else if (casts == "opaque")
        setShadowMode(RT_MATERIAL_OPAQUE_SHADOW);
    else if (casts == "Os")
        setShadowMode(0u);
    else if (casts == "shade")
        setShadowMode(RT_MATERIAL_SHADER_SHADOW);
    else if (!casts.empty())
        m_diag.warning(loc, "Attribute \"render\" \"casts_shadows\" \"" + casts +
                                "\": not none, opaque, Os or shade; ignored");
}

// Each object's own limit on the trace() depth of the rays its shader sends
// (Scene::materialSpecularDepth); outside the world also the default.
void RibBuilder::traceAttribute(const rib::ParamList& params) {
    int depth = std::min(params.getInt("maxspeculardepth", -1), 4096);
    if (depth >= 0) {
        m_attrStack.back().maxSpecularDepth = depth;
        if (!m_inWorld) m_options.maxSpecularDepth = depth;
    }
    // diffuse bounces along a path: the largest any object gives holds for all
    const int diffuse = std::min(params.getInt("maxdiffusedepth", -1), 4096);
    if (diffuse >= 0) {
        Scene& s = m_inWorld ? m_world : m_options;
        s.maxDiffuseDepth = std::max(s.maxDiffuseDepth, diffuse);
    }
    traceDepthOption(params);
}

// What a shadow ray sees of the surfaces from here on (RT_MATERIAL_SHADOW_MASK).
void RibBuilder::setShadowMode(uint32_t mode) {
    uint32_t& v = m_attrStack.back().visibility;
    v = (v & ~uint32_t(RT_MATERIAL_SHADOW_MASK)) | mode;
}

void RibBuilder::traceDepthOption(const rib::ParamList& params) {
    // maxtransparentdepth bounds the work (one trace round per layer): 0..65535 (16 bits of RayState::depth).
    // roulettedepth: trace() rays from this depth on meet Russian roulette (0: never)
    int roulette = params.getInt("roulettedepth", -1);
    if (roulette >= 0) (m_inWorld ? m_world : m_options).rouletteDepth = std::min(roulette, 4096);
    int depth = std::min(params.getInt("maxtransparentdepth", -1), 65535);
    if (depth < 0) return;
    if (m_inWorld)
        m_world.maxTransparentDepth = depth;
    else
        m_options.maxTransparentDepth = depth;
}

void RibBuilder::attributeBegin(L) { m_attrStack.push_back(m_attrStack.back()); }
void RibBuilder::attributeEnd(L) {
    if (m_attrStack.size() > 1) m_attrStack.pop_back();
}

void RibBuilder::resourceBegin(L) {
    m_resources.emplace_back();
}
void RibBuilder::resourceEnd(L) {
    if (m_resources.size() > 1) m_resources.pop_back();
}

void RibBuilder::resource(L, S name, S, P params) {
    Attributes& current = m_attrStack.back();
    if (params.getString("operation", "") == "save") {
        m_resources.back()[name] = current;
        return;
    }
    const Attributes* saved = nullptr;  // (the reader checked that there is one)
    for (auto it = m_resources.rbegin(); it != m_resources.rend() && !saved; ++it)
        if (auto found = it->find(name); found != it->end()) saved = &found->second;
    if (!saved) return;
    const std::string subset = params.getString("subset", "all");
    const Placement placement = current;
    // (the scoped coordinate systems are names of the blocks open, not attributes)
    std::vector<std::pair<std::string, glm::mat4>> scoped =
        std::move(current.scopedSystems);
    if (subset != "transform") current = *saved;
    static_cast<Placement&>(current) = subset == "shading" ? placement : *saved;
    current.scopedSystems = std::move(scoped);
}

void RibBuilder::format(L loc, int x, int y, float aspect) {
    if (x <= 0 || y <= 0 || x > 65536 || y > 65536 || (int64_t)x * y > (int64_t)1 << 28) {
        m_diag.error(loc, "Format " + std::to_string(x) + " " + std::to_string(y) +
                              " is out of range (1..65536 per side, 2^28 pixels)");
        return;
    }
    m_options.camera.width = x;
    m_options.camera.height = y;
    m_options.camera.pixelAspect = aspect > 0 ? aspect : 1.0f;
}
void RibBuilder::frameAspectRatio(L, float a) { m_options.camera.frameAspect = a; }
void RibBuilder::screenWindow(L, float l, float r, float b, float t) {
    CameraSpec& c = m_options.camera;
    c.screenWindowSet = true;
    c.screen[0] = l;
    c.screen[1] = r;
    c.screen[2] = b;
    c.screen[3] = t;
}
void RibBuilder::projection(L loc, const std::string& name, const rib::ParamList& params) {
    CameraSpec& c = m_options.camera;
    if (name == "perspective") {
        c.perspective = true;
        c.fovDeg = params.getFloat("fov", 90.0f);
        if (!(c.fovDeg > 0.0f && c.fovDeg < 180.0f)) {
            m_diag.error(loc, "perspective fov must be in (0, 180) degrees");
            c.fovDeg = 90.0f;
        }
    } else if (name == "orthographic") {
        c.perspective = false;
    } else if (name == "null") {
        // RI: the transforms that follow (a Perspective) are the projection
        c.perspective = false;
        m_projectionNull = true;
    } else {
        m_diag.error(loc, "unknown projection \"" + name + "\" (perspective, orthographic, null)");
    }
    // RI: transformations given before Projection are screen space; start camera space.
    m_attrStack.back().ctm = glm::mat4(1.0f);
}
void RibBuilder::clipping(L loc, float n, float f) {
    if (!(n > 0.0f) || !(f > n)) {
        m_diag.error(loc, "Clipping needs 0 < near < far");
        return;
    }
    m_options.camera.clipNear = n;
    m_options.camera.clipFar = f;
}
// PixelVariance: the error adaptive sampling refines each pixel to (PRMan's meaning
// under RIS), RayDrive's "pixelerror".
void RibBuilder::pixelVariance(L loc, float v) {
    if (!(v > 0.0f && v < 1e30f)) {
        m_diag.error(loc, "PixelVariance must be above 0");
        return;
    }
    m_options.render.pixelError = v;
}

// Hider "raytrace" (PRMan's RIS) or "hidden": RayDrive ray traces either way; "int
// minsamples" and "int maxsamples" bound each pixel's adaptive samples in place of
// PixelSamples. Other hiders are not RayDrive's: a warning.
void RibBuilder::hider(L loc, const std::string& type, const rib::ParamList& params) {
    if (type != "raytrace" && type != "hidden") {
        m_diag.warning(loc,
                       "Hider \"" + type +
                           "\" is not RayDrive's; it ray traces as Hider \"raytrace\"");
        return;
    }
    const int most = params.getInt("maxsamples", -1),
              least = params.getInt("minsamples", -1);
    if (most == 0 || most > 65536 || least == 0 || least > 65536) {
        m_diag.error(
            loc, "Hider \"" + type + "\": minsamples and maxsamples must be 1 to 65536");
        return;
    }
    if (most > 0) m_options.render.maxSamples = most;
    if (least > 0) m_options.render.minSamples = least;
}

void RibBuilder::pixelSamples(L loc, float x, float y) {
    if (!(x >= 1.0f && y >= 1.0f && x <= 64.0f && y <= 64.0f)) {
        m_diag.error(loc, "PixelSamples must be between 1 and 64 per axis");
        return;
    }
    m_options.camera.pixelSamples[0] = std::floor(x);
    m_options.camera.pixelSamples[1] = std::floor(y);
}
void RibBuilder::option(L loc, const std::string& name, const rib::ParamList& params) {
    setMessageValues(loc, name, params, (m_inWorld ? m_world : m_options).optionValues,
                     nullptr);
    if (name == "searchpath") {
        // "shader"/"texture" ["dir:dir:&"]: '&' stands for the path so far.
        for (auto [key, list] : {std::pair{"shader", &m_options.shaderSearchPath},
                                 std::pair{"texture", &m_options.textureSearchPath}})
            if (const std::string path = params.getString(key, ""); !path.empty())
                *list = updatedSearchPath(*list, path);
        return;
    }
    if (name == "limits") {  // PRMan's texture cache size, in KiB; RayDrive's treelets
        int kb = params.getInt("texturememory", -1);
        if (kb > 0) m_options.render.textureMemoryKB = kb;
        int tb = params.getInt("treeletbytes", -1);
        if (tb > 0) m_options.render.treeletBytes = tb;
        int sm = params.getInt("scenememory", -1);
        if (sm > 0) m_options.render.sceneMemoryKB = sm;
        int dt = params.getInt("dicedtriangles", -1);  // true displacement's budget
        if (dt > 0) m_options.render.dicedTriangles = dt;
        return;
    }
    if (name == "trace") traceDepthOption(params);
    if (name != "render") return;
    RenderOptionsSpec& r = m_options.render;
    r.time = params.getFloat("time", r.time);
    r.error = params.getFloat("error", r.error);
    r.firstPassBlock = params.getInt("firstpassblock", r.firstPassBlock);
    r.pixelError = params.getFloat("pixelerror", r.pixelError);
    r.exactQuadrics = params.getInt("exactquadrics", r.exactQuadrics ? 1 : 0) != 0;
    r.seed = params.getInt("seed", r.seed);
    if (const std::string s = params.getString("sampler", ""); !s.empty()) {
        if (s != "sobol" && s != "independent")
            m_diag.error(loc, "Option \"render\" \"sampler\" \"" + s +
                                  "\": known samplers are \"independent\" and \"sobol\"");
        else
            r.sobol = s == "sobol";
    }
    if (r.time < 0 || r.error < 0 || r.firstPassBlock < 1 || r.firstPassBlock > 64 ||
        !(r.pixelError > 0) || r.seed < 0) {
        m_diag.error(loc, "Option \"render\": time and error must be >= 0, firstpassblock "
                          "1..64, pixelerror > 0, seed >= 0");
        r = RenderOptionsSpec();
    }
}

void RibBuilder::cropWindow(L loc, float x0, float x1, float y0, float y1) {
    if (!(0 <= x0 && x0 < x1 && x1 <= 1 && 0 <= y0 && y0 < y1 && y1 <= 1)) {
        m_diag.error(loc, "CropWindow needs 0 <= xmin < xmax <= 1 and 0 <= ymin < ymax <= 1");
        return;
    }
    float* c = m_options.camera.crop;
    c[0] = x0, c[1] = x1, c[2] = y0, c[3] = y1;
}

void RibBuilder::depthOfField(L loc, float fstop, float focalLength, float focalDistance) {
    CameraSpec& c = m_options.camera;
    if (std::isinf(fstop)) {  // a bare DepthOfField: back to a pinhole
        c.fstop = 0;
        return;
    }
    if (!(fstop > 0 && focalLength > 0 && focalDistance > 0)) {
        m_diag.error(loc, "DepthOfField needs fstop, focallength and focaldistance > 0");
        return;
    }
    c.fstop = fstop, c.focalLength = focalLength, c.focalDistance = focalDistance;
}

void RibBuilder::matte(L, bool on) { m_attrStack.back().matte = on; }

// Surfaces are rendered as surfaces: "lines" and "points" (wire frames, point clouds of
// a surface's vertices) are a warning.
void RibBuilder::geometricRepresentation(L loc, S type) {
    if (type != "primitive")
        m_diag.warning(loc, "GeometricRepresentation \"" + type +
                                "\": surfaces are rendered as \"primitive\"");
}

void RibBuilder::procedural(L loc, const std::string& name, const std::vector<std::string>&,
                            const float*) {
    m_diag.warning(loc, "Procedural \"" + name + "\" is not supported; skipped");
}

void RibBuilder::polygon(L loc, const rib::ParamList& params) {
    if (!shown(loc, "Polygon")) return;
    std::vector<int> nverts;
    const rib::Param* P = params.find("P");
    if (!P) {
        m_diag.error(loc, "Polygon needs \"P\"");
        return;
    }
    nverts.push_back(static_cast<int>(P->floats.size() / 3));
    std::vector<int> verts(nverts[0]);
    for (int i = 0; i < nverts[0]; ++i) verts[i] = i;
    pointsPolygons(loc, nverts, verts, params);
}

void RibBuilder::pointsPolygons(L loc, const std::vector<int>& nverts,
                                const std::vector<int>& verts, const rib::ParamList& params) {
    if (!shown(loc, "PointsPolygons")) return;
    const rib::Param* P = params.find("P");
    if (!P || P->floats.size() % 3 != 0) {
        m_diag.error(loc, "polygons need \"P\" with 3 floats per point");
        return;
    }
    size_t np = P->floats.size() / 3;
    VertexData mesh;
    mesh.p.resize(np);
    for (size_t i = 0; i < np; ++i)
        mesh.p[i] = {P->floats[3 * i], P->floats[3 * i + 1], P->floats[3 * i + 2]};
    readVertexNormals(params, np, mesh);
    std::vector<int>& tris = mesh.tris;
    size_t offset = 0;
    for (int count : nverts) {
        if (count < 3 || offset + count > verts.size()) {
            m_diag.error(loc, "polygon with " + std::to_string(count) + " vertices skipped");
            offset += count > 0 ? count : 0;
            continue;
        }
        bool ok = true;
        for (int k = 0; k < count; ++k)
            if (verts[offset + k] < 0 || size_t(verts[offset + k]) >= np) ok = false;
        if (ok) triangulateConvex(&verts[offset], count, tris);
        else m_diag.error(loc, "polygon vertex index out of range");
        offset += count;
    }
    readPointParams(params, nverts, verts, mesh);
    addMesh(loc, mesh);
}

float RibBuilder::pixelsPerUnit(float depth) const {
    const CameraSpec& c = m_world.camera;
    Camera dc = m_world.deviceCamera();
    float unitsAcross = dc.screen[1] - dc.screen[0];
    float perScreenUnit = float(c.width) / unitsAcross;
    if (!c.perspective) return perScreenUnit;
    if (!(depth > 0.0f)) return 1e6f;
    return perScreenUnit / (dc.tan_half_fov * depth);
}

void RibBuilder::sphere(L loc, float radius, float zmin, float zmax, float thetamax,
                        const rib::ParamList& params) {
    if (!shown(loc, "Sphere")) return;
    if (m_defining)  // (no copy of the request outside ObjectBegin)
        keepQuadricCall([=, loc = rib::SourceLoc(loc), params = rib::ParamList(params)] {
            sphere(loc, radius, zmin, zmax, thetamax, params);
        });
    if (exactQuadrics()) {
        addQuadric(loc, "Sphere", makeSphere(radius, zmin, zmax, thetamax), params);
        return;
    }
    // Dice for the sphere's size on screen: chord error under 0.1 pixel.
    const int n = circleSegments(screenRadius(glm::vec3(0.0f), radius), 0.1f);
    const auto [nu, nv] = keySegments(n, n / 2);
    VertexData mesh;
    TriMesh m = tessellateSphere(radius, zmin, zmax, thetamax, nu, nv, &mesh.st);
    mesh.p = std::move(m.p), mesh.n = std::move(m.n), mesh.tris = std::move(m.tris);
    cornerPointParams(params, mesh);  // st is (u, v) here
    addMesh(loc, mesh);
}

}  // namespace rd
