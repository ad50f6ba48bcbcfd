// device_scene.h: the scene's arrays on the device (camera, BVH, triangles, attributes,
// normals only when some surface is smooth, materials, lights), built once per render.
#pragma once
#include "bvh/collapse4.h"
#include "features.h"
#include "ocl/buffer.h"
#include "scene_bvh.h"
#include "scene/scene.h"
#include "shaders/shader_set.h"

namespace rd {

struct DeviceScene {
    // `objects` are the scene's quadric records as the BVH build left them (scene_bvh.h).
    DeviceScene(const ClContext& ctx, const Scene& scene, const SceneBvh& bvh,
                const Features& f, const ShadingSetup& shading);
    Camera camera;
    DeviceBuffer<Camera> cameraBuf;
    DeviceBuffer<Bvh4Node> nodes;     // the wide layout the kernels traverse (in 128-byte
                                      // units: an eight-wide node takes two)
    DeviceBuffer<Triangle4> blocks;   // leaf triangles, four to a block, for intersection
                                      // (both empty with f.treelets: treelet_trace.h's)
    DeviceBuffer<Triangle> triangles; // by primitive index, for shading
    DeviceBuffer<TriangleAttr> attrs;
    DeviceBuffer<rt_float4> normals;
    DeviceBuffer<rt_float4> vertexSt, vertexCs, vertexOs;  // only when the scene has them
    DeviceBuffer<Quadric> quadrics;    // exact quadrics and CSG solids (placeholder if none)
    DeviceBuffer<uint32_t> csg;        // CSG member lists and programs
    DeviceBuffer<rt_float4> quadricPrimvars;  // varying Cs, Os of quadrics, if any
    DeviceBuffer<rt_float4> quadricMotion;    // motion blur: moving quadrics' last keys
    DeviceBuffer<Triangle> trianglesEnd;      // and moving triangles' 
    DeviceBuffer<Material> materials;  // bound to compiled shaders and parameter blocks
    DeviceBuffer<float> materialChannels;  // Scene::materialChannels, or a placeholder
    DeviceBuffer<float> params;        // every surface instance's parameter block
    // Shader parameters given per point (scene.h, Scene::triangleParams), placeholders
    // when no primitive gives any
    DeviceBuffer<uint32_t> triangleParams;
    DeviceBuffer<rt_float4> pointParamValues;
    DeviceBuffer<int32_t> pointParamLayout;  // per material (ShadingSetup::pointParamLayout)
};

// Bounds of every triangle, for the BVH builder.
std::vector<Aabb> triangleBounds(const Scene& scene);

// What the BVH is built over: the triangles and quadrics that are not members of a CSG
// solid, the solids, and the motion records of moving triangles.
BvhPrimitives bvhPrimitives(const Scene& scene);

}  // namespace rd
