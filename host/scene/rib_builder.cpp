// rib_builder.cpp: the Ri state machine (options, attribute and transform stacks, shader
// and light binding) turning RIB requests into Scenes.
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
    if (name == "visibility") {
        // PRMan: "int camera", "int trace" (or, later, "int diffuse" and "int specular"
        // together), "int transmission" / "string transmission"
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
            setShadowMode(m_attrStack.back().shadowHitShader ? RT_MATERIAL_SHADER_SHADOW : 0u);
        if (!transmission.empty() && transmission != "transparent" &&
            transmission != "opaque" && transmission != "Os" && transmission != "shader")
            m_diag.warning(loc,
                           "Attribute \"visibility\" \"string transmission\" \"" +
                               transmission +
                               "\": not transparent, opaque, Os or shader; taken as Os");
        return;
    }
    if (name == "shade") {  // PRMan: what a shadow ray's hit sees, the shader or Os
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
    if (name ==
        "displacementbound") {  // PRMan: "float sphere", "string coordinatesystem"
        const float r = params.getFloat("sphere", 0.0f);
        if (!(r >= 0.0f) || !std::isfinite(r))
            m_diag.warning(loc,
                           "Attribute \"displacementbound\" \"sphere\" must be finite "
                           "and not negative; ignored");
        else
            m_attrStack.back().displacementBound = r;
        return;
    }
    if (name == "render") {
        // BMRT: "int truedisplacement" 1 moves the surface; "string casts_shadows" is
        // what shadow rays see of it
        const int on = params.getInt("truedisplacement", -1);
        if (on >= 0) m_attrStack.back().trueDisplacement = on > 0 ? 1 : 0;
        const std::string casts = params.getString("casts_shadows", "");
        if (casts == "none") setShadowMode(RT_MATERIAL_NO_TRANSMISSION);
        else if (casts == "opaque") setShadowMode(RT_MATERIAL_OPAQUE_SHADOW);
        else if (casts == "Os") setShadowMode(0u);
        else if (casts == "shade") setShadowMode(RT_MATERIAL_SHADER_SHADOW);
        else if (!casts.empty())
            m_diag.warning(loc, "Attribute \"render\" \"casts_shadows\" \"" + casts +
                                    "\": not none, opaque, Os or shade; ignored");
    }
    if (name == "trace") {
        // Each object's own limit on the trace() depth of the rays its shader sends
        // (Scene::materialSpecularDepth); outside the world also the default.
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

void RibBuilder::color(L loc, const std::vector<float>& c) {
    const size_t k = size_t(m_world.colors.slots());
    if (c.size() != k) {
        m_diag.error(loc, "Color needs " + std::to_string(k) + " values (ColorSamples)");
        return;
    }
    std::copy_n(c.begin(), k, m_attrStack.back().color);
}
void RibBuilder::opacity(L loc, const std::vector<float>& c) {
    const size_t k = size_t(m_world.colors.slots());
    if (c.size() != k) {
        m_diag.error(loc,
                     "Opacity needs " + std::to_string(k) + " values (ColorSamples)");
        return;
    }
    float* o = m_attrStack.back().opacity;
    for (size_t i = 0; i < k; ++i) o[i] = std::fmin(1.0f, std::fmax(0.0f, c[i]));
}

void RibBuilder::surface(L loc, const std::string& name, const rib::ParamList& params) {
    // The shader is compiled and its parameters bound when the world is rendered; here
    // the call is kept with the transform that defines "shader" space.
    m_attrStack.back().surface = {name, params, m_attrStack.back().ctm, loc};
    m_attrStack.back().surfaceKey = ++m_surfaceCalls;
}

// A shader call the attributes keep (Atmosphere, Interior, Exterior, Displacement), in
// the space current at the call, with a number of its own; "" or "null" removes it.
void RibBuilder::keepCall(L loc, S name, P params, ShaderRef& call, uint64_t& key) {
    call = (name.empty() || name == "null")
               ? ShaderRef()
               : ShaderRef{name, params, m_attrStack.back().ctm, loc};
    key = call.name.empty() ? 0 : ++m_surfaceCalls;
}

// Atmosphere "" (or "null") removes it; the volume shader runs on each surface's Ci and
// Oi as seen from the ray's origin.
void RibBuilder::atmosphere(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.atmosphere, a.atmosphereKey);
}

// Interior "" (or "null") removes it. The volume shader runs on what a ray brings back
// from the inside of this surface (a hit on its back), over the segment from the ray's
// origin: absorption in coloured glass, fog inside an object.
void RibBuilder::interior(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.interior, a.interiorKey);
}

// Exterior "" (or "null") removes it. The volume shader runs on the segment a ray that
// left this surface travels outside it (a reflection, a refraction out of it), in place
// of the atmosphere.
void RibBuilder::exterior(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.exterior, a.exteriorKey);
}

// Deformation shaders were never carried out by any renderer: a warning.
void RibBuilder::deformation(L loc, S name, P) {
    if (!name.empty() && name != "null")
        m_diag.warning(loc, "Deformation \"" + name +
                                "\": deformation shaders are not carried out; ignored");
}

// Displacement "" (or "null") removes it. Displacements are rendered as bump maps: the
// shader's N shades the surface, rays still leave from the undisplaced one.
void RibBuilder::displacement(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.displacement, a.displacementKey);
}

// Imager: an option, the shader run on every pixel of the finished image.
void RibBuilder::imager(L loc, S name, P params) {
    Scene& s = m_inWorld ? m_world : m_options;
    s.imager = (name.empty() || name == "null") ? ShaderRef()
                                                 : ShaderRef{name, params, glm::mat4(1.0f), loc};
}

void RibBuilder::lightSource(L loc, const std::string& name, const std::string& handle,
                             const rib::ParamList& params) {
    // Before WorldBegin a light is an option of the frame, placed in camera space
    // (worldBegin() moves it into the world); the reader refuses one in an ObjectBegin
    // block.
    Scene& s = m_inWorld ? m_world : m_options;
    const uint32_t index = uint32_t(s.lights.size());
    if (!handle.empty()) (m_inWorld ? m_lightHandles : m_optionLightHandles)[handle] = index;
    s.lights.push_back({name, params, m_attrStack.back().ctm, loc});
}

// An area light: its light shader (e.g. arealight) runs at points on the geometry that
// follows in the same attribute block, one random point per shading point and sample
// (soft shadows as the samples add up). Its quadrics are diced so they can be sampled.
void RibBuilder::areaLightSource(L loc, S name, S handle, P params) {
    const size_t before = m_world.lights.size();
    lightSource(loc, name, handle, params);
    if (m_world.lights.size() > before) m_attrStack.back().areaLight = int(before);
}

// Illuminate turns a light off (or back on) for the geometry that follows, within the
// current attribute block. (Lights are on everywhere unless turned off: a light declared
// inside an attribute block still lights what comes after it.)
void RibBuilder::illuminate(L loc, const std::string& handle, bool on) {
    auto it = m_lightHandles.find(handle);
    if (it == m_lightHandles.end()) {
        m_diag.error(loc, "Illuminate: no light with handle \"" + handle + "\"");
        return;
    }
    if (it->second >= 32) {
        m_diag.warning(loc, "Illuminate: only the first 32 lights can be turned off");
        return;
    }
    uint32_t& off = m_attrStack.back().lightsOff;
    off = on ? (off & ~(1u << it->second)) : (off | (1u << it->second));
}

// One surface reference per distinct Surface call (same name, parameters, space), and
// per distinct set of primitive variables overriding its parameters (RI: a primitive
// variable named like a shader parameter gives that parameter its value on the primitive;
// constant ones, and uniform ones of a single face, become the instance's values; the
// others, on primitives that carry them (m_carriedPointParams), are given per point:
// rib_builder_point_params.cpp).
uint32_t RibBuilder::surfaceFor(const Attributes& a) {
    rib::ParamList overrides;
    std::string signature;
    const std::vector<std::pair<std::string, int>>& perPoint = m_carriedPointParams;
    for (const rib::Param& p : m_primVars ? m_primVars->params : std::vector<rib::Param>{}) {
        if (isStandardPrimvar(p.name)) continue;
        if (std::find_if(perPoint.begin(), perPoint.end(),
                         [&](const auto& q) { return q.first == p.name; }) != perPoint.end())
            continue;
        if (!givesOneValue(p)) {
            if (m_varyingPrimvarWarned.insert(p.name).second)
                m_diag.warning(a.surface.loc,
                               "primitive variable \"" + p.name + "\" (" +
                                   rib::storageClassName(p.storage) + " " +
                                   rib::paramTypeName(p.type) +
                                   ") does not reach shader parameters: per-point values are "
                                   "carried for float, color, point, vector and normal "
                                   "variables (8 a primitive)");
            continue;
        }
        overrides.params.push_back(p);
        signature += p.name + ":" + std::to_string(int(p.type)) + ":";
        for (float f : p.floats) signature += std::to_string(f) + ",";
        for (int v : p.ints) signature += std::to_string(v) + ",";
        for (const std::string& v : p.strings) signature += v + ",";
        signature += ";";
    }
    for (const auto& [name, floats] : perPoint)
        signature += name + ":" + std::to_string(floats) + " per point;";
    const uint32_t objectSpace = objectSpaceOf(a.surface);
    if (objectSpace != 0)
        signature += "object space " + std::to_string(objectSpace) + ";";
    auto [it, fresh] = m_surfaceVariants.emplace(std::make_pair(a.surfaceKey, signature),
                                                 uint32_t(m_world.surfaceRefs.size()));
    if (fresh) {
        ShaderRef ref = a.surface;
        if (objectSpace != 0) ref.objectToWorld = a.ctm;
        for (const rib::Param& p : overrides.params) {
            auto same = std::find_if(ref.params.params.begin(), ref.params.params.end(),
                                     [&](const rib::Param& q) { return q.name == p.name; });
            if (same != ref.params.params.end()) *same = p;
            else ref.params.params.push_back(p);
        }
        ref.pointParams = perPoint;
        int values = 0;
        for (const auto& [name, floats] : perPoint) values += pointParamEntries(floats);
        m_world.maxPointParams = std::max(m_world.maxPointParams, values);
        m_world.surfaceRefs.push_back(ref);
    }
    return it->second;
}

uint32_t RibBuilder::objectSpaceOf(const ShaderRef& call) {
    const std::string& name = call.name;
    if (name.empty()) return 0;
    auto known = m_readsObjectSpace.find(name);
    if (known == m_readsObjectSpace.end())
        known =
            m_readsObjectSpace.emplace(name, shaderReadsObjectSpace(m_world, name)).first;
    if (!known->second) return 0;
    const glm::mat4& ctm = m_attrStack.back().ctm;
    const std::string bytes(reinterpret_cast<const char*>(&ctm[0][0]), sizeof ctm);
    if (auto it = m_objectSpaces.find(bytes); it != m_objectSpaces.end())
        return it->second;
    // (each one is an instance of its own: a bound on their blocks' memory)
    if (m_objectSpaces.size() >= kMaxObjectSpaces) {
        if (m_warnedAt.insert({call.loc.file, call.loc.line}).second)
            m_diag.warning(call.loc,
                           "more than " + std::to_string(kMaxObjectSpaces) +
                               " object spaces for shaders that read \"object\" "
                               "space; the rest take the call's space as object "
                               "space");
        return 0;
    }
    return m_objectSpaces.emplace(bytes, uint32_t(m_objectSpaces.size() + 1))
        .first->second;
}

size_t RibBuilder::callIndex(uint64_t key, const ShaderRef& call, CallIndex& index,
                             std::vector<ShaderRef>& calls, size_t limit,
                             const char* request) {
    uint32_t objectSpace = objectSpaceOf(call);
    auto it = index.find({key, objectSpace});
    if (it != index.end()) return it->second;
    if (calls.size() >= limit && objectSpace != 0) {
        // past the limit, the call's own space stands for the primitive's
        if (m_warnedAt.insert({call.loc.file, call.loc.line}).second)
            m_diag.warning(
                call.loc, std::string("more than ") + std::to_string(limit) + " " +
                              request + " instances (one per object space for shader \"" +
                              call.name +
                              "\", which reads \"object\" space); "
                              "the rest take the call's space as object space");
        objectSpace = 0;
        it = index.find({key, objectSpace});
        if (it != index.end()) return it->second;
    }
    ShaderRef ref = call;
    if (objectSpace != 0) ref.objectToWorld = m_attrStack.back().ctm;
    index.emplace(std::make_pair(key, objectSpace), calls.size());
    calls.push_back(std::move(ref));
    return calls.size() - 1;
}

uint32_t RibBuilder::currentMaterial() {
    const Attributes& a = m_attrStack.back();
    const uint32_t surface = surfaceFor(a);
    Material m{};
    m.shader = surface;
    // (more than three channels: the material's RGB here, its channels beside it)
    const ColorSamples& colors = m_world.colors;
    float cs[ColorSamples::kMaxChannels], os[ColorSamples::kMaxChannels];
    std::copy_n(a.color, colors.slots(), cs);
    std::copy_n(a.opacity, colors.slots(), os);
    if (colors.n > 3) colors.toRgbValues(cs), colors.toRgbValues(os);
    m.cs = f4(cs[0], cs[1], cs[2]);
    m.os = f4(os[0], os[1], os[2], (os[0] + os[1] + os[2]) / 3.0f);
    m.lights_off = a.lightsOff;
    if (a.sides == 1) m.flags |= RT_MATERIAL_ONE_SIDED;
    // each volume or displacement call in use gets an index, 1 + it in the material's
    // bits
    auto bind = [&](uint64_t callKey, const ShaderRef& call, CallIndex& keys,
                    std::vector<ShaderRef>& calls, uint32_t shift, const char* request) {
        if (callKey == 0) return false;
        const size_t index = callIndex(callKey, call, keys, calls, 255, request);
        if (index < 255)
            m.flags |= uint32_t(index + 1) << shift;
        else
            m_diag.warning(call.loc, std::string("more than 255 ") + request +
                                         " calls; this one is not used");
        return index < 255;
    };
    bind(a.atmosphereKey, a.atmosphere, m_atmosphereKeys, m_world.atmospheres,
         RT_MATERIAL_ATMOSPHERE_SHIFT, "Atmosphere");
    bind(a.interiorKey, a.interior, m_interiorKeys, m_world.interiors,
         RT_MATERIAL_INTERIOR_SHIFT, "Interior");
    uint32_t exterior = 0;  // (in a table of its own: the material's flag bits are taken)
    if (a.exteriorKey != 0)
        exterior = uint32_t(callIndex(a.exteriorKey, a.exterior, m_exteriorKeys,
                                      m_world.exteriors, SIZE_MAX, "Exterior") +
                            1);
    if (bind(a.displacementKey, a.displacement, m_displacementKeys, m_world.displacements,
             RT_MATERIAL_DISPLACEMENT_SHIFT, "Displacement") &&
        a.displacesTruly())
        m.flags |= RT_MATERIAL_TRUE_DISPLACEMENT;
    if (a.matte) {
        m.flags |= RT_MATERIAL_MATTE;
        m_world.anyMatte = true;
    }
    m.flags |= a.visibility;
    std::string key(reinterpret_cast<const char*>(&m), sizeof m);
    if (colors.n > 3) {
        key.append(reinterpret_cast<const char*>(a.color),
                   sizeof(float) * size_t(colors.n));
        key.append(reinterpret_cast<const char*>(a.opacity),
                   sizeof(float) * size_t(colors.n));
    }
    const uint32_t attributeSet = attributeSetIndex(a.messages);
    key.append(reinterpret_cast<const char*>(&attributeSet), sizeof attributeSet);
    // a truly displaced surface's micropolygon edge, in pixels
    const float dicing =
        (m.flags & RT_MATERIAL_TRUE_DISPLACEMENT) ? std::sqrt(a.shadingRate) : 0.0f;
    key.append(reinterpret_cast<const char*>(&dicing), sizeof dicing);
    key.append(reinterpret_cast<const char*>(&exterior), sizeof exterior);
    // (the default is the world's: Option or attribute before WorldBegin)
    const int specularDepth =
        a.maxSpecularDepth >= 0 ? a.maxSpecularDepth : m_world.maxSpecularDepth;
    key.append(reinterpret_cast<const char*>(&specularDepth), sizeof specularDepth);
    if (auto it = m_materialKeys.find(key); it != m_materialKeys.end()) return it->second;
    uint32_t index = static_cast<uint32_t>(m_world.materials.size());
    m_world.materials.push_back(m);
    m_world.materialAttributes.push_back(attributeSet);
    m_world.materialDicing.push_back(dicing);
    m_world.materialExterior.push_back(exterior);
    m_world.materialSpecularDepth.push_back(specularDepth);
    if (colors.n > 3) {
        m_world.materialChannels.insert(m_world.materialChannels.end(), a.color,
                                        a.color + colors.n);
        m_world.materialChannels.insert(m_world.materialChannels.end(), a.opacity,
                                        a.opacity + colors.n);
    }
    m_materialKeys.emplace(std::move(key), index);
    return index;
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
        m_diag.error(loc, m_defining ? "ObjectInstance inside ObjectBegin"
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
    for (size_t i = 0; i < def.quadrics.size(); ++i) {
        const QuadricShape& q = def.quadrics[i];
        addQuadric(loc, quadricKindName(q.q.kind), q, def.quadricParams[i],
                   quadricPlacement(q.q));
    }
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
