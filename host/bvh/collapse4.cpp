// collapse4.cpp: binary to four-wide BVH, leaves packed into blocks of four triangles or
// four objects.
#include "collapse4.h"

#include <cfloat>

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
int packLeaf(const Bvh& bvh, const std::vector<Triangle>& tris, const BvhPrimitives* prims,
             int first, int count, std::vector<Triangle4>& blocks, int& blockCount) {
    int start = int(blocks.size());
    std::vector<uint32_t> triangles, objects;  // leaf slots
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

// Each wide node takes a binary node's children and keeps opening its largest interior
// child until it has W.
template <class Node, int W>
BvhWide<Node> collapseWide(const Bvh& bvh, const std::vector<Triangle>& tris,
                           const BvhPrimitives* prims) {
    BvhWide<Node> result;
    std::vector<Node>& out = result.nodes;
    out.resize(1);
    for (int k = 0; k < W; ++k) clearSlot(out[0], k);
    if (bvh.empty()) return result;
    const std::vector<BvhNode>& b = bvh.nodes;
    // Work list: (wide node index, binary node whose children it holds).
    std::vector<std::pair<size_t, int>> work;
    if (b[0].count > 0) {
        // A single leaf: the root holds it in slot 0.
        setSlot(out[0], 0, b[0]);
        out[0].child[0] = packLeaf(bvh, tris, prims, b[0].left_or_first, b[0].count, result.blocks,
                                   out[0].count[0]);
        return result;
    }
    work.push_back({0, 0});
    while (!work.empty()) {
        auto [wi, bi] = work.back();
        work.pop_back();
        std::vector<int> kids{b[bi].left_or_first, b[bi].left_or_first + 1};
        while (kids.size() < size_t(W)) {
            int best = -1;
            double bestArea = -1;
            for (size_t k = 0; k < kids.size(); ++k)
                if (b[kids[k]].count == 0 && area(b[kids[k]]) > bestArea)
                    best = int(k), bestArea = area(b[kids[k]]);
            if (best < 0) break;
            int open = kids[best];
            kids.erase(kids.begin() + best);
            kids.push_back(b[open].left_or_first);
            kids.push_back(b[open].left_or_first + 1);
        }
        for (int k = 0; k < W; ++k) {
            if (k >= int(kids.size())) {
                clearSlot(out[wi], k);
                continue;
            }
            const BvhNode& n = b[kids[k]];
            setSlot(out[wi], k, n);
            if (n.count > 0) {
                int blocks = 0;
                out[wi].child[k] =
                    packLeaf(bvh, tris, prims, n.left_or_first, n.count, result.blocks, blocks);
                out[wi].count[k] = blocks;
            } else {
                out[wi].child[k] = int(out.size());
                out[wi].count[k] = 0;
                out.emplace_back();
                work.push_back({out.size() - 1, kids[k]});
            }
        }
    }
    return result;
}

}  // namespace

Bvh4 collapseToBvh4(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims) {
    return collapseWide<Bvh4Node, 4>(bvh, tris, prims);
}

Bvh8 collapseToBvh8(const Bvh& bvh, const std::vector<Triangle>& tris,
                    const BvhPrimitives* prims) {
    return collapseWide<Bvh8Node, 8>(bvh, tris, prims);
}

}  // namespace rd
