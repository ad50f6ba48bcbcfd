// scene_bvh.cpp: top-level and prototype BVHs merged into one device layout.
#include "scene_bvh.h"

#include "device_scene.h"

namespace rd {

int appendBvh4(Bvh4& into, const Bvh4& part) {
    const int nodeOffset = int(into.nodes.size()), blockOffset = int(into.blocks.size());
    for (Bvh4Node n : part.nodes) {
        for (int k = 0; k < 4; ++k) {
            if (n.count[k] > 0) n.child[k] += blockOffset;       // a leaf: its first block
            else if (n.count[k] == 0) n.child[k] += nodeOffset;  // an interior child
        }
        into.nodes.push_back(n);
    }
    into.blocks.insert(into.blocks.end(), part.blocks.begin(), part.blocks.end());
    return nodeOffset;
}

BvhBuildSettings sceneBvhSettings() {
    BvhBuildSettings s;
    s.blockSize = 4;
    return s;
}

SceneBvh buildSceneBvh(const Scene& scene) {
    SceneBvh out;
    BvhPrimitives top = bvhPrimitives(scene);
    Bvh bvh = buildBvh(top.bounds, sceneBvhSettings());
    out.droppedPrims = bvh.droppedPrims;
    out.bvh4 = collapseToBvh4(bvh, scene.triangles, &top);
    std::vector<int> roots;
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
        roots.push_back(appendBvh4(out.bvh4, collapseToBvh4(pb, scene.triangles, &prims)));
    }
    out.objects = scene.quadrics;
    for (Quadric& q : out.objects)
        if (q.kind == RT_Q_INSTANCE) q.first_member = uint32_t(roots.at(q.first_member));
    return out;
}

}  // namespace rd
