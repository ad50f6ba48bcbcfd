// collapse4.h: turns the binary SAH BVH into the four-wide layout the kernels traverse
// (cl/include/bvh.h, Bvh4Node): each wide node takes a binary node's children and keeps
// opening its largest interior child until it has four (the usual BVH2 -> BVH4 collapse;
// leaves and primitive order are those of the binary tree).
#pragma once
#include <vector>

#include "cl/include/scene_types.h"
#include "sah_builder.h"

namespace rd {

// nodes[0] is the root. An empty tree gives one node with four unused slots. A leaf
// child refers to triangle blocks: child = first block, count = number of blocks.
struct Bvh4 {
    std::vector<Bvh4Node> nodes;
    std::vector<Triangle4> blocks;
};

// `tris` are the primitives the binary tree was built over.
Bvh4 collapseToBvh4(const Bvh& bvh, const std::vector<Triangle>& tris);

}  // namespace rd
