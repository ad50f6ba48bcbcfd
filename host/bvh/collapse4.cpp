// collapse4.cpp: binary to four-, eight- or sixteen-wide BVH by the SAH-optimal collapse, leaves
// packed into blocks of four triangles or four objects.
#include "collapse4.h"

#include <array>
#include <cfloat>
#include <cmath>

#include "host/film/run_in_parts.h"

namespace rd {
namespace {

double area(const BvhNode& n) {
    double dx = double(n.bmax[0]) - n.bmin[0], dy = double(n.bmax[1]) - n.bmin[1],
           dz = double(n.bmax[2]) - n.bmin[2];
    return dx < 0 ? 0 : 2 * (dx * dy + dy * dz + dz * dx);
}

// The six planes of a wide node as float arrays, whatever its layout.
struct Planes {
    float* lo[3];
    float* hi[3];
};
template <class Node>
Planes planes(Node& w) {
    constexpr int W = sizeof(w.child) / sizeof(w.child[0]);
    float* p = w.planes;
    return {{p, p + W, p + 2 * W}, {p + 3 * W, p + 4 * W, p + 5 * W}};
}

template <class Node>
void setSlot(Node& w, int k, const BvhNode& n) {
    Planes p = planes(w);
    for (int a = 0; a < 3; ++a) {
        p.lo[a][k] = n.bmin[a];
        p.hi[a][k] = n.bmax[a];
    }
}

template <class Node>
void clearSlot(Node& w, int k) {
    Planes p = planes(w);
    for (int a = 0; a < 3; ++a) {
        // lo > hi: the near/far slab test rejects it however the ray points
        p.lo[a][k] = FLT_MAX;
        p.hi[a][k] = -FLT_MAX;
    }
    w.child[k] = 0;
    w.count[k] = -1;
}

}  // namespace

namespace {

// Packs a leaf's primitives into blocks of four, triangles first, then objects (quadrics
// and CSG solids: prim lanes with RT_OBJECT_BIT, v0 = box minimum, v1 = box maximum);
// returns the first block's index.
// `triangles` and `objects`: the leaf's slots of each kind (their memory kept from leaf
// to leaf: two allocations a leaf were a tenth of a 1M-triangle collapse).
int packLeaf(const Bvh& bvh, const std::vector<Triangle>& tris, const BvhPrimitives* prims,
             int first, int count, std::vector<Triangle4>& blocks, int& blockCount,
             std::vector<uint32_t>& triangles, std::vector<uint32_t>& objects) {
    int start = int(blocks.size());
    triangles.clear(), objects.clear();
    for (int j = first; j < first + count; ++j) {
        uint32_t slot = bvh.primIndices[size_t(j)];
        uint32_t id = prims ? prims->ids[slot] : slot;
        ((id & RT_OBJECT_BIT) ? objects : triangles).push_back(slot);
    }
    for (size_t p = 0; p < triangles.size(); p += 4) {
        Triangle4 b{};
        float* dst[9] = {&b.v0x.x, &b.v0y.x, &b.v0z.x, &b.v1x.x, &b.v1y.x,
                         &b.v1z.x, &b.v2x.x, &b.v2y.x, &b.v2z.x};
        for (size_t lane = 0; lane < 4; ++lane) {
            if (p + lane >= triangles.size()) {
                b.prim[lane] = RT_EMPTY_LANE;
                continue;
            }
            uint32_t slot = triangles[p + lane];
            uint32_t prim = prims ? prims->ids[slot] : slot;
            const Triangle& t = tris[prim];
            const float src[9] = {t.v0.x, t.v0.y, t.v0.z, t.v1.x, t.v1.y,
                                  t.v1.z, t.v2.x, t.v2.y, t.v2.z};
            for (int c = 0; c < 9; ++c) dst[c][lane] = src[c];
            b.prim[lane] = prim;
        }
        blocks.push_back(b);
    }
    for (size_t p = 0; p < objects.size(); p += 4) {
        Triangle4 b{};
        float* lo[3] = {&b.v0x.x, &b.v0y.x, &b.v0z.x};
        float* hi[3] = {&b.v1x.x, &b.v1y.x, &b.v1z.x};
        for (size_t lane = 0; lane < 4; ++lane) {
            bool used = p + lane < objects.size();
            const Aabb box = used ? prims->bounds[objects[p + lane]] : Aabb();
            for (int a = 0; a < 3; ++a) lo[a][lane] = box.lo[a], hi[a][lane] = box.hi[a];
            b.prim[lane] = used ? prims->ids[objects[p + lane]] : RT_EMPTY_LANE;
        }
        blocks.push_back(b);
    }
    blockCount = int(blocks.size()) - start;
    return start;
}

}  // namespace

namespace {

// The collapse's costs, relative to one block's intersection. A wide node's box test
// costs 1.5 blocks: bench_trace --wide8, alternated runs, 1.0 / 1.5 / 2.0 within the
// noise of one another, all above the greedy collapse; sixteen-wide, 1.0 / 1.5 / 2.0 /
// 3.0 likewise (diffuse rays). A leaf made of a binary subtree
// holds at most two blocks (three: no faster); a binary leaf stays whole, however many it
// has.
constexpr double kNodeCost = 1.5, kBlockCost = 1.0;
constexpr int kMaxMergedLeafBlocks = 2;

// SAH-optimal collapse (Ylitie, Karras and Laine 2017, section 4.1). For every binary
// node n and every i <= W, cost[n][i] is the least SAH cost of the subtree of n laid out
// as at most i children of one wide node, each child a leaf (the subtree's primitives
// packed into blocks) or a wide node of its own. The usual greedy collapse (open the
// largest child until there are W) left half of a 1M-triangle tree's eight-wide nodes
// with two children, each a whole node's load and box test for two leaves.
template <int W>
struct SahCollapse {
    std::vector<std::array<double, W + 1>> cost;
    // how cost[n][i] splits i between n's children: the left child's share, or 0 for
    // cost[n][i - 1] (n in fewer slots)
    std::vector<std::array<int8_t, W + 1>> split;
    std::vector<int8_t> nodeSplit;  // a wide node at n: its left child's share of W
    std::vector<uint8_t> leaf;      // cost[n][1] is n as one leaf
    size_t blockBound = 0;          // the binary leaves' blocks: at least the wide tree's
};

template <int W>
SahCollapse<W> sahCollapse(const Bvh& bvh, const BvhPrimitives* prims) {
    const std::vector<BvhNode>& b = bvh.nodes;
    SahCollapse<W> c;
    c.cost.resize(b.size());
    c.split.resize(b.size());
    c.nodeSplit.assign(b.size(), 1);
    c.leaf.assign(b.size(), 0);
    std::vector<int> tris(b.size(), 0), objs(b.size(), 0);  // blocks are filled apart
    auto blocksOf = [&](size_t n) { return (tris[n] + 3) / 4 + (objs[n] + 3) / 4; };
    for (size_t n = b.size(); n-- > 0;) {  // children after their parents: bottom up
        const double a = area(b[n]);
        auto& cost = c.cost[n];
        auto& split = c.split[n];
        if (b[n].count > 0) {
            for (int j = b[n].left_or_first; j < b[n].left_or_first + b[n].count; ++j) {
                const uint32_t id = prims ? prims->ids[bvh.primIndices[size_t(j)]] : 0;
                ++((id & RT_OBJECT_BIT) ? objs[n] : tris[n]);
            }
            cost.fill(a * kBlockCost * blocksOf(n));
            split.fill(0);
            c.leaf[n] = 1;
            c.blockBound += size_t(blocksOf(n));
            continue;
        }
        const size_t l = size_t(b[n].left_or_first), r = l + 1;
        tris[n] = tris[l] + tris[r];
        objs[n] = objs[l] + objs[r];
        double opened[W + 1];  // n's two children sharing i slots
        int8_t share[W + 1];
        for (int i = 2; i <= W; ++i) {
            opened[i] = INFINITY, share[i] = 1;
            for (int k = 1; k < i; ++k)
                if (const double d = c.cost[l][size_t(k)] + c.cost[r][size_t(i - k)];
                    d < opened[i])
                    opened[i] = d, share[i] = int8_t(k);
        }
        const double asLeaf =
            blocksOf(n) <= kMaxMergedLeafBlocks ? a * kBlockCost * blocksOf(n) : INFINITY;
        const double asNode = a * kNodeCost + opened[W];
        c.nodeSplit[n] = share[W];
        c.leaf[n] = asLeaf <= asNode;
        cost[1] = std::min(asLeaf, asNode);
        split[1] = 0;
        for (size_t i = 2; i <= W; ++i) {
            if (opened[i] < cost[i - 1])
                cost[i] = opened[i], split[i] = share[i];
            else
                cost[i] = cost[i - 1], split[i] = 0;
        }
    }
    return c;
}

// The binary nodes that fill the i slots cost[n][i] stands for, appended to `out`.
template <int W>
void slotsOf(const Bvh& bvh, const SahCollapse<W>& c, int n, int i,
             std::vector<int>& out) {
    while (i > 1 && c.split[size_t(n)][size_t(i)] == 0) --i;
    if (i == 1) {
        out.push_back(n);
        return;
    }
    const int k = c.split[size_t(n)][size_t(i)], l = bvh.nodes[size_t(n)].left_or_first;
    slotsOf(bvh, c, l, k, out);
    slotsOf(bvh, c, l + 1, i - k, out);
}

// The primitives under binary node n: children cover adjacent ranges, left first.
std::pair<int, int> primRange(const Bvh& bvh, int n) {
    int lo = n, hi = n;
    while (bvh.nodes[size_t(lo)].count == 0) lo = bvh.nodes[size_t(lo)].left_or_first;
    while (bvh.nodes[size_t(hi)].count == 0) hi = bvh.nodes[size_t(hi)].left_or_first + 1;
    const BvhNode &first = bvh.nodes[size_t(lo)], &last = bvh.nodes[size_t(hi)];
    return {first.left_or_first, last.left_or_first + last.count - first.left_or_first};
}

// Lays out wide nodes from the work list `work` ((wide node, binary node whose subtree it
// lays out); the wide node is out[first of the pair]) depth first into `out` and
// `blocks`. With `deferred`, a work item whose subtree holds at most `defer` primitives
// is set aside there instead, its wide node left to be filled by its own lay-out.
template <class Node, int W>
void layOut(const Bvh& bvh, const std::vector<Triangle>& tris, const BvhPrimitives* prims,
            const SahCollapse<W>& sah, std::vector<std::pair<size_t, int>> work,
            std::vector<Node>& out, std::vector<Triangle4>& blocks, int defer = 0,
            std::vector<std::pair<size_t, int>>* deferred = nullptr) {
    const std::vector<BvhNode>& b = bvh.nodes;
    std::vector<int> kids;
    std::vector<uint32_t> triangles, objects;  // packLeaf's
    while (!work.empty()) {
        auto [wi, bi] = work.back();
        work.pop_back();
        if (deferred && primRange(bvh, bi).second <= defer) {
            deferred->push_back({wi, bi});
            continue;
        }
        kids.clear();
        const int l = b[size_t(bi)].left_or_first, k = sah.nodeSplit[size_t(bi)];
        slotsOf(bvh, sah, l, k, kids);
        slotsOf(bvh, sah, l + 1, W - k, kids);
        for (int slot = 0; slot < W; ++slot) {
            if (slot >= int(kids.size())) {
                clearSlot(out[wi], slot);
                continue;
            }
            setSlot(out[wi], slot, b[size_t(kids[size_t(slot)])]);
            if (sah.leaf[size_t(kids[size_t(slot)])]) {
                const auto [first, count] = primRange(bvh, kids[size_t(slot)]);
                out[wi].child[slot] = packLeaf(bvh, tris, prims, first, count, blocks,
                                               out[wi].count[slot], triangles, objects);
            } else {
                out[wi].child[slot] = int(out.size());
                out[wi].count[slot] = 0;
                out.emplace_back();
                work.push_back({out.size() - 1, kids[size_t(slot)]});
            }
        }
    }
}

template <class Node, int W>
BvhWide<Node> collapseWide(const Bvh& bvh, const std::vector<Triangle>& tris,
                           const BvhPrimitives* prims, size_t parallelFrom) {
    BvhWide<Node> result;
    std::vector<Node>& out = result.nodes;
    out.resize(1);
    for (int k = 0; k < W; ++k) clearSlot(out[0], k);
    if (bvh.empty()) return result;
    const std::vector<BvhNode>& b = bvh.nodes;
    if (b[0].count > 0) {
        // A single leaf: the root holds it in slot 0.
        std::vector<uint32_t> triangles, objects;
        setSlot(out[0], 0, b[0]);
        out[0].child[0] = packLeaf(bvh, tris, prims, b[0].left_or_first, b[0].count,
                                   result.blocks, out[0].count[0], triangles, objects);
        return result;
    }
    const SahCollapse<W> sah = sahCollapse<W>(bvh, prims);
    const int primCount = int(bvh.primIndices.size());
    if (size_t(primCount) < parallelFrom) {
        // (merged leaves pack no more blocks than their binary leaves: no reallocation)
        result.blocks.reserve(sah.blockBound);
        layOut<Node, W>(bvh, tris, prims, sah, {{0, 0}}, out, result.blocks);
        return result;
    }
    // The top levels here; the subtrees of at most a 16th of the primitives each on the
    // host's cores, into nodes and blocks of their own, appended in the order they were
    // set aside: the same tree and layout whatever the number of threads (the nodes and
    // blocks in another order than one thread's depth-first walk, the same traversals).
    std::vector<std::pair<size_t, int>> parts;
    layOut<Node, W>(bvh, tris, prims, sah, {{0, 0}}, out, result.blocks, primCount / 16,
                    &parts);
    std::vector<BvhWide<Node>> laid(parts.size());
    runTasks(parts.size(), hostThreads(), [&](size_t i, size_t) {
        laid[i].nodes.resize(1);
        layOut<Node, W>(bvh, tris, prims, sah, {{0, parts[i].second}}, laid[i].nodes,
                        laid[i].blocks);
    });
    size_t nodes = out.size(), blocks = result.blocks.size();
    for (const BvhWide<Node>& p : laid)
        nodes += p.nodes.size() - 1, blocks += p.blocks.size();
    out.reserve(nodes);
    result.blocks.reserve(blocks);
    for (size_t i = 0; i < parts.size(); ++i)
        appendWideTree(result, laid[i], int(parts[i].first));
    return result;
}

}  // namespace

Bvh4 collapseToBvh4(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims, size_t parallelFrom) {
    return collapseWide<Bvh4Node, 4>(bvh, tris, prims, parallelFrom);
}

Bvh8 collapseToBvh8(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims, size_t parallelFrom) {
    return collapseWide<Bvh8Node, 8>(bvh, tris, prims, parallelFrom);
}

Bvh16 collapseToBvh16(const Bvh& bvh, const std::vector<Triangle>& tris,
                      const BvhPrimitives* prims, size_t parallelFrom) {
    return collapseWide<Bvh16Node, 16>(bvh, tris, prims, parallelFrom);
}

}  // namespace rd
