// treelet_test.cpp: the cut of a four- or eight-wide BVH into treelets (host/bvh/treelets.h): every
// node lands in exactly one treelet, each treelet keeps within the byte budget (unless a
// single node is larger), a huge budget gives one treelet, and walking the treelets
// through their local indices and links reaches exactly the primitives of the input tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "host/bvh/collapse4.h"
#include "host/bvh/treelets.h"

using namespace rd;

namespace {

// A soup of small random triangles in a unit cube (fixed seed).
std::vector<Triangle> soup(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1), s(-0.02f, 0.02f);
    std::vector<Triangle> tris;
    for (int i = 0; i < n; ++i) {
        float x = u(rng), y = u(rng), z = u(rng);
        tris.push_back({{x, y, z, 0}, {x + s(rng), y + s(rng), z, 0}, {x, y + s(rng), z + s(rng), 0}});
    }
    return tris;
}

Bvh buildBinary(const std::vector<Triangle>& tris) {
    std::vector<Aabb> bounds;
    for (const Triangle& t : tris) {
        Aabb b;
        for (const rt_float4* v : {&t.v0, &t.v1, &t.v2}) {
            const float p[3] = {v->x, v->y, v->z};
            b.grow(p);
        }
        bounds.push_back(b);
    }
    return buildBvh(bounds);
}
Bvh4 build(const std::vector<Triangle>& tris) { return collapseToBvh4(buildBinary(tris), tris); }
Bvh8 build8(const std::vector<Triangle>& tris) { return collapseToBvh8(buildBinary(tris), tris); }

template <class Node>
constexpr int kWidth = int(sizeof(Node::count) / sizeof(Node::count[0]));

// The primitives reachable from treelet t's root, following links into other treelets.
template <class Node>
void walk(const TreeletsOf<Node>& tl, uint32_t t, std::multiset<uint32_t>& prims,
          size_t& visits) {
    const TreeletRange& r = tl.ranges[t];
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        uint32_t local = stack.back();
        stack.pop_back();
        ASSERT_LT(local, r.nodeCount);
        ++visits;
        const Node& n = tl.nodes[r.nodeFirst + local];
        for (int k = 0; k < kWidth<Node>; ++k) {
            if (n.count[k] > 0) {
                ASSERT_LE(uint32_t(n.child[k] + n.count[k]), r.blockCount);
                for (int b = 0; b < n.count[k]; ++b)
                    for (uint32_t p : tl.blocks[r.blockFirst + uint32_t(n.child[k] + b)].prim)
                        if (p != RT_EMPTY_LANE) prims.insert(p);
            } else if (n.count[k] == 0) {
                stack.push_back(uint32_t(n.child[k]));
            } else if (n.count[k] == RT_TREELET_LINK) {
                ASSERT_GT(uint32_t(n.child[k]), t) << "a link points to a later treelet";
                walk(tl, uint32_t(n.child[k]), prims, visits);
            }
        }
    }
}

template <class Node>
void checkCut(const BvhWide<Node>& bvh, const TreeletsOf<Node>& tl, size_t budget) {
    // every node in exactly one treelet
    ASSERT_EQ(tl.treeletOfNode.size(), bvh.nodes.size());
    std::vector<size_t> perTreelet(tl.count(), 0);
    for (uint32_t t : tl.treeletOfNode) {
        ASSERT_LT(t, tl.count());
        ++perTreelet[t];
    }
    size_t nodes = 0, blocks = 0;
    for (size_t t = 0; t < tl.count(); ++t) {
        const TreeletRange& r = tl.ranges[t];
        EXPECT_EQ(r.nodeCount, perTreelet[t]);
        EXPECT_EQ(r.nodeFirst, nodes) << "treelets are contiguous, in order";
        EXPECT_EQ(r.blockFirst, blocks);
        nodes += r.nodeCount;
        blocks += r.blockCount;
        // within budget, unless it is one node that alone exceeds it
        if (budget > 0 && r.bytes() > budget) {
            EXPECT_EQ(r.nodeCount, 1u) << "treelet " << t << " of " << r.bytes() << " bytes";
        }
    }
    EXPECT_EQ(nodes, bvh.nodes.size());
    EXPECT_EQ(blocks, bvh.blocks.size());
    EXPECT_EQ(tl.bytes(), bvh.nodes.size() * sizeof(Node) + bvh.blocks.size() * sizeof(Triangle4));
    // the same primitives, each once, reached by walking the treelets from the root
    std::multiset<uint32_t> want, got;
    for (const Triangle4& b : bvh.blocks)
        for (uint32_t p : b.prim)
            if (p != RT_EMPTY_LANE) want.insert(p);
    size_t visits = 0;
    walk(tl, 0, got, visits);
    EXPECT_EQ(visits, bvh.nodes.size());
    EXPECT_EQ(got, want);
}

}  // namespace

TEST(Treelets, HugeBudgetIsOneTreelet) {
    Bvh4 bvh = build(soup(3000, 1));
    for (size_t budget : {size_t(0), size_t(1) << 40}) {
        Treelets tl = cutTreelets(bvh, budget);
        EXPECT_EQ(tl.count(), 1u);
        checkCut(bvh, tl, budget);
        // one treelet is the input tree, node for node
        for (size_t i = 0; i < bvh.nodes.size(); ++i)
            for (int k = 0; k < 4; ++k) EXPECT_NE(tl.nodes[i].count[k], RT_TREELET_LINK);
    }
}

TEST(Treelets, EveryNodeOnceAndBudgetsRespected) {
    Bvh4 bvh = build(soup(3000, 2));
    ASSERT_GT(bvh.nodes.size(), 100u);
    size_t prev = 0;
    for (size_t budget : {size_t(1) << 20, size_t(64) << 10, size_t(4) << 10, size_t(1024),
                          size_t(1)}) {
        SCOPED_TRACE(budget);
        Treelets tl = cutTreelets(bvh, budget);
        checkCut(bvh, tl, budget);
        EXPECT_GE(tl.count(), prev) << "smaller budgets give more treelets";
        prev = tl.count();
    }
    // a budget below one node: one node per treelet (the AR250's level by level)
    Treelets one = cutTreelets(bvh, 1);
    EXPECT_EQ(one.count(), bvh.nodes.size());
    EXPECT_EQ(one.maxNodes, 1u);
}

TEST(Treelets, FullTreeletsUseTheirBudget) {
    // The bottom-up cut cuts off the largest child subtree of a node over budget, so
    // treelets are not slivers: on average they hold more than 30% of the budget.
    Bvh4 bvh = build(soup(20000, 3));
    const size_t budget = 4096;
    Treelets tl = cutTreelets(bvh, budget);
    checkCut(bvh, tl, budget);
    size_t total = 0;
    for (const TreeletRange& r : tl.ranges) total += r.bytes();
    EXPECT_GT(double(total) / double(tl.count()), 0.3 * budget);
}

TEST(Treelets, EmptyAndSingleLeafTrees) {
    for (int n : {0, 1, 3}) {
        Bvh4 bvh = build(soup(n, 4));
        Treelets tl = cutTreelets(bvh, 1);
        EXPECT_EQ(tl.count(), 1u);
        checkCut(bvh, tl, 1);
    }
}

// The eight-wide tree's cut (what the renderer takes on a CPU device): the same rules,
// its ranges sized by the eight-wide node.
template <class Node>
void expectWideTreeCutsTheSameWay(const BvhWide<Node>& bvh, size_t minNodes) {
    ASSERT_GT(bvh.nodes.size(), minNodes);
    size_t prev = 0;
    for (size_t budget : {size_t(1) << 40, size_t(64) << 10, size_t(4) << 10, size_t(1)}) {
        SCOPED_TRACE(budget);
        TreeletsOf<Node> tl = cutTreelets(bvh, budget);
        checkCut(bvh, tl, budget);
        for (const TreeletRange& r : tl.ranges) EXPECT_EQ(r.nodeBytes, sizeof(Node));
        EXPECT_GE(tl.count(), prev);
        prev = tl.count();
    }
    EXPECT_EQ(cutTreelets(bvh, 1).count(), bvh.nodes.size());
}

TEST(Treelets, EightWideTreeCutsTheSameWay) {
    const std::vector<Triangle> tris = soup(3000, 5);
    expectWideTreeCutsTheSameWay(build8(tris), 50u);
}

TEST(Treelets, SixteenWideTreeCutsTheSameWay) {
    const std::vector<Triangle> tris = soup(3000, 5);
    expectWideTreeCutsTheSameWay(collapseToBvh16(buildBinary(tris), tris), 20u);
}
