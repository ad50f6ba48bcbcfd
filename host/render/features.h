// features.h: what a scene needs (DESIGN.md section 5). analyse() reads the Scene once;
// buildOptions() is the one place -D options for the kernels come from, so a scene gets
// no code, ray fields or buffers for features it does not use.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"
#include "shaders/shader_set.h"

namespace rd {

// The passes a shader's while or for loop may make at one shading point before it is cut
// (RSL_MAX_LOOP_ITERATIONS, rsl_abi.h: a loop that never ends would hang the device;
// the render reports the points, RenderStats::shaderLoopsCut).
constexpr int kShaderLoopPasses = 65536;

struct Features {
    bool smoothNormals = false; // per-vertex normals to interpolate
    bool transparency = false;  // some Os < 1: continuation rays
    // shadow rays through surfaces that let light through (Os < 1, or Attribute
    // "visibility" "transmission" 0): a closest-hit walk attenuating at each
    bool transparentShadows = false;
    // ... and surfaces whose shader's Oi says what a shadow ray keeps (transmission
    // "shader"): the ray goes on in the pool where it meets one (RT_SHADER_SHADOWS)
    bool shaderShadows = false;
    bool shadowRays = false;    // some light other than ambient
    bool trace = false;         // some surface shader calls trace()
    bool sampledTrace = false;  // ... and random(): traced rays in sampled directions
    bool visibilityRays = false;  // ... occlusion(): traced rays that ask if they escape
    int maxSpecularDepth = 2;   // trace() recursion limit
    bool materialDepths = false;  // objects' limits differ: a table by material
    int maxDiffuseDepth = -1;     // maxdiffusedepth given 0 or 1 (RT_MAX_DIFFUSE_DEPTH)
    bool aovs = false;          // AOVs asked for: geometric (z, N) or shaders'
    int shaderAovFloats = 0;    // floats a sample of the shaders' AOVs (shader_aovs.h)
    uint32_t primvars = 0;      // RT_PRIMVAR_* some triangle carries per vertex
    bool depthOfField = false;  // a thin-lens camera
    bool signedFilter = false;  // a pixel filter with negative lobes: samples weigh < 0
    bool quadrics = false;      // exact quadrics (RT_HAS_QUADRICS)
    bool csg = false;           // some of them CSG solids
    bool quadricPrimvars = false;  // some quadric has varying Cs or Os
    bool motion = false;        // moving quadrics or triangles: a time per sample
    bool instances = false;     // ObjectInstance records over shared prototypes
    bool atmosphere = false;    // Atmosphere (volume) shaders on some surfaces
    bool interior = false;      // Interior (volume) shaders on some surfaces
    bool exterior = false;      // Exterior (volume) shaders on some surfaces
    int clipPlanes = 0;         // ClippingPlane requests honoured (camera rays)
    bool oneSided = false;      // Sides 1 surfaces: their backs pass rays on
    bool invisible = false;     // surfaces camera or traced rays go through (visibility)
    bool derivatives = false;   // some shader takes Du/Dv/area/calculatenormal/filterstep
    bool displacement = false;  // Displacement shaders (bump: N only)
    bool textures = false;      // some shader looks up a texture the scene has
    bool procedurals = false;   // DelayedReadArchive bounds not loaded yet
    int pointParams = 0;        // shader parameters given per point: the most on a surface
    bool displacementPointParams = false;  // ... and some reach a displacement shader
    float pixelSpread = 0.0f;   // footprint growth per unit of ray length (perspective)
    bool treelets = false;      // treelet-streamed traversal (render/treelet_trace.h)
    bool int64Min = false;      // the device has 64-bit atomic min (its closest hits)
    int bvhWidth = 4;           // the resident BVH's node width: 4, 8 (RT_BVH8) or 16 (RT_BVH16)
    // intersect_shadow traces packets of RT_PACKET_RAYS rays a work-item
    // (RT_SHADOW_PACKETS): eight- or sixteen-wide resident BVH, no instances, motion or
    // procedurals.
    bool shadowPackets = false;
    // intersect_closest takes RT_PACKET_RAYS consecutive rays a work-item, traced as
    // a packet where they are coherent (RT_CLOSEST_PACKETS); the same conditions.
    bool closestPackets = false;
    // The work-items intersect_shadow takes for `rays` shaded rays and `lights` lights,
    // and intersect_closest for `rays` rays.
    size_t shadowItems(size_t rays, size_t lights) const;
    size_t closestItems(size_t rays) const;
    uint32_t lightCount = 0;
    // Volume shaders loop over the lights and shadow rays are traced: a shaded ray may
    // send one more shadow ray a light, from a point inside the volume it crossed
    // (RT_VOLUME_SHADOWS, shade_rsl.cl).
    bool volumeShadows = false;
    // Shadow ray slots a shaded ray has (the pool's second part, ray.h): one a light, two
    // with volume shadows; 0 without shadow rays.
    uint32_t shadowSlots() const {
        return shadowRays ? lightCount * (volumeShadows ? 2u : 1u) : 0u;
    }
    // Light shaders inlined at their one call site each (every instance of a shader
    // goes through it, told apart by where its data is: shader_set.cpp).
    bool specialisedLights = false;
    // Some surface takes every light's coefficient from its base evaluation
    // (ShadingSetup::lightCoefs).
    bool lightCoefficients = false;
    int maxTransparentDepth = 256;  // Attribute/Option "trace" "maxtransparentdepth"
    int rouletteDepth = 0;      // Russian roulette on traced rays from this depth (0: off)
    // Which random numbers (rng.clh): 0 the default set; another seed gives independent
    // samples of the same image (RT_SEED, so a new seed builds a new program once).
    uint32_t seed = 0;
    // Samples from Owen-scrambled Sobol sequences rather than independent numbers
    // (RT_SAMPLER_SOBOL, rng.clh).
    bool sobol = false;
    // Power of two at least the scene's largest coordinate, at most 1: ray offsets off a
    // surface scale with it (math.clh), so a scene scaled to 1e-6 does not leak light.
    float sceneScale = 1.0f;
    // ColorSamples n <= 3 other than RGB: colours are n channels, converted to RGB as a
    // sample retires (RSL_COLOR_SAMPLES, RSL_NRGB, RSL_RGBN; rsl_abi.h COLOURS)
    ColorSamples colors;

    std::vector<std::string> names() const;
    int traceSlots = 0;         // the most trace() rays a surface's evaluation spawns
    // Rays a shaded hit may spawn: its continuation, plus its traced rays.
    int spawnSlots() const { return trace ? 1 + traceSlots : 1; }
    // A round may leave rays for the next: traced, continued or handed-over shadow rays.
    bool spawns() const { return trace || transparency || shaderShadows; }
    // Floats of a ray's AOV payload (ray_aovs.clh): shader AOVs that rays below trace()
    // calls bring parts back to, or that surfaces behind transparent ones add to, or the
    // lights' parts shadow rays carry on through the pool, one weight an AOV float and
    // colour channel; 0 otherwise.
    int rayAovFloats() const {
        return (trace || transparency || shaderShadows) && shaderAovFloats > 0
                   ? shaderAovFloats * colors.n
                   : 0;
    }
    std::string
        aovChannels;  // each AOV float's channel (shaderAovChannels), when it has any
};

Features analyse(const Scene& scene, const ShadingSetup& shading);
// The traversal the device gets: node width (bvhWidth 4, 8 or 16 as asked, else by
// device: `floatLanes`, its native float vector width) and packets (when asked and the
// scene allows them). After f.treelets is settled.
void chooseTraversal(Features& f, int bvhWidth, bool shadowPackets, bool closestPackets,
                     bool cpuDevice, unsigned floatLanes);

std::string buildOptions(const Features& f);

}  // namespace rd
