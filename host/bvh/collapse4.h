// collapse4.h: turns the binary SAH BVH into the four-wide layout the kernels traverse
// (cl/include/bvh.h, Bvh4Node): each wide node takes a binary node's children and keeps
// opening its largest interior child until it has four (the usual BVH2 -> BVH4 collapse;
// leaves and primitive order are those of the binary tree).
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

// What the binary tree was built over when it is not just `tris`: ids[i] is primitive
// i's triangle index, or RT_OBJECT_BIT | its quadric index (cl/include/quadric.h), and
// bounds[i] its box.
struct BvhPrimitives {
    std::vector<uint32_t> ids;
    std::vector<Aabb> bounds;
};

// Without `prims`, the tree was built over `tris` themselves.
Bvh4 collapseToBvh4(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims = nullptr);
// The same collapse to eight children per node (Bvh8Node).
Bvh8 collapseToBvh8(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims = nullptr);

}  // namespace rd
