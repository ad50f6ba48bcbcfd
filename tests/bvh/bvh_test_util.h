// bvh_test_util.h: helpers for bvh_test.cpp: a portable seeded generator, random
// triangle soups and rays, a reference closest-hit traversal of the flattened BVH (the
// same walk the OpenCL kernels do), brute force, an invariant checker and a naive
// median-split builder to compare SAH quality against.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "host/bvh/sah_builder.h"

namespace rd::bvhtest {

// splitmix64: unlike std:: distributions, gives the same sequence on every library.
struct Rng {
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float uniform(float lo, float hi) {
        return lo + (hi - lo) * float(next() >> 40) * (1.0f / 16777216.0f);
    }
    int below(int n) { return int(next() % uint64_t(n)); }
};

struct Vec3 {
    float x, y, z;
};
inline Vec3 operator-(Vec3 a, Vec3 b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator+(Vec3 a, Vec3 b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator*(Vec3 a, float s) {
    return {a.x * s, a.y * s, a.z * s};
}
inline float dot(Vec3 a, Vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

struct Triangle {
    Vec3 v[3];
    Aabb bounds() const {
        Aabb b;
        for (const Vec3& p : v) {
            float q[3] = {p.x, p.y, p.z};
            b.grow(q);
        }
        return b;
    }
};

struct Ray {
    Vec3 o, d;
};

struct Hit {
    float t = INFINITY;
    int prim = -1;
};

// Mostly small triangles with some large ones, so leaves overlap as in real scenes.
inline std::vector<Triangle> randomSoup(Rng& rng, int n) {
    std::vector<Triangle> tris(n);
    for (Triangle& t : tris) {
        Vec3 c{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        float s = rng.below(10) == 0 ? rng.uniform(0.1f, 0.6f) : rng.uniform(0.01f, 0.1f);
        for (Vec3& p : t.v)
            p = c + Vec3{rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s)};
    }
    return tris;
}

// Most rays aim at a point inside a random triangle, so that many of them hit.
inline Ray randomRay(Rng& rng, const std::vector<Triangle>& tris) {
    Ray r;
    r.o = {rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f)};
    if (rng.below(10) < 7) {
        const Triangle& t = tris[rng.below(int(tris.size()))];
        float u = rng.uniform(0, 1), v = rng.uniform(0, 1);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        Vec3 p = t.v[0] + (t.v[1] - t.v[0]) * u + (t.v[2] - t.v[0]) * v;
        r.d = p - r.o;
    } else {
        do {
            r.d = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        } while (dot(r.d, r.d) > 1 || dot(r.d, r.d) < 1e-4f);
    }
    return r;
}

// Möller-Trumbore; returns t, or infinity for a miss.
inline float intersect(const Triangle& tri, const Ray& r) {
    Vec3 e1 = tri.v[1] - tri.v[0], e2 = tri.v[2] - tri.v[0];
    Vec3 p = cross(r.d, e2);
    float det = dot(e1, p);
    if (std::fabs(det) < 1e-12f) return INFINITY;
    float inv = 1.0f / det;
    Vec3 s = r.o - tri.v[0];
    float u = dot(s, p) * inv;
    if (u < 0 || u > 1) return INFINITY;
    Vec3 q = cross(s, e1);
    float v = dot(r.d, q) * inv;
    if (v < 0 || u + v > 1) return INFINITY;
    float t = dot(e2, q) * inv;
    return t > 1e-6f ? t : INFINITY;
}

inline void closerHit(Hit& h, float t, int prim) {
    // Ties go to the lower index so that brute force and BVH order agree.
    if (t < h.t || (t == h.t && t != INFINITY && prim < h.prim)) h = {t, prim};
}

inline Hit closestHitBruteForce(const std::vector<Triangle>& tris, const Ray& r) {
    Hit h;
    for (size_t i = 0; i < tris.size(); ++i) closerHit(h, intersect(tris[i], r), int(i));
    return h;
}

// Slab test with a little slack on the far distance so rounding never culls a box the
// triangle test would hit (as PBRT does).
inline bool hitsBox(const BvhNode& n, const Ray& r, float tMax) {
    float o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
    float tNear = 0.0f, tFar = tMax;
    for (int a = 0; a < 3; ++a) {
        float inv = 1.0f / d[a];
        float t0 = (n.bmin[a] - o[a]) * inv, t1 = (n.bmax[a] - o[a]) * inv;
        if (t0 > t1) std::swap(t0, t1);
        tNear = std::max(tNear, t0);
        tFar = std::min(tFar, t1 * 1.00001f);
    }
    return tNear <= tFar;
}

inline Hit closestHitBvh(const Bvh& bvh, const std::vector<Triangle>& tris,
                         const Ray& r) {
    Hit h;
    if (bvh.empty()) return h;  // the empty root must not be descended
    std::vector<int> stack = {0};
    while (!stack.empty()) {
        const BvhNode& n = bvh.nodes[stack.back()];
        stack.pop_back();
        if (!hitsBox(n, r, h.t)) continue;
        if (n.count == 0) {
            stack.push_back(n.left_or_first + 1);
            stack.push_back(n.left_or_first);
            continue;
        }
        for (int i = 0; i < n.count; ++i) {
            int prim = int(bvh.primIndices[n.left_or_first + i]);
            closerHit(h, intersect(tris[prim], r), prim);
        }
    }
    return h;
}

inline Aabb nodeBox(const BvhNode& n) {
    return Aabb(n.bmin[0], n.bmin[1], n.bmin[2], n.bmax[0], n.bmax[1], n.bmax[2]);
}

// Everything the device traversal relies on: each valid primitive referenced exactly
// once and invalid ones never; boxes nest; children adjacent, after their parent and
// reached once; leaf sizes in [1, maxLeaf]; depth and droppedPrims as reported.
inline ::testing::AssertionResult checkInvariants(const Bvh& bvh,
                                                  const std::vector<Aabb>& prims,
                                                  int maxLeaf) {
    using ::testing::AssertionFailure;
    uint32_t invalid = 0;
    for (const Aabb& b : prims) invalid += b.isValid() ? 0 : 1;
    if (bvh.droppedPrims != invalid)
        return AssertionFailure()
               << "droppedPrims " << bvh.droppedPrims << " != " << invalid;
    if (bvh.primIndices.size() != prims.size() - invalid)
        return AssertionFailure() << "primIndices has " << bvh.primIndices.size();
    if (bvh.nodes.empty()) return AssertionFailure() << "no root";
    if (bvh.empty()) {
        if (bvh.nodes.size() != 1 || bvh.nodes[0].count != 0 || bvh.depth != 1)
            return AssertionFailure() << "bad empty tree";
        return ::testing::AssertionSuccess();
    }
    std::vector<int> refs(prims.size(), 0);
    std::vector<char> slotSeen(bvh.primIndices.size(), 0), nodeSeen(bvh.nodes.size(), 0);
    std::vector<std::pair<int, int>> stack = {{0, 1}};  // node, depth
    int depth = 0;
    nodeSeen[0] = 1;
    while (!stack.empty()) {
        auto [i, d] = stack.back();
        stack.pop_back();
        depth = std::max(depth, d);
        const BvhNode& n = bvh.nodes[i];
        Aabb box = nodeBox(n);
        if (n.count < 0) return AssertionFailure() << "node " << i << " count < 0";
        if (n.count == 0) {
            int c = n.left_or_first;
            if (c <= i || size_t(c) + 1 >= bvh.nodes.size())
                return AssertionFailure() << "node " << i << " bad children " << c;
            for (int k = c; k <= c + 1; ++k) {
                if (nodeSeen[k]) return AssertionFailure() << "node " << k << " twice";
                nodeSeen[k] = 1;
                if (!box.contains(nodeBox(bvh.nodes[k])))
                    return AssertionFailure() << "node " << i << " misses child " << k;
                stack.push_back({k, d + 1});
            }
            continue;
        }
        if (n.count > maxLeaf)
            return AssertionFailure() << "leaf " << i << " has " << n.count << " prims";
        if (n.left_or_first < 0 ||
            size_t(n.left_or_first) + n.count > bvh.primIndices.size())
            return AssertionFailure() << "leaf " << i << " range out of bounds";
        for (int k = n.left_or_first; k < n.left_or_first + n.count; ++k) {
            if (slotSeen[k]) return AssertionFailure() << "slot " << k << " shared";
            slotSeen[k] = 1;
            uint32_t p = bvh.primIndices[k];
            if (p >= prims.size() || !prims[p].isValid())
                return AssertionFailure() << "slot " << k << " bad prim " << p;
            if (++refs[p] > 1) return AssertionFailure() << "prim " << p << " twice";
            if (!box.contains(prims[p]))
                return AssertionFailure() << "leaf " << i << " misses prim " << p;
        }
    }
    if (std::count(nodeSeen.begin(), nodeSeen.end(), 0) != 0)
        return AssertionFailure() << "unreachable nodes";
    if (std::count(slotSeen.begin(), slotSeen.end(), 0) != 0)
        return AssertionFailure() << "unreferenced prim slots";
    if (depth != bvh.depth)
        return AssertionFailure() << "depth " << bvh.depth << ", actual " << depth;
    return ::testing::AssertionSuccess();
}

// Naive reference: split the index range in half along the widest centroid axis.
inline Bvh buildMedianBvh(const std::vector<Aabb>& prims, int maxLeaf) {
    Bvh bvh;
    for (uint32_t i = 0; i < prims.size(); ++i) bvh.primIndices.push_back(i);
    bvh.nodes.push_back(BvhNode{});
    struct Task {
        int node, begin, end, depth;
    };
    std::vector<Task> stack = {{0, 0, int(prims.size()), 1}};
    while (!stack.empty()) {
        Task t = stack.back();
        stack.pop_back();
        bvh.depth = std::max(bvh.depth, t.depth);
        Aabb box, cbox;
        for (int i = t.begin; i < t.end; ++i) {
            const Aabb& b = prims[bvh.primIndices[i]];
            box.grow(b);
            float c[3];
            b.centroid(c);
            cbox.grow(c);
        }
        BvhNode& n = bvh.nodes[t.node];
        std::memcpy(n.bmin, box.lo, sizeof n.bmin);
        std::memcpy(n.bmax, box.hi, sizeof n.bmax);
        if (t.end - t.begin <= maxLeaf) {
            n.left_or_first = t.begin;
            n.count = t.end - t.begin;
            continue;
        }
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (cbox.hi[a] - cbox.lo[a] > cbox.hi[axis] - cbox.lo[axis]) axis = a;
        int mid = (t.begin + t.end) / 2;
        auto first = bvh.primIndices.begin();
        std::nth_element(first + t.begin, first + mid, first + t.end,
                         [&](uint32_t x, uint32_t y) {
                             return prims[x].centroid(axis) < prims[y].centroid(axis);
                         });
        int left = int(bvh.nodes.size());
        n.left_or_first = left;
        n.count = 0;
        bvh.nodes.resize(bvh.nodes.size() + 2);
        stack.push_back({left, t.begin, mid, t.depth + 1});
        stack.push_back({left + 1, mid, t.end, t.depth + 1});
    }
    return bvh;
}

}  // namespace rd::bvhtest
