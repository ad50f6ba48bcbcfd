// collapse4.h: turns the binary SAH BVH into the four-wide layout the kernels traverse
// (cl/include/bvh.h, Bvh4Node), or the eight- or sixteen-wide one (Bvh8Node, Bvh16Node). Which binary nodes
// become wide nodes, which are opened into their parent's slots and which small subtrees
// become one leaf is chosen for the least SAH cost of the wide tree (Ylitie et al. 2017);
// primitive order is the binary tree's, and a leaf's primitives are a binary subtree's.
#pragma once
#include <vector>

#include "cl/include/quadric.h"
#include "cl/include/scene_types.h"
#include "sah_builder.h"

namespace rd {

// nodes[0] is the root. An empty tree gives one node with four unused slots. A leaf
// child refers to blocks (of triangles, or of objects): child = first block, count =
// number of blocks.
template <class Node>
struct BvhWide {
    std::vector<Node> nodes;
    std::vector<Triangle4> blocks;
};
using Bvh4 = BvhWide<Bvh4Node>;
using Bvh8 = BvhWide<Bvh8Node>;
using Bvh16 = BvhWide<Bvh16Node>;

// What the binary tree was built over when it is not just `tris`: ids[i] is primitive
// i's triangle index, or RT_OBJECT_BIT | its quadric index (cl/include/quadric.h), and
// bounds[i] its box.
struct BvhPrimitives {
    std::vector<uint32_t> ids;
    std::vector<Aabb> bounds;
};

// A tree of at least this many primitives is laid out on the host's cores: its top
// levels first, then each subtree of at most a 16th of them, in a fixed order (the same
// layout for any number of threads; another order of nodes and blocks than one depth-
// first walk, the same tree).
constexpr size_t kParallelCollapse = size_t(1) << 16;

// Without `prims`, the tree was built over `tris` themselves.
Bvh4 collapseToBvh4(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims = nullptr,
                    size_t parallelFrom = kParallelCollapse);
// The same collapse to eight children per node (Bvh8Node).
Bvh8 collapseToBvh8(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims = nullptr,
                    size_t parallelFrom = kParallelCollapse);
// And to sixteen (Bvh16Node).
Bvh16 collapseToBvh16(const Bvh& bvh, const std::vector<Triangle>& tris,
                      const BvhPrimitives* prims = nullptr,
                      size_t parallelFrom = kParallelCollapse);

// Appends `part`'s nodes and blocks to `into`, its children's indices moved with them,
// and returns where its root landed: appended, or with `rootAt` >= 0 in place of
// into.nodes[rootAt] (a node set aside for it, which some parent already refers to).
template <class Node>
int appendWideTree(BvhWide<Node>& into, const BvhWide<Node>& part, int rootAt = -1) {
    constexpr int W = sizeof(Node::count) / sizeof(Node::count[0]);
    const int nodeOffset = int(into.nodes.size()) - (rootAt >= 0 ? 1 : 0);
    const int blockOffset = int(into.blocks.size());
    for (size_t j = 0; j < part.nodes.size(); ++j) {
        Node n = part.nodes[j];
        for (int k = 0; k < W; ++k) {
            if (n.count[k] > 0)
                n.child[k] += blockOffset;  // a leaf: its first block
            else if (n.count[k] == 0)
                n.child[k] += nodeOffset;  // an interior child
        }
        if (j == 0 && rootAt >= 0)
            into.nodes[size_t(rootAt)] = n;
        else
            into.nodes.push_back(n);
    }
    into.blocks.insert(into.blocks.end(), part.blocks.begin(), part.blocks.end());
    return rootAt >= 0 ? rootAt : nodeOffset;
}

// The share of a wide tree's child slots in use (a node of two children in eight uses a
// quarter of what its load and box test cost).
template <class Node>
double usedSlots(const BvhWide<Node>& tree) {
    constexpr int W = sizeof(Node::count) / sizeof(Node::count[0]);
    size_t used = 0;
    for (const Node& n : tree.nodes)
        for (int k = 0; k < W; ++k) used += n.count[k] >= 0;
    return tree.nodes.empty() ? 0.0 : double(used) / double(W * tree.nodes.size());
}

}  // namespace rd
