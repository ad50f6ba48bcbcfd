// features.cpp: scene analysis and kernel specialisation options.
#include "features.h"

#include "cl/include/ray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rd {

namespace {

// What the materials, the vertices' Os and the quadrics' Os ask for: transparency, one
// sided surfaces, invisibility, transparent or shader-made shadows.
void opacityFeatures(const Scene& scene, Features& f) {
    for (const Material& m : scene.materials) {
        if (m.os.x < 1.0f || m.os.y < 1.0f || m.os.z < 1.0f) f.transparency = true;
        // a one-sided surface's back continues the ray, as a transparent surface does
        if (m.flags & RT_MATERIAL_ONE_SIDED) f.oneSided = f.transparency = true;
        if (m.flags &
            (RT_MATERIAL_NO_CAMERA | RT_MATERIAL_NO_TRACE | RT_MATERIAL_NO_DIFFUSE))
            f.invisible = f.transparency = true;
        // (os.w: the mean opacity, what a shadow through it keeps in other channels)
        const uint32_t shadow = m.flags & RT_MATERIAL_SHADOW_MASK;
        if (shadow == RT_MATERIAL_NO_TRANSMISSION || shadow == RT_MATERIAL_SHADER_SHADOW ||
            (shadow == 0 &&
             (m.os.x < 1.0f || m.os.y < 1.0f || m.os.z < 1.0f || m.os.w < 1.0f)))
            f.transparentShadows = true;
        if (shadow == RT_MATERIAL_SHADER_SHADOW) f.shaderShadows = true;
    }
    const size_t n = size_t(scene.colors.n);  // (more than three: the channels' opacity)
    for (size_t i = 0; n > 3 && i < scene.materialChannels.size(); ++i)
        if (i % (2 * n) >= n && scene.materialChannels[i] < 1.0f) f.transparency = true;
    // (a vertex's Os: a float4, or with more than three channels n floats in lanes / 4)
    const size_t chunks = size_t(scene.colors.lanes() / 4);
    for (size_t i = 0; i < scene.vertexOs.size(); ++i) {
        const rt_float4& o = scene.vertexOs[i];
        const float lanes[4] = {o.x, o.y, o.z, o.w};
        const size_t first = 4 * (i % chunks), channels = size_t(scene.colors.slots());
        for (size_t j = 0; j < 4 && first + j < channels; ++j)
            if (lanes[j] < 1.0f) f.transparency = true;
    }
    // (a quadric's primvars: of each 8 float4s, the Cs corners then the Os corners)
    for (size_t i = 0; i < scene.quadricPrimvars.size(); ++i) {
        const rt_float4& o = scene.quadricPrimvars[i];
        if (i % 8 >= 4 && (o.x < 1.0f || o.y < 1.0f || o.z < 1.0f)) f.transparency = true;
    }
}

// The largest coordinate of the scene's geometry (triangles; quadrics', solids' and
// archives' bounds), which the ray offsets scale with.
float sceneExtent(const Scene& scene) {
    float extent = 0.0f;
    for (const Triangle& t : scene.triangles)
        for (const rt_float4& v : {t.v0, t.v1, t.v2})
            extent = std::fmax(
                extent,
                std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z))));
    for (const Aabb& b : scene.quadricBounds)
        for (int k = 0; k < 3; ++k)
            if (b.lo[k] <= b.hi[k])
                extent =
                    std::fmax(extent, std::fmax(std::fabs(b.lo[k]), std::fabs(b.hi[k])));
    return extent;
}

// Primitive variables that feed shader parameters per point (the scene's data is only
// used when some shader has such a parameter)
void pointParamFeatures(const ShadingSetup& shading, Features& f) {
    const std::vector<int32_t>& layout = shading.pointParamLayout;
    const size_t most = size_t(shading.maxPointParams),
                 stride = pointParamLayoutStride(most);
    for (size_t k = 0; k + stride <= layout.size(); k += stride)
        for (size_t i = 1; i <= size_t(layout[k]) && i <= most; ++i) {
            const bool surface = layout[k + i] >= 0,
                       displacement = layout[k + most + i] >= 0;
            if (surface || displacement) f.pointParams = shading.maxPointParams;
            f.displacementPointParams |= displacement;
        }
}

// What the shaders' code asks of the kernels: lights, shadows, traces, volumes
void shadingFeatures(const ShadingSetup& shading, Features& f) {
    f.lightCount = shading.lightCount;
    f.specialisedLights = f.lightCount > 0;  // (shader_set.cpp: rd_run_light)
    f.shadowRays = shading.shadowRays;
    f.transparentShadows = f.transparentShadows && f.shadowRays;
    f.shaderShadows = f.shaderShadows && f.shadowRays;
    f.lightCoefficients = shading.lightCoefs;
    f.trace = shading.usesTrace;
    f.traceSlots = shading.usesTrace ? std::max(1, shading.traceSlots) : 0;
    f.sampledTrace = shading.sampledTrace;
    f.visibilityRays = shading.visibilityRays;
    f.transparency |= shading.shaderOpacity;  // (a cut-out leaf: its shader's Oi)
    f.materialDepths = shading.materialDepths;
    f.atmosphere = shading.atmosphere;
    f.interior = shading.interior;
    f.exterior = shading.exterior;
    f.volumeShadows = f.shadowRays && shading.volumeLights &&
                      (f.atmosphere || f.interior || f.exterior);
    f.displacement = shading.displacement;
    f.derivatives = shading.derivatives || shading.displacement;
    pointParamFeatures(shading, f);
}

}  // namespace

Features analyse(const Scene& scene, const ShadingSetup& shading) {
    Features f;
    f.smoothNormals = scene.anySmoothNormals;
    opacityFeatures(scene, f);
    f.primvars = scene.primvarsUsed;
    shadingFeatures(shading, f);
    f.maxSpecularDepth = scene.maxSpecularDepth;
    if (scene.maxDiffuseDepth == 0 || scene.maxDiffuseDepth == 1)
        f.maxDiffuseDepth = scene.maxDiffuseDepth;
    f.maxTransparentDepth = scene.maxTransparentDepth;
    f.rouletteDepth = scene.rouletteDepth;
    f.seed = uint32_t(std::max(0, scene.render.seed));
    f.sobol = scene.render.sobol;
    const float extent = sceneExtent(scene);
    while (f.sceneScale > 1e-30f && f.sceneScale * 0.5f >= extent) f.sceneScale *= 0.5f;
    f.colors = scene.colors;
    const Camera camera = scene.deviceCamera();
    f.depthOfField = camera.lens_radius > 0;
    for (int axis = 0; axis < 2; ++axis)  // (a sign change, or negative from the start)
        f.signedFilter |= camera.filter_table && (camera.filter_negative_start[axis] ||
                                                  camera.filter_flips[axis][0] <= 1.0f);
    f.quadrics = !scene.quadrics.empty();
    f.csg = !scene.csg.empty();
    f.quadricPrimvars = !scene.quadricPrimvars.empty();
    f.motion = !scene.quadricMotion.empty() || !scene.trianglesEnd.empty() ||
               scene.camera.moving;
    f.instances = !scene.prototypes.empty();
    f.procedurals = !scene.procedurals.empty();
    // clipped camera rays go on past what they meet, as through a transparent surface
    f.clipPlanes = int(std::min(scene.clipPlanes.size(), kMaxClipPlanes));
    if (f.clipPlanes > 0) f.transparency = true;
    // a pixel's width at unit distance along a perspective eye ray (0 orthographic: the
    // ray's width stays the pixel's)
    if (f.derivatives)
        f.pixelSpread = camera.perspective
                            ? std::fabs(camera.screen[1] - camera.screen[0]) /
                                  float(camera.width) * camera.tan_half_fov
                            : 0.0f;
    return f;
}

std::vector<std::string> Features::names() const {
    std::vector<std::string> n{"triangles"};
    if (quadrics) n.push_back("quadrics");
    if (csg) n.push_back("csg");
    if (quadricPrimvars) n.push_back("quadric_primvars");
    if (motion) n.push_back("motion_blur");
    if (instances) n.push_back("instances");
    if (atmosphere) n.push_back("atmosphere");
    if (interior) n.push_back("interior");
    if (exterior) n.push_back("exterior");
    if (materialDepths) n.push_back("object_specular_depths");
    if (clipPlanes > 0) n.push_back("clipping_planes");
    if (oneSided) n.push_back("one_sided");
    if (invisible) n.push_back("visibility");
    if (derivatives) n.push_back("derivatives");
    if (displacement) n.push_back("displacement");
    if (textures) n.push_back("textures");
    if (procedurals) n.push_back("deferred_procedurals");
    if (pointParams > 0) n.push_back("point_params");
    if (pointParams > 0 && displacementPointParams)
        n.push_back("displacement_point_params");
    if (trace && rouletteDepth > 0) n.push_back("roulette");
    if (smoothNormals) n.push_back("smooth_normals");
    if (transparency) n.push_back("transparency");
    if (transparentShadows) n.push_back("transparent_shadows");
    if (shaderShadows) n.push_back("shader_shadows");
    if (shadowRays) n.push_back("shadow_rays");
    if (volumeShadows) n.push_back("volume_shadows");
    if (specialisedLights) n.push_back("specialised_lights");
    if (lightCoefficients) n.push_back("light_coefficients");
    if (trace) n.push_back("trace");
    if (sampledTrace) n.push_back("sampled_trace");
    if (visibilityRays) n.push_back("occlusion");
    if (aovs) n.push_back("aovs");
    if (shaderAovFloats > 0) n.push_back("shader_aovs");
    if (rayAovFloats() > 0) n.push_back("ray_aovs");
    if (sobol) n.push_back("sobol_sampler");
    if (treelets) n.push_back("treelets");
    if (bvhWidth == 8) n.push_back("bvh8");
    if (bvhWidth == 16) n.push_back("bvh16");
    if (shadowPackets) n.push_back("shadow_packets");
    if (closestPackets) n.push_back("closest_packets");
    if (depthOfField) n.push_back("depth_of_field");
    if (signedFilter) n.push_back("signed_filter");
    if (!colors.isRgb()) n.push_back("color_samples_" + std::to_string(colors.n));
    if (primvars & RT_PRIMVAR_ST) n.push_back("vertex_st");
    if (primvars & RT_PRIMVAR_CS) n.push_back("vertex_Cs");
    if (primvars & RT_PRIMVAR_OS) n.push_back("vertex_Os");
    return n;
}

// Work-items for `rays` rays, RT_PACKET_RAYS each when in packets.
static size_t items(size_t rays, bool packets) {
    return packets ? (rays + RT_PACKET_RAYS - 1) / RT_PACKET_RAYS : rays;
}

size_t Features::shadowItems(size_t rays, size_t lights) const {
    return items(rays, shadowPackets) * lights;
}

size_t Features::closestItems(size_t rays) const { return items(rays, closestPackets); }

void chooseTraversal(Features& f, int bvhWidth, bool shadowPackets, bool closestPackets,
                     bool cpuDevice, unsigned floatLanes) {
    // Node width by measurement (bench_trace --wide8 --wide16): on a CPU device eight,
    // where PoCL tests a node's boxes with AVX, and sixteen where its vectors are sixteen
    // floats wide (AVX-512: 1.01-1.07x the eight-wide rate on every ray kind on a Zen 5,
    // session 38; a Zen 4, which splits 512-bit operations, measured 0.94-0.99 in session
    // 18, before the SAH collapse: `--bvh-width 8` there until measured again; on a Zen 3
    // with AVX2, session 40, sixteen took 1.06-1.09x the SPD scenes' intersect_closest
    // time and 0.89x the bunny's bounces': eight there);
    // four elsewhere, where no figures say otherwise. The treelets are cut from the same
    // tree (eight-wide treelets: 1.08-1.37x the four-wide ones' rate at budgets of 4 KiB to
    // the whole tree).
    f.bvhWidth = bvhWidth == 4 || bvhWidth == 8 || bvhWidth == 16 ? bvhWidth
                 : !cpuDevice                                     ? 4
                 : floatLanes >= 16                               ? 16
                                                                  : 8;
    // Packets of eight rays a work-item in triangle scenes (bench_trace: primary rays
    // 1.3-1.4x, shadow rays 1.3-1.4x the one-ray kernels' rate; benchmarks/packets.sh:
    // intersect_closest 0.54-0.91 of its time, intersect_shadow 0.75 on the bunny, 0.92-1.06
    // on the small SPD scenes). With quadrics, tested a lane at a time, shadow packets cost
    // balls 1.1-1.2x: none there.
    const bool packetsFit = f.bvhWidth >= 8 && !f.treelets && !f.quadrics && !f.instances &&
                            !f.motion && !f.procedurals;
    f.shadowPackets =
        shadowPackets && f.shadowRays && packetsFit && !f.transparentShadows;
    f.closestPackets = closestPackets && packetsFit;
}

std::string buildOptions(const Features& f) {
    // No fast-math: watertight intersection and robust offsets rely on IEEE rounding.
    std::string o = "-cl-std=CL1.2 -DRT_SPAWN_SLOTS=" + std::to_string(f.spawnSlots()) +
                    " -DRSL_MAX_TRACE=" + std::to_string(std::max(1, f.traceSlots)) +
                    " -DRT_MAX_SPECULAR_DEPTH=" + std::to_string(f.maxSpecularDepth) +
                    " -DRSL_MAX_LOOP_ITERATIONS=" + std::to_string(kShaderLoopPasses);
    if (f.smoothNormals) o += " -DRT_HAS_SMOOTH_NORMALS";
    if (f.transparency) o += " -DRT_HAS_TRANSPARENCY";
    if (f.transparentShadows) o += " -DRT_HAS_TRANSPARENT_SHADOWS";
    if (f.shaderShadows) o += " -DRT_SHADER_SHADOWS";
    if (f.transparency || f.transparentShadows)
        o += " -DRT_MAX_TRANSPARENT_DEPTH=" + std::to_string(f.maxTransparentDepth) + "u";
    if (f.shadowRays) o += " -DRT_HAS_SHADOW_RAYS";
    if (f.sceneScale < 1.0f) {
        char buf[48];
        std::snprintf(buf, sizeof buf, " -DRT_SCENE_SCALE=%.9ef", double(f.sceneScale));
        o += buf;
    }
    if (f.aovs) o += " -DRT_HAS_AOVS";
    if (f.shaderAovFloats > 0) o += " -DRT_SHADER_AOVS=" + std::to_string(f.shaderAovFloats);
    if (f.rayAovFloats() > 0) o += " -DRT_RAY_AOVS -DRD_AOV_CHANNELS=" + f.aovChannels;
    if (f.depthOfField) o += " -DRT_HAS_DEPTH_OF_FIELD";
    if (f.signedFilter) o += " -DRT_SIGNED_FILTER";
    if (!f.colors.isRgb()) {
        auto matrix = [](const std::vector<float>& m) {
            std::string v;
            char buf[32];
            for (float x : m) {
                std::snprintf(buf, sizeof buf, "%s%.9ef", v.empty() ? "" : ",", double(x));
                v += buf;
            }
            return v;
        };
        if (f.colors.lanes() > 4)
            o += " -DRSL_COLOR_LANES=" + std::to_string(f.colors.lanes());
        o += " -DRSL_COLOR_SAMPLES=" + std::to_string(f.colors.n) + " -DRSL_NRGB=" +
             matrix(f.colors.toRgb) + " -DRSL_RGBN=" + matrix(f.colors.fromRgb);
    }
    if (f.quadrics) o += " -DRT_HAS_QUADRICS";
    if (f.quadricPrimvars) o += " -DRT_HAS_QUADRIC_PRIMVARS";
    if (f.motion) o += " -DRT_HAS_MOTION";
    if (f.instances) o += " -DRT_HAS_INSTANCES";
    if (f.atmosphere) o += " -DRT_HAS_ATMOSPHERE";
    if (f.interior) o += " -DRT_HAS_INTERIOR";
    if (f.exterior) o += " -DRT_HAS_EXTERIOR";
    if (f.volumeShadows) o += " -DRT_VOLUME_SHADOWS -DRSL_VOLUME_SHADOWS";
    if (f.materialDepths) o += " -DRT_MATERIAL_DEPTHS";
    if (f.maxDiffuseDepth >= 0)
        o += " -DRT_MAX_DIFFUSE_DEPTH=" + std::to_string(f.maxDiffuseDepth);
    if (f.clipPlanes > 0) o += " -DRT_CLIP_PLANES=" + std::to_string(f.clipPlanes);
    if (f.oneSided) o += " -DRT_HAS_ONE_SIDED";
    if (f.invisible) o += " -DRT_HAS_INVISIBLE";
    if (f.derivatives) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " -DRT_HAS_DERIVATIVES -DRT_PIXEL_SPREAD=%.9ef",
                      double(f.pixelSpread));
        o += buf;
    }
    if (f.displacement) o += " -DRT_HAS_DISPLACEMENT";
    if (f.textures) o += " -DRT_HAS_TEXTURES";
    if (f.procedurals) o += " -DRT_HAS_PROCEDURALS";
    if (f.pointParams > 0) o += " -DRSL_MAX_PARAM_PRIMVARS=" + std::to_string(f.pointParams);
    if (f.pointParams > 0 && f.displacementPointParams)
        o += " -DRSL_DISPLACEMENT_PRIMVARS";
    if (f.treelets) o += f.int64Min ? " -DRT_HAS_TREELETS -DRT_HAS_INT64_MIN" : " -DRT_HAS_TREELETS";
    if (f.bvhWidth == 8) o += " -DRT_BVH8";
    if (f.bvhWidth == 16) o += " -DRT_BVH16";
    if (f.shadowPackets) o += " -DRT_SHADOW_PACKETS";
    if (f.closestPackets) o += " -DRT_CLOSEST_PACKETS";
    if (f.sampledTrace) o += " -DRT_INCOHERENT_TRACE";
    if (f.visibilityRays) o += " -DRT_HAS_VISIBILITY_RAYS";
    if (f.specialisedLights) o += " -DRD_SPECIALISED_LIGHTS";
    if (f.trace && f.rouletteDepth > 0)
        o += " -DRT_ROULETTE_DEPTH=" + std::to_string(f.rouletteDepth) + "u";
    if (f.seed != 0) o += " -DRT_SEED=" + std::to_string(f.seed) + "u";
    if (f.sobol) o += " -DRT_SAMPLER_SOBOL";
    if (f.primvars & RT_PRIMVAR_ST) o += " -DRT_HAS_VERTEX_ST";
    if (f.primvars & RT_PRIMVAR_CS) o += " -DRT_HAS_VERTEX_CS";
    if (f.primvars & RT_PRIMVAR_OS) o += " -DRT_HAS_VERTEX_OS";
    return o;
}

}  // namespace rd
