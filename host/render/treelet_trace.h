// treelet_trace.h: the trace stage as treelet-streamed traversal (DESIGN.md sections 1
// and 3, issue 5): the BVH cut into treelets under a byte budget (bvh/treelets.h); each
// round intersects the queued (ray, treelet) pairs, keeps the closest hit by an atomic
// min on (t, primitive), queues rays into the child treelets they enter and counts each
// treelet's queue; the host reads the counts (one download per round), groups the queue
// by treelet and, when the scene is not resident, uploads only the treelets that have
// rays into a fixed-size device cache, in as many chunks as the cache needs. The render
// loop calls closest() and shadow() instead of intersect_closest and intersect_shadow
// when a treelet budget is set; images do not depend on the budget.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "bvh/treelets.h"
#include "cl/include/ray.h"
#include "cl/include/scene_types.h"
#include "features.h"
#include "ocl/kernel.h"

namespace rd {

// Per round number (0 = the root round), summed over every trace of the render.
struct TreeletRoundStats {
    uint64_t pairs = 0;            // (ray, treelet) pairs intersected
    uint64_t treeletsWithRays = 0; // treelets whose queue was not empty (the hit flags)
    uint64_t uploads = 0;          // treelets uploaded into the cache for the round
};

struct TreeletStats {
    bool used = false;       // the render traced through treelets
    bool streamed = false;   // not resident: a cache of `cacheSlots` treelets
    std::string why;         // why not, when a budget was asked for and not used
    size_t budgetBytes = 0, treelets = 0, treeletBytes = 0, cacheSlots = 0, slotBytes = 0;
    uint64_t traces = 0, rounds = 0, pairs = 0, launches = 0;
    uint64_t uploads = 0, uploadedBytes = 0;
    uint64_t reruns = 0;  // rounds run again after their queue overflowed and grew
    std::vector<TreeletRoundStats> byRound;
};

// What object blocks need besides the BVH (used with RT_HAS_QUADRICS: quadric records,
// CSG lists, triangles, motion keys, and each ray's sample for its shutter time; any
// buffers otherwise). The triangles are also what treelet_resolve reads u, v from.
struct TraceScene {
    const DeviceBuffer<Quadric>& quadrics;
    const DeviceBuffer<uint32_t>& csg;
    const DeviceBuffer<Triangle>& triangles;
    const DeviceBuffer<rt_float4>& quadricMotion;
    const DeviceBuffer<Triangle>& trianglesEnd;
    const DeviceBuffer<uint32_t>& raySample;  // of the closest-hit rays (shadow ray i: i / lights)
    const DeviceBuffer<float>& sampleTime;
};

// What shadow rays read of the surfaces they pass in scenes where some let light through
// (RT_HAS_TRANSPARENT_SHADOWS): they walk them a layer a closest-hit trace, as
// intersect_shadow does, and dim their weights and AOV parts by each one's transmittance.
struct ShadowSurfaces {
    const DeviceBuffer<TriangleAttr>& attrs;
    const DeviceBuffer<Material>& materials;
    const DeviceBuffer<float>& materialChannels;
    DeviceBuffer<float>& shadowAov;  // RT_SHADER_AOVS: the parts each shadow ray carries
    int maxTransparentDepth;         // layers after the first
    // RT_SHADER_SHADOWS: each sample's rays in flight (a ray handed to the pool counts)
    DeviceBuffer<uint32_t>& slotRays;
};

// Decides whether the scene traces through treelets with this budget (0: no) and sets
// f.treelets and f.int64Min for buildOptions(). The treelet kernels handle triangles,
// quadrics, CSG solids and motion; a scene with instances or deferred archives (whose
// prototype trees and bounds the cut does not cover), or a device without
// cl_khr_int64_base_atomics, keeps the resident traversal (`why` says which).
void configureTreelets(Features& f, const ClContext& ctx, size_t budgetBytes,
                       TreeletStats& stats);

class TreeletTracer {
public:
    // `bvh`: the four-, eight- or sixteen-wide tree, as the program was built (RT_BVH8,
    // RT_BVH16);
    // `sceneMemoryBytes`: device bytes the BVH may take (0 or at least the whole cut:
    // every treelet resident); `rays`: the most rays closest() is given at once.
    template <class Node>
    TreeletTracer(const ClContext& ctx, cl_program program, Profiler& prof,
                  const BvhWide<Node>& bvh, size_t budgetBytes, size_t sceneMemoryBytes,
                  size_t rays, TreeletStats& stats);
    ~TreeletTracer();
    // intersect_closest's work: hits[i] for the first n rays that are alive.
    void closest(cl_uint n, const DeviceBuffer<rt_float4>& origin,
                 const DeviceBuffer<rt_float4>& direction, const DeviceBuffer<RayState>& state,
                 DeviceBuffer<RayHit>& hits, const TraceScene& scene);
    // intersect_shadow's work: weight[i] zeroed for the occluded ones (their states left
    // as they were), or dimmed by the surfaces passed when `surfaces` is given; `lights`
    // shadow rays per shaded ray (for their time). With RT_SHADER_SHADOWS a ray that meets
    // a surface whose shader says what gets through is handed to the pool there, as
    // intersect_shadow hands it (its state, origin's t and weight rewritten).
    void shadow(cl_uint n, DeviceBuffer<rt_float4>& origin,
                const DeviceBuffer<rt_float4>& direction, DeviceBuffer<RayState>& state,
                DeviceBuffer<float>& weight, const TraceScene& scene, cl_uint lights,
                const ShadowSurfaces* surfaces = nullptr);

    // Rays traced so far (the first rounds' active counters, read without resetting), and
    // the per-kernel active counts handed to the profiler for --stats.
    uint64_t peekRays() const;
    void collectActive();

private:
    struct Impl;
    std::unique_ptr<Impl> m;
};

}  // namespace rd
