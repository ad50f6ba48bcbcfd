// ray_pool.h: the device side of the streaming core. The ray pool (structure of arrays,
// a fixed capacity: the rays traced in one round), the rays the shade stage spawns (slot
// r * spawn + k: ray r's k-th), the spill stack those that do not fit wait on, the
// shadow rays (light_count slots per ray), the sample slots (each sample's running
// total, its pixel and index, its count of rays in flight) and the pixel-job ring.
// Buffers a scene does not need (AOVs, motion times, instance ids) keep one element.
#pragma once
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cl/include/film.h"
#include "cl/include/ray.h"
#include "ocl/buffer.h"
#include "ocl/device.h"
#include "ocl/kernel.h"

namespace rd {

struct RayPool {
    RayPool(const ClContext& ctx, size_t capacity, size_t spawn, uint32_t shadowLights,
            size_t slots, bool aovs, bool motion, bool instances, size_t shaderKeys,
            size_t weightFloats, size_t shaderAovFloats = 0, size_t rayAovFloats = 0,
            bool shadowHandoffs = false)
        : weightFloats(weightFloats),
          rayAovFloats(rayAovFloats),
          origin(ctx, capacity),
          direction(ctx, capacity),
          weight(ctx, capacity * weightFloats),
          state(ctx, capacity),
          sample(ctx, capacity),
          hits(ctx, capacity),
          hitInstance(ctx, instances ? capacity : 0),
          key(ctx, capacity),
          keyCount(ctx, 2 * shaderKeys),
          keyCursor(ctx, shaderKeys),
          sorted(ctx, capacity),
          nextOrigin(ctx, capacity * spawn),
          nextDirection(ctx, capacity * spawn),
          nextWeight(ctx, capacity * spawn * weightFloats),
          nextState(ctx, capacity * spawn),
          nextSample(ctx, capacity * spawn),
          spawnMask(ctx, capacity),
          groupLive(ctx, capacity / RT_COMPACT_GROUP + 1),
          spillOrigin(ctx, spillCapacity(capacity, spawn, shadowHandoffs)),
          spillDirection(ctx, spillCapacity(capacity, spawn, shadowHandoffs)),
          spillWeight(ctx, spillCapacity(capacity, spawn, shadowHandoffs) * weightFloats),
          spillState(ctx, spillCapacity(capacity, spawn, shadowHandoffs)),
          spillSample(ctx, spillCapacity(capacity, spawn, shadowHandoffs)),
          shOrigin(ctx, capacity * shadowLights),
          shDirection(ctx, capacity * shadowLights),
          shWeight(ctx, capacity * shadowLights * weightFloats),
          shState(ctx, capacity * shadowLights),
          newSample(ctx, 2 * capacity),
          refillEnds(ctx, capacity),
          refillFit(ctx, 3),
          totals(ctx, slots),
          samplePixel(ctx, slots),
          sampleIndex(ctx, slots),
          sampleTime(ctx, motion ? slots : 0),
          aov(ctx, aovs ? slots : 0),
          aovValues(ctx, slots * shaderAovFloats),
          shAov(ctx, capacity * shadowLights * shaderAovFloats),
          aovw(ctx, capacity * rayAovFloats),
          nextAovw(ctx, capacity * spawn * rayAovFloats),
          spillAovw(ctx, spillCapacity(capacity, spawn, shadowHandoffs) * rayAovFloats),
          slotRays(ctx, slots),
          slotAbort(ctx, slots),
          jobs(ctx, slots),
          progress(ctx, 6) {
        shState.fillZero();
        spawnMask.fillZero();
        keyCount.fillZero();
        keyCursor.fillZero();
        progress.upload({~0u, 0u, 0u, ~0u, 0u, 0u});
        slotRays.fillZero();
        slotAbort.fillZero();
    }
    // Sample slots per ray of capacity. Jobs retire in any order but free their slots
    // oldest first, so a sample whose ray tree runs many rounds holds back the slots
    // after it; with two slots a ray the SPD gears at 9 samples a pixel filled the ring
    // and traced rounds of 3-30% of the pool (pool fill 0.47; four: 0.57).
    static constexpr size_t kSlotsPerRay = 4;
    // Device bytes per ray of capacity, for sizing the pool to a memory budget.
    static size_t bytesPerRay(size_t spawn, uint32_t shadowLights,
                              size_t weightFloats = 4, size_t shaderAovFloats = 0,
                              size_t rayAovFloats = 0, bool shadowHandoffs = false) {
        const size_t spill = spillCapacity(1, spawn, shadowHandoffs);
        const size_t weights = 1 + spawn + spill + shadowLights;
        return 144 + 2 * 100 + spawn * 72 + spill * 68 +
               size_t(shadowLights) * 64 + kSlotsPerRay * 56 +
               weights * weightFloats * 4 -
               weights * 16 +  // (the figures above count four floats a weight)
               (kSlotsPerRay + shadowLights) * shaderAovFloats * 4 +
               (1 + spawn + spill) * rayAovFloats * 4;
    }
    // Rays of one round: `wanted`, or (0) enough to keep every compute unit busy (16k rays
    // each), within a memory budget of an eighth of the device's memory (64-512 MiB).
    static size_t capacityFor(size_t wanted, const DeviceInfo& device, size_t spawn,
                              uint32_t shadowLights, size_t weightFloats,
                              size_t shaderAovFloats = 0, size_t rayAovFloats = 0,
                              bool shadowHandoffs = false) {
        if (wanted == 0)
            wanted = std::clamp<size_t>(size_t(device.computeUnits) << 14, size_t(1) << 14,
                                        size_t(1) << 20);
        const size_t memoryBudget = std::clamp<size_t>(device.globalMemBytes / 8,
                                                       size_t(64) << 20, size_t(512) << 20);
        return std::clamp<size_t>(
            std::min(wanted, memoryBudget / bytesPerRay(spawn, shadowLights, weightFloats,
                                                        shaderAovFloats, rayAovFloats,
                                                        shadowHandoffs)),
            64, std::max<size_t>(64, wanted));
    }
    // Floats of a ray's weight (cl/include/ray.h rt_weight): 2 under ColorSamples 1, 4 up
    // to three channels, else the scene's colour vector (8 or 16).
    static size_t weightFloatsOf(int colorChannels) {
        return colorChannels == 1   ? 2
               : colorChannels <= 3 ? 4
               : colorChannels <= 7 ? 8
                                    : 16;
    }
    const size_t weightFloats;
    const size_t rayAovFloats;  // a ray's AOV weights (ray_aovs.clh), 0 when none
    // Only a scene whose shaders trace, or whose shadow rays are handed over to the pool
    // (RT_SHADER_SHADOWS: one a light), can spawn more rays than it traced: the rest
    // (continuations through Opacity < 1 at most one a ray) never need the stack. Ray
    // trees outgrow the pool over rounds, not in one, so the stack is as deep as a pool
    // of hits spawning the ABI's most (1 + RSL_MAX_TRACE, 9) whatever the scene's own
    // slots (sized by its shaders' trace() bound, it lost the rays of 127-ray trees
    // through a pool of 64: Numerics.RayTreesSpillAndTheImageDoesNotDependOnThePool).
    static constexpr size_t kSpillPerRay = 9;
    static size_t spillCapacity(size_t capacity, size_t spawn, bool shadowHandoffs) {
        return spawn > 1 || shadowHandoffs ? capacity * kSpillPerRay : 0;
    }
    // the round's rays
    DeviceBuffer<rt_float4> origin, direction;
    DeviceBuffer<float> weight;  // weightFloats a ray
    DeviceBuffer<RayState> state;
    DeviceBuffer<uint32_t> sample;  // the ray's sample slot
    DeviceBuffer<RayHit> hits;
    DeviceBuffer<uint32_t> hitInstance;                // instance of each closest hit
    // the sort by shader (keyCount: two halves, by round parity)
    DeviceBuffer<uint32_t> key, keyCount, keyCursor, sorted;
    // what the shade stage spawns, compacted into the next round (and the spill stack)
    DeviceBuffer<rt_float4> nextOrigin, nextDirection;
    DeviceBuffer<float> nextWeight;
    DeviceBuffer<RayState> nextState;
    DeviceBuffer<uint32_t> nextSample;
    DeviceBuffer<uint32_t> spawnMask;  // per traced ray: bit k set when slot k was filled
    DeviceBuffer<uint32_t> groupLive;  // live spawned rays per group of traced rays
    DeviceBuffer<rt_float4> spillOrigin, spillDirection;
    DeviceBuffer<float> spillWeight;
    DeviceBuffer<RayState> spillState;
    DeviceBuffer<uint32_t> spillSample;
    // shadow rays
    DeviceBuffer<rt_float4> shOrigin, shDirection;
    DeviceBuffer<float> shWeight;
    DeviceBuffer<RayState> shState;
    // the refill: the new samples' (pixel, index) pairs; for a refill queued before the
    // round's wait, the staged jobs' ends (samples in jobs 0..j) and what fit_refill
    // found fits: jobs, samples, and the rays the round spawned
    DeviceBuffer<uint32_t> newSample, refillEnds, refillFit;
    // sample slots and pixel jobs
    DeviceBuffer<SampleTotal> totals;
    DeviceBuffer<uint32_t> samplePixel, sampleIndex;
    DeviceBuffer<float> sampleTime;  // motion blur: each sample's time
    DeviceBuffer<SampleAov> aov;
    // the shaders' AOVs (RT_SHADER_AOVS floats): a sample slot's, and the parts of its
    // first surface's that a shadow ray carries (the light's, added if it gets through)
    DeviceBuffer<float> aovValues, shAov;
    // AOV weights (rayAovFloats a ray) of the pool's rays, the spawn slots, the spill
    // stack
    DeviceBuffer<float> aovw, nextAovw, spillAovw;
    DeviceBuffer<uint32_t> slotRays, slotAbort;
    DeviceBuffer<PixelJob> jobs;
    // retire_samples, two halves by launch parity: oldest job in flight, aborted, NaN/Inf
    DeviceBuffer<uint32_t> progress;
};

struct RenderKernels {
    // `p`: the trace program, `shading`: the one with the shade kernels (render_programs.h)
    RenderKernels(const ClContext& ctx, cl_program p, cl_program shading, Profiler& prof,
                  const std::vector<std::string>& shadeKernels)
        : generateEye(ctx, p, "generate_eye", prof),
          intersectClosest(ctx, p, "intersect_closest", prof),
          classify(ctx, p, "classify_hits", prof),
          scatter(ctx, p, "scatter_by_shader", prof),
          intersectShadow(ctx, p, "intersect_shadow", prof),
          closeRound(ctx, p, "close_round", prof),
          compactScatter(ctx, p, "compact_scatter", prof), fitRefill(ctx, p, "fit_refill", prof),
          retire(ctx, p, "retire_samples", prof) {
        for (const std::string& name : shadeKernels)
            shade.push_back(std::make_unique<Kernel>(ctx, shading, name, prof));
    }
    Kernel generateEye, intersectClosest, classify, scatter, intersectShadow, closeRound,
        compactScatter, fitRefill, retire;
    std::vector<std::unique_ptr<Kernel>> shade;  // one per compiled surface shader
    std::vector<Kernel*> all() {
        std::vector<Kernel*> v{&generateEye, &intersectClosest, &classify, &scatter,
                               &intersectShadow, &closeRound, &compactScatter, &retire};
        for (auto& s : shade) v.push_back(s.get());
        return v;
    }
};

}  // namespace rd
