// renderer.h: the render loop of DESIGN.md section 3 for one Scene on one device: upload
// the scene and its BVH, then for each tile refill the pool with eye samples, trace and
// shade in rounds, trace shadow rays, and retire whole samples to the film.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "film/film.h"
#include "ocl/context.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "features.h"
#include "scene/scene.h"

namespace rd {

struct RenderSettings {
    size_t poolCapacity = size_t(1) << 18;  // rays in flight per batch
};

struct RenderStats {
    double elapsedSec = 0;
    double sceneSetupMs = 0, bvhBuildMs = 0;
    uint64_t eyeRays = 0, continuationRays = 0, shadowRays = 0;
    uint64_t triangles = 0, bvhNodes = 0, droppedPrims = 0;
    uint64_t nonfiniteSamples = 0;
    size_t poolCapacity = 0;
    int tiles = 0;
    Features features;
    ProgramBuildInfo program;
    std::string device, platform;
    std::map<std::string, KernelStats> kernels;
};

class Renderer {
public:
    Renderer(const ClContext& ctx, const RenderSettings& settings);
    // Renders `scene` into `film` (sized from the scene's Format) and returns the figures
    // for --stats. Throws on OpenCL errors.
    RenderStats render(const Scene& scene, Film& film);

private:
    const ClContext& m_ctx;
    RenderSettings m_settings;
};

}  // namespace rd
