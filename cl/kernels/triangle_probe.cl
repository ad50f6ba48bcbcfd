/* triangle_probe.cl: counts how many triangles of a list each ray hits, with the scalar
 * watertight test and with the four-wide block test (one triangle per block), for tests
 * of rays through shared edges and vertices and of grazing rays
 * (tests/host/triangle_edge_test.cpp). Not part of a render. */
#include "ray.h"
#include "triangle.clh"

__kernel void triangle_probe(uint count, uint ntris,
                             __global const Triangle* tris,
                             __global const Triangle4* blocks, /* block k: triangle k */
                             __global const float4* origin,
                             __global const float4* direction,
                             __global uint* scalar_hits,
                             __global uint* block_hits,
                             __global uint* active_counter) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float4 o = origin[i], d = direction[i];
    WatertightRay w = rt_watertight_setup(d);
    uint ns = 0, nb = 0;
    for (uint k = 0; k < ntris; ++k) {
        float t, u, v;
        uint prim = RT_NO_HIT;
        ns += rt_intersect_triangle(&w, o, tris[k].v0, tris[k].v1, tris[k].v2, 0.0f, INFINITY,
                                    &t, &u, &v);
        nb += rt_intersect_triangle4(&w, o, &blocks[k], 0.0f, INFINITY, RT_NO_HIT, &t, &u, &v,
                                     &prim);
    }
    scalar_hits[i] = ns;
    block_hits[i] = nb;
}
