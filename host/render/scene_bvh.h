// scene_bvh.h: the scene's BVH as the device traverses it: the top level over triangles,
// quadrics, CSG solids, moving triangles and instances, then one BVH per instanced
// prototype in its own object space, all in one node and block array; each instance
// record is given the root node of its prototype's tree.
#pragma once
#include <vector>

#include "bvh/collapse4.h"
#include "scene/scene.h"

namespace rd {

struct SceneBvh {
    Bvh4 bvh4;
    std::vector<Quadric> objects;  // scene.quadrics, instances pointing at their roots
    uint32_t droppedPrims = 0;     // primitives with unusable bounds (non-finite)
};

// How the renderer builds its trees (the benchmarks build with the same): SAH counting
// primitives in the kernels' blocks of four.
BvhBuildSettings sceneBvhSettings();

SceneBvh buildSceneBvh(const Scene& scene);

// Appends `part` (a tree with its own node and block indices) to `into`; returns the
// index of its root there.
int appendBvh4(Bvh4& into, const Bvh4& part);

}  // namespace rd
