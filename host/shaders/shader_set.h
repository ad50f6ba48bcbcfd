// shader_set.h: the scene's RSL shaders, compiled by rsl2cl for this render. It finds each
// shader on the search path (Option "searchpath" "shader", the RIB's folder, the current
// folder, RayDrive's standard shaders), compiles it once, binds every Surface and
// LightSource call's parameters into float blocks (RIB values over the shader's defaults,
// points moved from "shader" space to world space), and assembles the OpenCL source of
// the shade stage: the RSL runtime, the light instances (their blocks lead the parameter
// buffer), the services the generated code calls, the shaders, and one shade kernel per
// surface shader.
#pragma once
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "film/film.h"
#include "light_services.h"
#include "message_services.h"
#include "rib/diagnostics.h"
#include "scene/scene.h"

namespace rsl {
struct EmittedShader;
}

namespace rd {

// Scenes with at most this many lights take each light's coefficient from a surface's
// base evaluation (rsl_abi.h, LIGHT COEFFICIENTS): its private arrays grow with the
// lights, one float4 a light for Ci and for each light-dependent variable.
constexpr uint32_t kLightCoefLimit = 64;

// The ints a material takes in ShadingSetup::pointParamLayout (shade_common.clh reads
// them): the count, the surface shader's slots, the displacement shader's.
inline size_t pointParamLayoutStride(size_t maxPointParams) {
    return 1 + 2 * maxPointParams;
}

struct ShadingSetup {
    // Extra OpenCL sources by name (generated), and the kernel files to assemble.
    std::map<std::string, std::string> generated;
    std::vector<std::string> sourceOrder;
    std::vector<std::string> shadeKernels;  // per compiled surface shader
    std::vector<std::string> surfaceNames;  // the shaders themselves, same order
    std::vector<Material> materials;        // Material::shader/params filled in
    // the scene block, every light instance's block and place (rsl_abi.h
    // RslGlobals::scene_params), then every surface instance's block
    std::vector<float> params;
    // Parameters given per point (ShaderRef::pointParams), when some surface has them:
    // per material, pointParamLayoutStride(maxPointParams) ints: how many its primitives
    // give, then the offset of each in its surface shader's block, then in its
    // displacement shader's (maxPointParams each; -1: the shader has no float or triple
    // of that name, or there is none)
    int maxPointParams = 0;
    std::vector<int32_t> pointParamLayout;
    uint32_t lightCount = 0;                // LightSource instances (ambient included)
    bool shadowRays = false;                // some light is not ambient
    // Some surface's base evaluation gives every light's coefficient (rsl_abi.h, LIGHT
    // COEFFICIENTS; at most kLightCoefLimit lights): it is not evaluated per light.
    bool lightCoefs = false;
    bool usesTrace = false;                 // some surface calls trace()
    // Some surface calls trace() and random(): its traced rays sample directions (glossy,
    // diffuse), incoherent, unlike mirror and glass rays.
    bool sampledTrace = false;
    bool visibilityRays =
        false;           // some surface calls occlusion(): rays that ask if they escape
    int traceSlots = 0;  // rays a hit may spawn with trace(): the surfaces' most a run
    // Some surface's shader sets Oi below Os (EmittedShader::writesOpacity): rays go on
    // through it even where every Os is 1 (RT_HAS_TRANSPARENCY).
    bool shaderOpacity = false;
    bool atmosphere = false;                // some surface has an Atmosphere shader
    bool interior = false;                  // some surface has an Interior shader
    bool exterior = false;                  // some surface has an Exterior shader
    bool volumeLights = false;              // some volume shader loops over the lights
    // Objects' trace() depth limits differ (Scene::materialSpecularDepth): a table by
    // material in the scene block
    bool materialDepths = false;
    bool displacement = false;              // some surface has a Displacement shader
    bool derivatives = false;               // some surface shader takes derivatives
    bool imager = false;                    // the kernel imager_apply runs the Imager
    // Prepare functions and their blocks' offsets in params: the kernel
    // rd_prepare_uniforms runs each once before shading (uniform work, rsl::HoistPlan).
    std::vector<std::pair<std::string, uint32_t>> prepares;
    // Some shader calls texture(), environment(), shadow() or bump(); the strings its
    // instances may pass as map names (parameter values, literals), for TextureSet.
    bool textures = false;
    std::vector<std::string> textureNames;
    // The AOVs shaders write (shader_aovs.h), RT_SHADER_AOVS floats a sample in all.
    std::vector<ShaderAov> aovs;
    int aovFloats = 0;
};

class ShaderSet {
public:
    ShaderSet(const Scene& scene, rib::Diagnostics& diag);
    ~ShaderSet();
    // Compiles what the scene uses. Shaders that cannot be found or compiled are
    // reported (file:line of the request, then the compiler's own file:line:col) and
    // replaced: surfaces by defaultsurface, lights dropped. `aovs`: the AOVs the render
    // writes; the shaders write those that are not the renderer's own (shader_aovs.h).
    ShadingSetup prepare(const std::vector<std::string>& aovs = {});

    // Directories searched for NAME.sl, in order.
    const std::vector<std::string>& searchPath() const { return m_path; }

private:
    // Per call of a kind, its shader and its block's start; nullptr, -1 when skipped.
    using BoundCalls = std::vector<std::pair<const rsl::EmittedShader*, int32_t>>;
    struct BoundVolumes {
        BoundCalls atmospheres, interiors, exteriors, displacements;
    };
    // Per surface call (Scene::surfaceRefs): its shader's index among the compiled
    // surfaces, its block's start, where its per-point parameters go.
    struct BoundSurfaces {
        std::vector<const rsl::EmittedShader*> shaders;  // each compiled surface, once
        std::vector<uint32_t> shader, block;
        std::vector<std::vector<int32_t>> pointParams;
    };

    const rsl::EmittedShader* find(const std::string& name, const std::string& kind,
                                   const rib::SourceLoc& loc);
    bool bindCases(const std::vector<ShaderRef>& refs, const std::string& kind,
                   const std::string& evArg, ShadingSetup& out, std::ostream& cases,
                   std::ostream& shaders, std::set<std::string>& emitted,
                   BoundCalls& bound);
    BoundLights bindLights(ShadingSetup& out, std::ostream& shaders);
    BoundSurfaces bindSurfaces(ShadingSetup& out, const std::vector<std::string>& aovs,
                               bool lightCoefs, std::ostream& shaders,
                               std::ostream& kernels);
    void bindMaterials(ShadingSetup& out, const BoundSurfaces& surfaces,
                       const BoundVolumes& volumes);
    void bindVolumes(ShadingSetup& out, std::ostream& shaders, std::ostream& svc,
                     std::set<std::string>& emitted, BoundVolumes& volumes);
    void appendMaterialDepths(ShadingSetup& out) const;
    void bindDisplacements(ShadingSetup& out, std::ostream& shaders, std::ostream& svc,
                           std::set<std::string>& emitted, BoundVolumes& volumes);
    std::string bindImager(ShadingSetup& out, std::ostream& shaders);
    ShaderBlocks shaderBlocks(const ShadingSetup& out, const BoundSurfaces& surfaces,
                              const BoundVolumes& volumes, bool used) const;
    std::set<std::string> spaceNames() const;
    bool someShaderCalls(const char* service) const;
    const Scene& m_scene;
    rib::Diagnostics& m_diag;
    std::vector<std::string> m_path;
    std::map<std::string, std::unique_ptr<rsl::EmittedShader>> m_cache;  // null: failed
};

// Whether shader NAME, found on the scene's search path as ShaderSet finds it, reads
// "object" space: each primitive's own object space then needs an instance of its own
// (ShaderRef::objectToWorld). Compiled quietly: ShaderSet reports what is wrong with it.
bool shaderReadsObjectSpace(const Scene& options, const std::string& name);

// Binds a shader call's parameters: defaults, then the RIB's values (by name, checked
// against the declared type), points/vectors/normals moved to world space, RGB colour
// defaults in the scene's colour channels; for an imager (which works on the film's RGB)
// the RIB's colours are made RGB instead.
std::vector<float> bindParameters(const rsl::EmittedShader& shader, const ShaderRef& call,
                                  rib::Diagnostics& diag, const ColorSamples& colors = {});

// Where each of the call's per-point parameters (ShaderRef::pointParams) goes in its
// block: the offset of the shader's parameter of that name, or -1 (none, or one of
// another size: reported).
std::vector<int32_t> pointParamOffsets(const rsl::EmittedShader& shader, const ShaderRef& call,
                                       rib::Diagnostics& diag);

}  // namespace rd
