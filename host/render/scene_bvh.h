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
    int width = 4;  // the layout built: bvh4 (four-wide) or bvh8 (eight-wide)
    Bvh4 bvh4;
    Bvh8 bvh8;
    std::vector<Quadric> objects;  // scene.quadrics, instances pointing at their roots
    uint32_t droppedPrims = 0;     // primitives with unusable bounds (non-finite)
};

// How the renderer builds its trees (the benchmarks build with the same): SAH counting
// primitives in the kernels' blocks of four.
BvhBuildSettings sceneBvhSettings();

// width 4 or 8: the layout the resident traversal reads (RT_BVH8 for eight).
SceneBvh buildSceneBvh(const Scene& scene, int width = 4);

// The nodes as the device buffer holds them: raw node bytes in 128-byte units (an
// eight-wide node takes two), so one buffer type serves both widths.
std::vector<Bvh4Node> deviceNodes(const SceneBvh& bvh);
const std::vector<Triangle4>& deviceBlocks(const SceneBvh& bvh);

}  // namespace rd
