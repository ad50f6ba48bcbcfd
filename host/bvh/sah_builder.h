// sah_builder.h: builds the flattened binary BVH (BvhNode, cl/include/bvh.h) that the
// OpenCL kernels traverse, with a binned surface-area-heuristic builder (Wald 2007).
#pragma once

#include <cstdint>
#include <vector>

#include "cl/include/bvh.h"
#include "host/bvh/aabb.h"

namespace rd {

struct BvhBuildSettings {
    int binCount = 16;    // SAH bins per axis, clamped to [2, 256]
    int maxLeafSize = 4;  // nodes with at most this many primitives always become leaves
    float traversalCost = 1.0f;
    float intersectionCost = 1.0f;
    // Primitives are intersected this many at a time (the kernels' four-triangle blocks):
    // SAH counts a set of n as ceil(n / blockSize) intersections, so leaves fill blocks.
    int blockSize = 1;
    // A tree of at least parallelPrims primitives is built on `threads` threads (0: the
    // host's cores) below its top levels; the tree and its layout are the same for any
    // number of threads.
    size_t parallelPrims = 65536;
    unsigned threads = 0;
};

// The largest leaf the builder emits when maxLeafSize is below it: a node of up to this
// many primitives becomes a leaf when SAH says a leaf is cheaper than any split.
constexpr int kBvhMaxLeafCap = 16;

// Past this depth the builder stops using SAH and splits at the object median, so the
// tree depth is at most kBvhMedianDepth + ceil(log2(n)) + 1 whatever the input; kernels
// can size their traversal stacks from Bvh::depth.
constexpr int kBvhMedianDepth = 40;

struct Bvh {
    // nodes[0] is the root. The children of an interior node are adjacent and always
    // stored after their parent.
    std::vector<BvhNode> nodes;
    // Leaf slot -> original primitive index: a leaf covers
    // primIndices[left_or_first .. left_or_first + count).
    std::vector<uint32_t> primIndices;
    // Nodes on the longest root-to-leaf path (1 for a single leaf, also when empty).
    int depth = 0;
    // Primitives whose bounds had a NaN or infinite coordinate, or lo > hi on some axis.
    // They are never referenced by the tree.
    uint32_t droppedPrims = 0;

    // An empty tree (no valid primitives) is a single root with count 0, left_or_first 0
    // and bmin = +FLT_MAX > bmax = -FLT_MAX. count 0 reads as "interior", so traversal
    // must not descend it: check empty() on the host and skip the launch, or test
    // count == 0 && left_or_first == 0 at the root (no interior node points at itself).
    // Note a slab test using min/max of the two plane distances does NOT reject an
    // inverted box; only a sign-ordered near/far slab test does.
    bool empty() const { return primIndices.empty(); }
};

// Builds a BVH over primBounds (one box per primitive). Deterministic: the same input
// and settings give the same tree. O(n log n); a large tree's subtrees in parallel.
Bvh buildBvh(const std::vector<Aabb>& primBounds, const BvhBuildSettings& settings = {});

// The SAH cost of a built tree relative to its root's area, with the given costs: the
// quantity the builder minimises, exposed for tests and benchmarks.
double bvhSahCost(const Bvh& bvh, float traversalCost = 1.0f,
                  float intersectionCost = 1.0f);

}  // namespace rd
