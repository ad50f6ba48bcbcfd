// scene_bvh.h: the scene's BVH as the device traverses it: the top level over triangles,
// quadrics, CSG solids, moving triangles and instances, then one BVH per instanced
// prototype in its own object space, all in one node and block array; each instance
// record is given the root node of its prototype's tree.
#pragma once
#include <cstring>
#include <vector>

#include "bvh/collapse4.h"
#include "scene/scene.h"

namespace rd {

struct SceneBvh {
    int width = 4;  // the layout built: bvh4, bvh8 or bvh16 (four, eight or sixteen wide)
    Bvh4 bvh4;
    Bvh8 bvh8;
    Bvh16 bvh16;
    std::vector<Quadric> objects;  // scene.quadrics, instances pointing at their roots
    uint32_t droppedPrims = 0;     // primitives with unusable bounds (non-finite)
};

// Calls f with the tree of the width built (bvh4, bvh8 or bvh16).
template <class S, class F>
decltype(auto) withTree(S& bvh, F&& f) {
    if (bvh.width == 16) return f(bvh.bvh16);
    if (bvh.width == 8) return f(bvh.bvh8);
    return f(bvh.bvh4);
}

// How the renderer builds its trees (the benchmarks build with the same): SAH counting
// primitives in the kernels' blocks of four.
BvhBuildSettings sceneBvhSettings();

// width 4, 8 or 16: the layout the resident traversal reads (RT_BVH8, RT_BVH16).
SceneBvh buildSceneBvh(const Scene& scene, int width = 4);

// The nodes as the device buffer holds them: raw node bytes in 128-byte units (an
// eight-wide node takes two, a sixteen-wide one four), so one buffer type serves every
// width.
std::vector<Bvh4Node> deviceNodes(const SceneBvh& bvh);
// The same for a tree of any width.
template <class Node>
std::vector<Bvh4Node> inNodeUnits(const std::vector<Node>& nodes) {
    static_assert(sizeof(Node) % sizeof(Bvh4Node) == 0, "node units");
    std::vector<Bvh4Node> out(nodes.size() * (sizeof(Node) / sizeof(Bvh4Node)));
    if (!out.empty()) std::memcpy(out.data(), nodes.data(), out.size() * sizeof(Bvh4Node));
    return out;
}
// The built layout's node count and node bytes.
size_t nodeCount(const SceneBvh& bvh);
size_t nodeBytes(const SceneBvh& bvh);
const std::vector<Triangle4>& deviceBlocks(const SceneBvh& bvh);

}  // namespace rd
