// scene_bvh.cpp: top-level and prototype BVHs merged into one device layout.
#include "scene_bvh.h"


#include "bvh/quadric_blocks.h"
#include "device_scene.h"

namespace rd {

namespace {

// The top level, then each prototype's tree appended, in the layout of width W.
template <class Node, int W, class Collapse>
BvhWide<Node> buildWide(const Scene& scene, const BvhPrimitives& top, const Bvh& bvh,
                        Collapse collapse, std::vector<int>& roots) {
    BvhWide<Node> out = collapse(bvh, scene.triangles, &top, kParallelCollapse);
    for (const Scene::Prototype& p : scene.prototypes) {
        BvhPrimitives prims;
        for (uint32_t t = p.firstTriangle; t < p.firstTriangle + p.triangleCount; ++t) {
            Aabb b;
            const Triangle& tri = scene.triangles[t];
            for (const rt_float4* v : {&tri.v0, &tri.v1, &tri.v2}) {
                const float q[3] = {v->x, v->y, v->z};
                b.grow(q);
            }
            prims.ids.push_back(t);
            prims.bounds.push_back(b);
        }
        Bvh pb = buildBvh(prims.bounds, sceneBvhSettings());
        roots.push_back(appendWideTree(
            out, collapse(pb, scene.triangles, &prims, kParallelCollapse)));
    }
    return out;
}

}  // namespace

BvhBuildSettings sceneBvhSettings() {
    BvhBuildSettings s;
    s.blockSize = 4;
    // A node's eight box tests cost less than a block's four triangle tests: bench_trace
    // --sah-traversal 0.6 against 1.0, three runs each (RayDrive over Embree): diffuse
    // rays 0.81 against 0.78 (75k) and 0.91-0.93 against 0.88 (bunny), shadow rays 1.01-
    // 1.02 against 0.87-0.99 (75k), 1M triangles unchanged.
    s.traversalCost = 0.6f;
    return s;
}

SceneBvh buildSceneBvh(const Scene& scene, int width) {
    SceneBvh out;
    out.width = width == 8 || width == 16 ? width : 4;
    BvhPrimitives top = bvhPrimitives(scene);
    Bvh bvh = buildBvh(top.bounds, sceneBvhSettings());
    out.droppedPrims = bvh.droppedPrims;
    std::vector<int> roots;
    if (out.width == 16)
        out.bvh16 = buildWide<Bvh16Node, 16>(scene, top, bvh, collapseToBvh16, roots);
    else if (out.width == 8)
        out.bvh8 = buildWide<Bvh8Node, 8>(scene, top, bvh, collapseToBvh8, roots);
    else
        out.bvh4 = buildWide<Bvh4Node, 4>(scene, top, bvh, collapseToBvh4, roots);
    out.objects = scene.quadrics;
    for (Quadric& q : out.objects)
        if (q.kind == RT_Q_INSTANCE) q.first_member = uint32_t(roots.at(q.first_member));
    withTree(out, [&](auto& tree) { appendQuadricBlocks(tree.blocks, out.objects); });
    return out;
}

std::vector<Bvh4Node> deviceNodes(const SceneBvh& bvh) {
    return withTree(bvh, [](const auto& tree) { return inNodeUnits(tree.nodes); });
}

const std::vector<Triangle4>& deviceBlocks(const SceneBvh& bvh) {
    return withTree(bvh, [](const auto& tree) -> const std::vector<Triangle4>& {
        return tree.blocks;
    });
}

size_t nodeCount(const SceneBvh& bvh) {
    return withTree(bvh, [](const auto& tree) { return tree.nodes.size(); });
}

size_t nodeBytes(const SceneBvh& bvh) {
    return withTree(bvh, [](const auto& tree) {
        return tree.nodes.size() * sizeof(tree.nodes[0]);
    });
}

}  // namespace rd
