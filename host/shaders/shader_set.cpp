// shader_set.cpp: finding, compiling and binding the scene's RSL shaders, and writing the
// generated part of the shade stage's OpenCL source.
#include "shader_set.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <glm/glm.hpp>
#include <set>
#include <sstream>

#include "compiler.h"
#include "emit_cl.h"
#include "light_services.h"
#include "message_services.h"
#include "ocl/program.h"
#include "scene/dice_displaced.h"
#include "shader_aovs.h"
#include "shader_path.h"
#include "space_services.h"

namespace rd {
namespace fs = std::filesystem;

namespace {

// The scene block at the front of the params buffer (ShaderSet::prepare), float offsets:
// camera to current (16, the RSL row-vector matrix), the "world" row (-worldOrigin, 1),
// Format (x, y resolution, pixel aspect) then Clipping (near, far); a multiple of four
// floats, as light blocks after it load float4s.
// Then the starts of attribute()'s table and option()'s block (message_services.h),
// the start of the per-material Exterior table (1 + the shader's index, 0 for none),
// the start of the table of spaces (space_services.h), the start of the per-material
// trace() depth limits (when they differ), the clipping planes
// (normal, offset: clipped where n.P + offset > 0), then current to camera (16).
constexpr size_t kSceneCamera = 0, kSceneWorld = 16, kSceneFormat = 20,
                 kSceneAttributes = 25, kSceneOptions = 26, kSceneShaderBlocks = 27,
                 kSceneExteriors = 28, kSceneSpaces = 29, kSceneDepths = 30,
                 kSceneClipPlanes = 32,
                 kSceneCameraInverse = kSceneClipPlanes + 4 * kMaxClipPlanes,
                 kSceneFloats = kSceneCameraInverse + 16;

// The block about to be appended to out.params has uniform work to do once (hoist.h).
void addPrepare(ShadingSetup& out, const rsl::EmittedShader& sh) {
    if (!sh.prepFunction.empty())
        out.prepares.push_back({sh.prepFunction, uint32_t(out.params.size())});
}

// The strings an instance of a texture-using shader may pass as map names.
void noteTextures(ShadingSetup& out, const rsl::EmittedShader& sh, const ShaderRef& call) {
    if (!sh.usesTexture) return;
    out.textures = true;
    for (const std::string& s : sh.strings) out.textureNames.push_back(s);
    for (const rsl::ParamSlot& slot : sh.params) {
        if (slot.type.base != rsl::BaseType::String) continue;
        for (const std::string& s : slot.stringDefaults) out.textureNames.push_back(s);
        if (const rib::Param* p = call.params.find(slot.name))
            for (const std::string& s : p->strings) out.textureNames.push_back(s);
    }
}

// Compiles shader NAME of `file` (its one shader, or the one of that name); false, with
// the reasons in `messages`, when it does not compile.
bool compileShader(const std::string& file, const std::string& name,
                   const std::vector<std::string>& includeDirs, int colorChannels,
                   std::ostream& messages, rsl::EmittedShader& emitted) {
    rsl::Diagnostics rd(&messages);
    rsl::Program prog;
    rsl::PreprocessOptions opts;
    opts.includeDirs = includeDirs;
    const rsl::ShaderDecl* decl = nullptr;
    if (rsl::compileFile(file, opts, prog, rd))
        for (const auto& sh : prog.shaders)
            if (sh->name == name || prog.shaders.size() == 1) decl = sh.get();
    if (decl) emitted = rsl::emitOpenCL(*decl, prog, rd, colorChannels);
    return decl && emitted.ok && !rd.hasErrors();
}
}  // namespace

bool shaderReadsObjectSpace(const Scene& options, const std::string& name) {
    const std::vector<std::string> path = shaderSearchPath(
        options.shaderSearchPath, fs::path(options.sourceFile).parent_path().string());
    const std::string file = findShaderFile(path, name);
    std::ostringstream quiet;  // (ShaderSet reports what is wrong with it)
    rsl::EmittedShader emitted;
    return !file.empty() &&
           compileShader(file, name, path, options.colors.n, quiet, emitted) &&
           emitted.usesObjectSpace;
}

ShaderSet::ShaderSet(const Scene& scene, rib::Diagnostics& diag)
    : m_scene(scene),
      m_diag(diag),
      m_path(shaderSearchPath(scene.shaderSearchPath,
                              fs::path(scene.sourceFile).parent_path().string())) {}

ShaderSet::~ShaderSet() = default;

namespace {
// What happens to a shader of this kind that cannot be used.
std::string leftOut(const std::string& kind) {
    return kind == "light"          ? "light left out"
           : kind == "volume"       ? "volume shader left out"
           : kind == "displacement" ? "displacement left out"
           : kind == "imager"       ? "imager left out"
                                    : "using defaultsurface";
}
}  // namespace

const rsl::EmittedShader* ShaderSet::find(const std::string& name, const std::string& kind,
                                          const rib::SourceLoc& loc) {
    auto it = m_cache.find(name);
    if (it != m_cache.end()) return it->second.get();
    std::unique_ptr<rsl::EmittedShader>& slot = m_cache[name];
    const std::string file = findShaderFile(m_path, name);
    if (file.empty()) {
        m_diag.warning(loc, kind + " shader \"" + name + "\" not found (" + name +
                                ".sl on the shader search path); " +
                                leftOut(kind));
        return nullptr;
    }
    std::ostringstream messages;
    rsl::EmittedShader emitted;
    const bool compiled =
        compileShader(file, name, m_path, m_scene.colors.n, messages, emitted);
    // The compiler's own messages carry the shader file's line and column.
    std::istringstream lines(messages.str());
    for (std::string l; std::getline(lines, l);)
        if (l.find(": warning: ") == std::string::npos)
            m_diag.warning(loc, "in " + kind + " shader \"" + name + "\": " + l + " (" +
                                    leftOut(kind) + ")");
    if (!compiled) return nullptr;
    if (emitted.kind != kind) {
        m_diag.warning(loc, "shader \"" + name + "\" is a " + emitted.kind +
                                " shader, not a " + kind + " shader; not used");
        return nullptr;
    }
    for (const std::string& space : emitted.namedSpaces)
        if (!m_scene.coordinateSystems.count(space))
            m_diag.warning(loc,
                           kind + " shader \"" + name + "\" names coordinate system \"" +
                               space +
                               "\", which the scene does not define "
                               "(CoordinateSystem); \"current\" space stands for it");
    slot = std::make_unique<rsl::EmittedShader>(std::move(emitted));
    return slot.get();
}

// Binds each call of a list of shaders run by index (atmospheres, displacements): its
// parameter block goes into out.params, its case into `cases`, its code into `shaders`
// once. A shader that cannot be used is reported by find() and skipped.
bool ShaderSet::bindCases(const std::vector<ShaderRef>& refs, const std::string& kind,
                          const std::string& evArg, ShadingSetup& out,
                          std::ostream& cases, std::ostream& shaders,
                          std::set<std::string>& emitted, BoundCalls& bound) {
    bool any = false;
    bound.assign(refs.size(), {nullptr, -1});
    for (size_t i = 0; i < refs.size(); ++i) {
        const rsl::EmittedShader* sh = find(refs[i].name, kind, refs[i].loc);
        if (!sh) continue;
        bound[i] = {sh, int32_t(out.params.size())};
        std::vector<float> block = bindParameters(*sh, refs[i], m_diag, m_scene.colors);
        addPrepare(out, *sh);
        noteTextures(out, *sh, refs[i]);
        cases << "    case " << i << ": " << sh->functionName << "(g, params + "
              << out.params.size() << ", " << evArg << "); break;\n";
        out.params.insert(out.params.end(), block.begin(), block.end());
        if (emitted.insert(sh->name).second) shaders << sh->source << "\n";
        any = true;
    }
    return any;
}

namespace {
// The scene block (kScene* offsets): what the services read that moves with the camera.
std::vector<float> sceneBlock(const Scene& scene) {
    std::vector<float> params(kSceneFloats, 0.0f);
    // RSL row-vector matrices are glm's column-major arrays as they are.
    const glm::mat4 camToWorld = glm::inverse(scene.camera.worldToCamera);
    std::copy_n(&camToWorld[0][0], 16, params.begin() + kSceneCamera);
    const glm::mat4& toCamera = scene.camera.worldToCamera;
    std::copy_n(&toCamera[0][0], 16, params.begin() + kSceneCameraInverse);
    // "world": the renderer's current space is the world moved so the eye is at the
    // origin (precision far from it); world points are current + worldOrigin.
    const glm::dvec3& wo = scene.worldOrigin;
    float* w = &params[kSceneWorld];
    w[0] = float(-wo.x), w[1] = float(-wo.y), w[2] = float(-wo.z), w[3] = 1.0f;
    for (size_t k = 0; k < std::min(scene.clipPlanes.size(), kMaxClipPlanes); ++k) {
        const auto& [p, n] = scene.clipPlanes[k];
        float* c = &params[kSceneClipPlanes + 4 * k];
        c[0] = n.x, c[1] = n.y, c[2] = n.z, c[3] = -glm::dot(n, p);
    }
    float* f = &params[kSceneFormat];
    f[0] = float(scene.camera.width), f[1] = float(scene.camera.height);
    f[2] = scene.camera.pixelAspect;
    f[3] = scene.camera.clipNear, f[4] = std::min(scene.camera.clipFar, 1e30f);
    return params;
}

// The defines the shading source starts with: the light cache's size and the light
// coefficients (rsl_abi.h), and where the scene block keeps what the kernels read.
std::string shadingDefines(uint32_t lightCount, bool lightCoefs) {
    // the shadow lookups' world origin: the world row's translation, negated
    const std::string w = "(p)[" + std::to_string(kSceneWorld);
    return "#define RSL_LIGHT_CACHE " +
           std::to_string(std::clamp<uint32_t>(lightCount, 1, kLightCoefLimit)) + "\n" +
           (lightCoefs ? "#define RSL_LIGHT_COEFS " + std::to_string(lightCount) + "\n"
                       : "") +
           "#define RD_SCENE_WORLD_ORIGIN(p) (float4)(-" + w + "], -" + w + " + 1], -" +
           w + " + 2], 0.0f)\n#define RD_SCENE_CLIP_PLANES " +
           std::to_string(kSceneClipPlanes) + "\n#define RD_SCENE_EXTERIORS " +
           std::to_string(kSceneExteriors) + "\n#define RD_SCENE_DEPTHS " +
           std::to_string(kSceneDepths) + "\n";
}

// imager_apply: the Imager shader `function` (its block at `offset`) over the resolved
// pixels (host/render/imager_stage).
std::string imagerKernel(const std::string& function, size_t offset) {
    return "__kernel void imager_apply(uint width, uint count, __global float4* pixels,\n"
           "                           __global const float* params,\n"
           "                           __global uint* active_counter) {\n"
           "    uint i = get_global_id(0);\n"
           "    RT_COUNT_RANGE(active_counter, count);\n"
           "    if (i >= count) return;\n"
           "    float4 c = pixels[i];\n"
           "    RslGlobals g;\n"
           "    g.P = (float4)((float)(i % width) + 0.5f, (float)(i / width) + 0.5f, "
           "0.0f, "
           "0.0f);\n"
           "    g.N = g.Ng = g.I = g.E = g.dPdu = g.dPdv = g.L = g.Ps = (float4)(0.0f);\n"
           "    g.Cl = rsl_f2c(0.0f);\n"
           "    g.Cs = g.Os = rsl_f2c(1.0f);\n"
           "    g.Ci = rsl_c3(c); /* the film's RGB (rsl_abi.h, COLOURS) */\n"
           "    g.Oi = rsl_f2c(c.w);\n"
           "    g.Ol = rsl_f2c(0.0f);\n"
           "    RSL_CW(g.Ol) = c.w; /* alpha (rsl_abi.h, IMAGER) */\n"
           "    g.u = g.v = g.s = g.t = g.du = g.dv = g.time = 0.0f;\n"
           "    g.ncomps = (float)RSL_CHANNELS;\n"
           "    g.light_cache_count = 0;\n"
           "    g.light_cache = 0;\n"
           "    g.loops_cut = 0;\n"
           "    g.lights_off = 0u;\n"
           "    g.rng_pixel = i;\n    g.rng_sample = 0u;\n    g.rng_depth = 0u;\n"
           "    g.texctx = 0;\n"
           "    g.scene_params = params;\n"
           "    g.material = -1;\n    g.ray_depth = 0u;\n"
           "    RslEval ev;\n"
           "    rd_eval_init(&ev, 0, 0, -1, -1);\n"
           "    " +
           function + "(&g, params + " + std::to_string(offset) +
           ", &ev);\n"
           "    float4 rgb = rsl_c2v(g.Ci);\n"
           "    pixels[i] = (float4)(rgb.x, rgb.y, rgb.z, RSL_CW(g.Ol));\n"
           "}\n";
}

// rd_prepare_uniforms: uniform work, once per bound instance, one work-item each.
std::string prepareKernel(const std::vector<std::pair<std::string, uint32_t>>& prepares) {
    if (prepares.empty()) return {};
    std::ostringstream prep;
    prep << "__kernel void rd_prepare_uniforms(uint count, __global float* params,\n"
            "                                  __global uint* active_counter) {\n"
            "    uint i = get_global_id(0);\n"
            "    RT_COUNT_RANGE(active_counter, count);\n    switch (i) {\n";
    for (size_t i = 0; i < prepares.size(); ++i)
        prep << "    case " << i << ": " << prepares[i].first << "(params + "
             << prepares[i].second << ", params); break;\n";
    prep << "    default: break;\n    }\n}\n";
    return prep.str();
}

// A volume kind's dispatcher rd_<kind>(index, globals, params, evaluation) over its
// bound calls' `cases`.
std::string volumeDispatcher(const char* kind, const std::string& cases) {
    return std::string("static void rd_") + kind +
           "(int a, RslGlobals* g, __global const float* params, RslEval* ev) {\n"
           "    switch (a) {\n" +
           cases + "    default: break;\n    }\n}\n";
}

// The generated sources: the shaders and their services (rd_shading.cl), the shade
// kernels (rd_shade_kernels.cl), and the order the program takes them in.
void writeSources(ShadingSetup& out, bool lightCoefs, const std::string& shading,
                  const std::string& kernels) {
    out.generated["rd_shading.cl"] =
        shadingDefines(out.lightCount, lightCoefs) +
        "#ifdef RD_SPECIALISED_LIGHTS\n#define RSL_LIGHT_FUNCTION "
        "inline __attribute__((always_inline))\n#endif\n"
        "#define RSL_SHADER_FUNCTION inline __attribute__((always_inline))\n"
        "#include \"sample_random.clh\"\n"
        "#include \"rsl_abi.h\"\n#include \"rsl_stdlib.clh\"\n"
        "#include \"area_light.clh\"\n" +
        shading;
    out.generated["rd_shade_kernels.cl"] =
        "#include \"counters.clh\"\n#include \"shade_common.clh\"\n#include "
        "\"volume.clh\"\n" +
        kernels;
    out.sourceOrder = {"rd_shading.cl", "rd_textures.cl", "rd_shade_kernels.cl"};
}
}  // namespace

// Light instances: their parameters in the params buffer (with their uniform work
// prepared, as a surface's), followed by the light's place (P, N) and an area light's
// triangles (light_services.h).
BoundLights ShaderSet::bindLights(ShadingSetup& out, std::ostream& shaders) {
    BoundLights lights;
    for (size_t sceneLight = 0; sceneLight < m_scene.lights.size(); ++sceneLight) {
        const ShaderRef& l = m_scene.lights[sceneLight];
        const rsl::EmittedShader* sh = find(l.name, "light", l.loc);
        if (!sh) continue;
        std::vector<float> block = bindParameters(*sh, l, m_diag, m_scene.colors);
        noteTextures(out, *sh, l);
        // In the light shader P and N are the light's own: its shader-space origin and +z
        // axis, or for an area light a point of its geometry (below)
        glm::vec3 o(l.shaderToWorld * glm::vec4(0, 0, 0, 1));
        glm::vec3 n = glm::transpose(glm::inverse(glm::mat3(l.shaderToWorld))) * glm::vec3(0, 0, 1);
        if (glm::dot(n, n) > 0.0f) n = glm::normalize(n);
        addPrepare(out, *sh);
        const size_t at = out.params.size(), placeAt = at + block.size();
        lights.block.push_back(at);
        out.params.insert(out.params.end(), block.begin(), block.end());
        out.params.insert(out.params.end(), {o.x, o.y, o.z, 0.0f, n.x, n.y, n.z, 0.0f});
        lights.place.push_back(placeAt);
        lights.areaAt.push_back(0);
        lights.areaCount.push_back(0);
        const auto known =
            std::find_if(lights.shaders.begin(), lights.shaders.end(),
                         [&](const auto* s) { return s->name == sh->name; });
        lights.shaderOf.push_back(int(known - lights.shaders.begin()));
        if (known == lights.shaders.end()) {
            lights.shaders.push_back(sh);
            shaders << sh->source << "\n";
        }
        // an area light: a point on its geometry instead, weighted by area
        auto area = m_scene.areaLightTriangles.find(uint32_t(sceneLight));
        if (area != m_scene.areaLightTriangles.end() && !area->second.empty()) {
            const auto& tris = area->second;
            const size_t count = std::min<size_t>(tris.size(), 4096);
            if (count < tris.size())
                m_diag.warning(l.loc, "area light geometry of " + std::to_string(tris.size()) +
                                          " triangles: the first 4096 emit");
            lights.areaAt.back() = appendAreaTriangles(tris, count, out.params);
            lights.areaCount.back() = count;
        }
        lights.ambient.push_back(sh->ambientLight);
        // a light whose "shadowname" names a shadow map is shadowed by that map (its
        // shader's shadow() call) instead of by a traced shadow ray
        const rib::Param* sn = l.params.find("shadowname");
        const std::string map = sn && !sn->strings.empty() ? sn->strings[0] : "";
        lights.mapShadowed.push_back(!map.empty() && map != "raytrace");
        out.shadowRays |= !sh->ambientLight;
    }
    out.lightCount = lights.count();
    return lights;
}

// Surfaces: one compiled shader per name, each with its shade kernel (shade_rsl.cl made
// its own), and one parameter block per call; a shader that cannot be used gives way to
// defaultsurface. `aovs`: those the render writes (shader_aovs.h).
ShaderSet::BoundSurfaces ShaderSet::bindSurfaces(ShadingSetup& out,
                                                 const std::vector<std::string>& aovs,
                                                 bool lightCoefs, std::ostream& shaders,
                                                 std::ostream& kernels) {
    BoundSurfaces bound;
    const size_t refs = m_scene.surfaceRefs.size();
    bound.block.resize(refs);
    bound.shader.resize(refs);
    bound.pointParams.resize(refs);
    std::map<std::string, uint32_t> surfaceIndex;
    const std::string& kernelTemplate = embeddedClSources().at("shade_rsl.cl");
    // The AOVs the surface shaders write: laid out over every shader the scene uses
    std::vector<const rsl::EmittedShader*> surfaces;
    for (const ShaderRef& ref : m_scene.surfaceRefs)
        surfaces.push_back(find(ref.name, "surface", ref.loc));
    out.aovs = layoutShaderAovs(aovs, m_scene, surfaces, m_diag);
    out.aovFloats = shaderAovFloats(out.aovs);
    for (size_t r = 0; r < m_scene.surfaceRefs.size(); ++r) {
        const ShaderRef& ref = m_scene.surfaceRefs[r];
        const rsl::EmittedShader* sh = find(ref.name, "surface", ref.loc);
        ShaderRef fallback{"defaultsurface", {}, ref.shaderToWorld, ref.loc};
        if (!sh) sh = find("defaultsurface", "surface", ref.loc);
        const ShaderRef& call = sh && sh->name == ref.name ? ref : fallback;
        if (!sh) continue;
        auto [it, fresh] = surfaceIndex.emplace(sh->name, uint32_t(out.surfaceNames.size()));
        if (fresh) {
            bound.shaders.push_back(sh);
            out.surfaceNames.push_back(sh->name);
            out.shadeKernels.push_back("shade_" + sh->name);
            shaders << sh->source << "\n";
            std::string k = "#define RSL_DERIVS_" + sh->name + " " +
                            (sh->usesDerivatives ? "1" : "0") + "\n#define RD_LIGHT_COEFS_" +
                            sh->name + " " + (lightCoefs && sh->lightCoefs ? "1" : "0") + "\n" +
                            (out.aovFloats > 0 ? shaderAovMacros(*sh, out.aovs, m_diag, ref.loc)
                                               : std::string()) +
                            kernelTemplate;
            for (size_t p = k.find("SURFACE"); p != std::string::npos; p = k.find("SURFACE", p))
                k.replace(p, 7, sh->name);
            kernels << k << "\n";
            out.usesTrace |= sh->usesTrace;
            out.traceSlots = std::max(out.traceSlots, sh->traceBound);
            out.lightCoefs |= lightCoefs && sh->lightCoefs;
            out.sampledTrace |= sh->usesTrace && sh->usesRandom;
            out.visibilityRays |= sh->usesVisibility;
            out.shaderOpacity |= sh->writesOpacity;
            out.derivatives |= sh->usesDerivatives;
        }
        bound.shader[r] = it->second;
        bound.block[r] = uint32_t(out.params.size());
        bound.pointParams[r] = pointParamOffsets(*sh, call, m_diag);
        std::vector<float> block = bindParameters(*sh, call, m_diag, m_scene.colors);
        addPrepare(out, *sh);
        noteTextures(out, *sh, call);
        out.params.insert(out.params.end(), block.begin(), block.end());
    }
    return bound;
}

// The names of spaces a shader with the space table may ask for: its literals, and the
// strings its calls and defaults give (a space named by a parameter).
std::set<std::string> ShaderSet::spaceNames() const {
    std::set<std::string> names;
    for (const auto& [name, sh] : m_cache) {
        if (!sh || !sh->usesSpaceTable) continue;
        names.insert(sh->namedSpaces.begin(), sh->namedSpaces.end());
        for (const rsl::ParamSlot& slot : sh->params)
            names.insert(slot.stringDefaults.begin(), slot.stringDefaults.end());
    }
    for (const auto* calls :
         {&m_scene.surfaceRefs, &m_scene.lights, &m_scene.displacements,
          &m_scene.atmospheres, &m_scene.interiors, &m_scene.exteriors})
        for (const ShaderRef& call : *calls)
            for (const rib::Param& p : call.params.params)
                names.insert(p.strings.begin(), p.strings.end());
    return names;
}

// Whether some compiled shader's code calls `service` (its name and first argument).
bool ShaderSet::someShaderCalls(const char* service) const {
    return std::any_of(m_cache.begin(), m_cache.end(), [&](const auto& entry) {
        return entry.second && entry.second->source.find(service) != std::string::npos;
    });
}

ShadingSetup ShaderSet::prepare(const std::vector<std::string>& aovs) {
    ShadingSetup out;
    std::ostringstream shaders, svc, kernels;
    // --- the scene block, at the front of the params buffer (RslGlobals::scene_params)
    out.params = sceneBlock(m_scene);
    const SpaceSlots spaces{kSceneCamera, kSceneCameraInverse, kSceneWorld, kSceneSpaces};
    // --- light instances and the services that run them (light_services.h)
    const BoundLights lights = bindLights(out, shaders);
    svc << lightServices(lights) << spaceService(spaces);
    // Light coefficients (rsl_abi.h): the base evaluation of a surface gives each light's
    // coefficient, where the kernel otherwise evaluated the surface once more per light.
    // The light cache holds every light up to the same limit (rsl_abi.h RslLightCache).
    const bool lightCoefs = out.lightCount >= 1 && out.lightCount <= kLightCoefLimit;
    // --- surfaces: one compiled shader per name, one parameter block per call
    const BoundSurfaces surfaces = bindSurfaces(out, aovs, lightCoefs, shaders, kernels);
    std::set<std::string> emitted;
    BoundVolumes volumes;
    bindVolumes(out, shaders, svc, emitted, volumes);
    appendMaterialDepths(out);
    bindDisplacements(out, shaders, svc, emitted, volumes);
    const std::string imager = bindImager(out, shaders);
    bindMaterials(out, surfaces, volumes);
    // Each light shader is inlined at its one call site (RD_SPECIALISED_LIGHTS). Light
    // parameters were compiled-in constants, each of the first 32 instances inlined with
    // its own, until the light's uniform work (a cone's cosine, its axis) was prepared
    // like a surface's: shade_spd is the same (SPD gears, balls: 1.02x; with the cone's
    // cos() left per point: 1.35x), an edited light keeps the program, and 40 spotlights
    // shade in 0.79x the time with one inlined copy instead of 32.
    // Surface shaders are inlined into their shade kernel's few call sites (base, light
    // and trace modes): the work a mode does not change is hoisted out of the light loop
    // (shade_spd a further 0.9x; a cold test suite 2-3% longer to build).
    // attribute() and option(), once every shader is known (attribute data only when
    // some shader asks); the table of spaces, when some shader reads it
    if (std::any_of(m_cache.begin(), m_cache.end(), [](const auto& entry) {
            return entry.second && entry.second->usesSpaceTable;
        }))
        appendSpaceTable(m_scene, spaces, spaceNames(), out.params);
    const bool shaderParamsUsed = someShaderCalls("rsl_shader_param(g");
    svc << shaderParamService(shaderBlocks(out, surfaces, volumes, shaderParamsUsed),
                              shaderParamsUsed, kSceneShaderBlocks, out.params);
    svc << messageServices(
        m_scene, someShaderCalls("rsl_attribute(g"),
        MessageSlots{kSceneFormat, kSceneFormat + 3, kSceneAttributes, kSceneOptions},
        out.params, m_diag);
    writeSources(out, lightCoefs, shaders.str() + svc.str(),
                 kernels.str() + imager + prepareKernel(out.prepares));
    if (out.displacement && hasTrueDisplacement(m_scene))  // (true_displacement.h)
        out.sourceOrder.push_back("displace_vertices.cl");
    return out;
}

// Atmospheres, interiors (what comes back from inside a surface) and exteriors (from
// outside the surface a ray left; a table by material: its flag bits are taken). Each
// kind's calls bound, and its dispatcher (the kernel's evaluation: every light, or under
// RT_VOLUME_SHADOWS one light's evaluations counted or picked; no traces, no
// derivatives).
void ShaderSet::bindVolumes(ShadingSetup& out, std::ostream& shaders, std::ostream& svc,
                            std::set<std::string>& emitted, BoundVolumes& volumes) {
    auto bindKind = [&](const std::vector<ShaderRef>& calls, const char* kind,
                        BoundCalls& bound) {
        std::ostringstream cases;
        if (!bindCases(calls, "volume", "ev", out, cases, shaders, emitted, bound))
            return false;
        svc << volumeDispatcher(kind, cases.str());
        for (const auto& b : bound) out.volumeLights |= b.first && b.first->usesLighting;
        return true;
    };
    out.atmosphere = bindKind(m_scene.atmospheres, "atmosphere", volumes.atmospheres);
    out.interior = bindKind(m_scene.interiors, "interior", volumes.interiors);
    out.exterior = bindKind(m_scene.exteriors, "exterior", volumes.exteriors);
    if (!out.exterior) return;
    out.params[kSceneExteriors] = intBits(int64_t(out.params.size()));
    for (size_t mi = 0; mi < m_scene.materials.size(); ++mi) {
        const uint32_t e =
            mi < m_scene.materialExterior.size() ? m_scene.materialExterior[mi] : 0;
        const bool bound =
            e > 0 && e <= volumes.exteriors.size() && volumes.exteriors[e - 1].first;
        out.params.push_back(bound ? float(e) : 0.0f);
    }
}

// Objects' own trace() depth limits, when they differ and some shader traces
void ShaderSet::appendMaterialDepths(ShadingSetup& out) const {
    const auto& depths = m_scene.materialSpecularDepth;
    out.materialDepths = out.usesTrace && depths.size() == m_scene.materials.size() &&
                         std::any_of(depths.begin(), depths.end(), [&](int d) {
                             return d != m_scene.maxSpecularDepth;
                         });
    if (!out.materialDepths) return;
    out.params[kSceneDepths] = intBits(int64_t(out.params.size()));
    for (int d : depths) out.params.push_back(float(d));
}

// Displacements: bump shaders run before the surface (shade_common.clh rd_displace)
void ShaderSet::bindDisplacements(ShadingSetup& out, std::ostream& shaders,
                                  std::ostream& svc, std::set<std::string>& emitted,
                                  BoundVolumes& volumes) {
    std::ostringstream disp;
    out.displacement = bindCases(m_scene.displacements, "displacement", "ev", out, disp,
                                 shaders, emitted, volumes.displacements);
    if (out.displacement)
        svc << "static void rd_displace(int d, RslGlobals* g, __global const float* "
               "params, "
               "RslEval* ev) {\n    switch (d) {\n"
            << disp.str() << "    default: break;\n    }\n}\n";
}

// The imager: a kernel over the resolved pixels (host/render/imager_stage); "" if none
std::string ShaderSet::bindImager(ShadingSetup& out, std::ostream& shaders) {
    if (m_scene.imager.name.empty()) return "";
    const ShaderRef& ref = m_scene.imager;
    const rsl::EmittedShader* sh = find(ref.name, "imager", ref.loc);
    if (!sh) return "";
    std::vector<float> block = bindParameters(*sh, ref, m_diag, m_scene.colors);
    addPrepare(out, *sh);
    noteTextures(out, *sh, ref);
    std::string imager = imagerKernel(sh->functionName, out.params.size());
    out.params.insert(out.params.end(), block.begin(), block.end());
    shaders << sh->source << "\n";
    out.imager = true;
    return imager;
}

}  // namespace rd
