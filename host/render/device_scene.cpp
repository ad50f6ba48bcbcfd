// device_scene.cpp: uploading the scene.
#include "device_scene.h"

namespace rd {

std::vector<Aabb> triangleBounds(const Scene& scene) {
    std::vector<Aabb> bounds(scene.triangles.size());
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        for (const rt_float4* v : {&t.v0, &t.v1, &t.v2}) {
            const float p[3] = {v->x, v->y, v->z};
            bounds[i].grow(p);
        }
    }
    return bounds;
}

BvhPrimitives bvhPrimitives(const Scene& scene) {
    BvhPrimitives p;
    std::vector<Aabb> tb = triangleBounds(scene);
    for (size_t i = 0; i < tb.size(); ++i) {
        // solid members are reached through their solid, moving triangles through their
        // motion records, prototypes through their instances
        // (and diced triangles through their pieces)
        if (scene.attrs[i].flags &
            (RT_QF_CSG_MEMBER | RT_QF_MOVING | RT_QF_PROTOTYPE | RT_QF_DICED))
            continue;
        p.ids.push_back(uint32_t(i));
        p.bounds.push_back(tb[i]);
    }
    for (size_t i = 0; i < scene.quadrics.size(); ++i) {
        // (a diced moving triangle's record too: its pieces' records stand for it)
        if (scene.quadrics[i].flags & (RT_QF_CSG_MEMBER | RT_QF_DICED)) continue;
        p.ids.push_back(RT_OBJECT_BIT | uint32_t(i));
        p.bounds.push_back(scene.quadricBounds[i]);
    }
    return p;
}

// Every triangle's entry, none for those added before the first that had any (or all,
// when only quadrics have them): the shade kernel reads it at any triangle hit.
static std::vector<uint32_t> triangleParamsFor(const Scene& scene) {
    std::vector<uint32_t> t = scene.triangleParams;
    t.resize(scene.triangles.size(), RT_NO_POINT_PARAMS);
    return t;
}

DeviceScene::DeviceScene(const ClContext& ctx, const Scene& scene, const SceneBvh& bvh,
                         const Features& f, const ShadingSetup& shading)
    : camera(scene.deviceCamera()),
      cameraBuf(ctx, std::vector<Camera>{camera}),
      // the treelet path (treelet_trace.h) keeps its own copy of the tree, or a cache
      nodes(f.treelets ? DeviceBuffer<Bvh4Node>(ctx, 0)
                       : DeviceBuffer<Bvh4Node>(ctx, deviceNodes(bvh))),
      blocks(f.treelets ? DeviceBuffer<Triangle4>(ctx, 0)
                        : DeviceBuffer<Triangle4>(ctx, deviceBlocks(bvh))),
      triangles(ctx, scene.triangles),
      attrs(ctx, scene.attrs),
      normals(f.smoothNormals ? DeviceBuffer<rt_float4>(ctx, scene.normals)
                              : DeviceBuffer<rt_float4>(ctx, 0)),
      vertexSt(ctx, scene.vertexSt),
      vertexCs(ctx, scene.vertexCs),
      vertexOs(ctx, scene.vertexOs),
      quadrics(ctx, bvh.objects),
      csg(ctx, scene.csg),
      quadricPrimvars(ctx, scene.quadricPrimvars),
      quadricMotion(ctx, scene.quadricMotion),
      trianglesEnd(ctx, scene.trianglesEnd),
      materials(ctx, shading.materials),
      materialChannels(ctx, scene.materialChannels),
      // rd_prepare_uniforms writes the shaders' uniform results into the parameter
      // blocks: a kernel's write to a CL_MEM_READ_ONLY buffer is undefined (Oclgrind
      // reports it; a GPU may drop it)
      params(ctx, shading.params,
             shading.prepares.empty() ? CL_MEM_READ_ONLY : CL_MEM_READ_WRITE),
      triangleParams(
          ctx, f.pointParams > 0 ? triangleParamsFor(scene) : std::vector<uint32_t>{}),
      pointParamValues(
          ctx, f.pointParams > 0 ? scene.pointParamValues : std::vector<rt_float4>{}),
      pointParamLayout(
          ctx, f.pointParams > 0 ? shading.pointParamLayout : std::vector<int32_t>{}) {}

}  // namespace rd
