// treelets.h: cuts the four-, eight- or sixteen-wide BVH (collapse4.h) into treelets under a byte budget, the
// unit the treelet-streamed traversal queues rays into and uploads (DESIGN.md sections 1
// and 3; cl/include/treelet.h for the device layout). A treelet's bytes are its nodes
// plus the leaf blocks they reference. The cut works bottom up, cutting off the largest
// child subtree while a node's subtree is over budget (treelets.cpp says why not top
// down); treelets are numbered breadth first, so treelet 0 holds the root and a
// treelet's parent always has a smaller index.
#pragma once
#include <cstddef>
#include <vector>

#include "cl/include/treelet.h"
#include "collapse4.h"

namespace rd {

struct TreeletRange {
    uint32_t nodeFirst = 0, nodeCount = 0;    // in the cut's nodes
    uint32_t blockFirst = 0, blockCount = 0;  // in the cut's blocks
    uint32_t nodeBytes = sizeof(Bvh4Node);    // of one node: the cut's width
    size_t bytes() const {
        return size_t(nodeCount) * nodeBytes + size_t(blockCount) * sizeof(Triangle4);
    }
};

// A cut of a four-, eight- or sixteen-wide (Bvh4Node, Bvh8Node, Bvh16Node) tree.
template <class Node>
struct TreeletsOf {
    // Every treelet's nodes, then the next's; child indices local to the treelet (a
    // treelet's root is its first node), links to other treelets as RT_TREELET_LINK.
    std::vector<Node> nodes;
    std::vector<Triangle4> blocks;
    std::vector<TreeletRange> ranges;
    std::vector<uint32_t> treeletOfNode;  // the input tree's node i went to this treelet
    uint32_t maxNodes = 0, maxBlocks = 0;  // of any one treelet (the cache slot's size)
    size_t count() const { return ranges.size(); }
    size_t bytes() const {
        return nodes.size() * sizeof(Node) + blocks.size() * sizeof(Triangle4);
    }
    // The resident layout: treelet i where the cut put it.
    std::vector<TreeletRef> residentRefs() const;
};
using Treelets = TreeletsOf<Bvh4Node>;
using Treelets8 = TreeletsOf<Bvh8Node>;
using Treelets16 = TreeletsOf<Bvh16Node>;

// Bytes of node i of `bvh` with the blocks its leaf children reference.
template <class Node>
size_t treeletNodeBytes(const BvhWide<Node>& bvh, size_t node);

// Cuts `bvh` into treelets of at most `budgetBytes` each; a node that alone is larger
// than the budget is a treelet by itself. A budget of 0 means one treelet.
template <class Node>
TreeletsOf<Node> cutTreelets(const BvhWide<Node>& bvh, size_t budgetBytes);

}  // namespace rd
