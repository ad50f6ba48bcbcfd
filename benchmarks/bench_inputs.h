// bench_inputs.h: the meshes and rays bench_trace times RayDrive and Embree on: sphere
// fields made here, a mesh read from an OFF file, primary rays in the renderer's tile
// order, and diffuse and shadow rays from the primary hits.
#pragma once
#include <string>
#include <vector>

#include "cl/include/ray.h"
#include "cl/include/scene_types.h"

struct Mesh {
    std::vector<Triangle> tris;
    std::string name;
};

// A field of `count` spheres, each diced into about `perSphere` triangles, scattered in a
// 10x10x10 box: many objects, open space between them, as a scene has.
Mesh sphereField(int count, int perSphere, const std::string& name);

// A triangle mesh from an OFF file (polygons fanned into triangles), scaled and centred
// into the same 10x10x10 box, e.g. the Stanford bunny from Debian's libcgal-demo
// (run_trace.sh fetches it; it is not ours to commit).
Mesh loadOff(const std::string& path);

struct Rays {
    std::vector<rt_float4> org, dir;  // w: tmin, tmax
};

// Primary rays through side x side pixels, in the order the renderer samples them
// (rd::tileOrder: 16x16 tiles, Morton order within a tile) or in scanline order.
Rays primaryRays(int side, const std::string& order);

// Secondary rays from the primary hits: cosine-ish random directions (diffuse) or toward
// a point light (shadow). Rays whose primary ray missed are left out.
Rays secondaryRays(const Mesh& m, const Rays& prim, const std::vector<RayHit>& hits,
                   bool shadow);
