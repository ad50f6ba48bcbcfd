// treelets.cpp: the bottom-up cut of a four- or eight-wide BVH into treelets, and their
// contiguous layout.
#include "treelets.h"

#include <algorithm>
#include <deque>

namespace rd {

namespace {
// A node's children (4 or 8).
template <class Node>
constexpr int kWidth = int(sizeof(Node::count) / sizeof(Node::count[0]));
}  // namespace

template <class Node>
size_t treeletNodeBytes(const BvhWide<Node>& bvh, size_t node) {
    size_t bytes = sizeof(Node);
    for (int k = 0; k < kWidth<Node>; ++k)
        if (bvh.nodes[node].count[k] > 0) bytes += size_t(bvh.nodes[node].count[k]) * sizeof(Triangle4);
    return bytes;
}

template <class Node>
std::vector<TreeletRef> TreeletsOf<Node>::residentRefs() const {
    std::vector<TreeletRef> refs(ranges.size());
    for (size_t i = 0; i < ranges.size(); ++i)
        refs[i] = {int32_t(ranges[i].nodeFirst), int32_t(ranges[i].blockFirst)};
    return refs;
}

namespace {

// Which nodes root a treelet, bottom up (collapse4 appends children after their parent,
// so reverse index order visits children first): a node's open bytes are its own plus
// its children's that were not cut off; while they exceed the budget, the child subtree
// with the most open bytes is cut off as a treelet of its own. Every treelet but the
// root's is then at least a quarter full (the cut child was the largest). A greedy
// top-down growth was tried first: the root treelet takes a wide slab of the tree and
// every node on its boundary starts a treelet, so 64 KiB gave more, smaller treelets
// than 4 KiB.
template <class Node>
std::vector<char> treeletRoots(const BvhWide<Node>& bvh, size_t budgetBytes) {
    const size_t nodeCount = bvh.nodes.size();
    std::vector<size_t> open(nodeCount, 0);
    std::vector<char> isRoot(nodeCount, 0);
    isRoot[0] = 1;
    for (size_t i = nodeCount; i-- > 0;) {
        const Node& n = bvh.nodes[i];
        open[i] = treeletNodeBytes(bvh, i);
        std::vector<uint32_t> kids;
        for (int k = 0; k < kWidth<Node>; ++k)
            if (n.count[k] == 0) {
                kids.push_back(uint32_t(n.child[k]));
                open[i] += open[size_t(n.child[k])];
            }
        // largest first; ties by index so every run cuts the same
        std::sort(kids.begin(), kids.end(), [&](uint32_t a, uint32_t b) {
            return open[a] > open[b] || (open[a] == open[b] && a < b);
        });
        for (uint32_t c : kids) {
            if (open[i] <= budgetBytes) break;
            isRoot[c] = 1;
            open[i] -= open[c];
        }
    }
    return isRoot;
}

// Each treelet's nodes: treelets numbered breadth first from the root's (a parent's
// treelet comes first), a treelet's nodes in depth-first order from its root (local node
// 0). Fills treeletOfNode.
template <class Node>
std::vector<std::vector<uint32_t>> treeletMembers(const BvhWide<Node>& bvh,
                                                  const std::vector<char>& isRoot,
                                                  std::vector<uint32_t>& treeletOfNode) {
    std::vector<std::vector<uint32_t>> members;
    std::deque<uint32_t> roots{0};
    while (!roots.empty()) {
        const uint32_t id = uint32_t(members.size());
        members.emplace_back();
        std::vector<uint32_t> stack{roots.front()};
        roots.pop_front();
        while (!stack.empty()) {
            uint32_t node = stack.back();
            stack.pop_back();
            members[id].push_back(node);
            treeletOfNode[node] = id;
            const Node& n = bvh.nodes[node];
            for (int k = kWidth<Node> - 1; k >= 0; --k) {
                if (n.count[k] != 0) continue;
                const uint32_t c = uint32_t(n.child[k]);
                if (isRoot[c])
                    roots.push_back(c);
                else
                    stack.push_back(c);
            }
        }
    }
    return members;
}

// Layout: each treelet's nodes in joining order, the blocks its leaf children reference
// right after, indices rewritten local to the treelet (a child in another treelet: that
// treelet's number, RT_TREELET_LINK).
template <class Node>
void layOutTreelets(const BvhWide<Node>& bvh,
                    const std::vector<std::vector<uint32_t>>& members,
                    TreeletsOf<Node>& out) {
    std::vector<uint32_t> localIndex(bvh.nodes.size(), 0);
    for (const std::vector<uint32_t>& mine : members)
        for (size_t j = 0; j < mine.size(); ++j) localIndex[mine[j]] = uint32_t(j);
    for (size_t t = 0; t < members.size(); ++t) {
        TreeletRange r;
        r.nodeBytes = uint32_t(sizeof(Node));
        r.nodeFirst = uint32_t(out.nodes.size());
        r.blockFirst = uint32_t(out.blocks.size());
        for (uint32_t node : members[t]) {
            Node n = bvh.nodes[node];
            for (int k = 0; k < kWidth<Node>; ++k) {
                if (n.count[k] > 0) {
                    const int32_t local = int32_t(out.blocks.size() - r.blockFirst);
                    for (int32_t b = 0; b < n.count[k]; ++b)
                        out.blocks.push_back(bvh.blocks[size_t(n.child[k] + b)]);
                    n.child[k] = local;
                } else if (n.count[k] == 0) {
                    const uint32_t child = uint32_t(n.child[k]);
                    if (out.treeletOfNode[child] == t) {
                        n.child[k] = int32_t(localIndex[child]);
                    } else {
                        n.child[k] = int32_t(out.treeletOfNode[child]);
                        n.count[k] = RT_TREELET_LINK;
                    }
                }
            }
            out.nodes.push_back(n);
        }
        r.nodeCount = uint32_t(out.nodes.size() - r.nodeFirst);
        r.blockCount = uint32_t(out.blocks.size() - r.blockFirst);
        out.maxNodes = std::max(out.maxNodes, r.nodeCount);
        out.maxBlocks = std::max(out.maxBlocks, r.blockCount);
        out.ranges.push_back(r);
    }
}

}  // namespace

template <class Node>
TreeletsOf<Node> cutTreelets(const BvhWide<Node>& bvh, size_t budgetBytes) {
    TreeletsOf<Node> out;
    out.treeletOfNode.assign(bvh.nodes.size(), ~0u);
    if (budgetBytes == 0) budgetBytes = ~size_t(0);
    const std::vector<char> isRoot = treeletRoots(bvh, budgetBytes);
    layOutTreelets(bvh, treeletMembers(bvh, isRoot, out.treeletOfNode), out);
    return out;
}

template struct TreeletsOf<Bvh4Node>;
template struct TreeletsOf<Bvh8Node>;
template struct TreeletsOf<Bvh16Node>;
template size_t treeletNodeBytes(const Bvh4&, size_t);
template size_t treeletNodeBytes(const Bvh8&, size_t);
template size_t treeletNodeBytes(const Bvh16&, size_t);
template Treelets cutTreelets(const Bvh4&, size_t);
template Treelets8 cutTreelets(const Bvh8&, size_t);
template Treelets16 cutTreelets(const Bvh16&, size_t);

}  // namespace rd
