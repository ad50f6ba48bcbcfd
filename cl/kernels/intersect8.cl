/* intersect8.cl: closest-hit and any-hit kernels over an eight-wide BVH of triangles
 * (traverse8.clh), for measuring the node width (benchmarks/bench_trace.cpp --wide8). */
#include "counters.clh"
#include "traverse8.clh"

__kernel void intersect_closest8(uint count, __global const Bvh8Node* nodes,
                                 __global const Triangle4* blocks,
                                 __global const float4* origin,
                                 __global const float4* direction,
                                 __global const RayState* state, __global RayHit* hits,
                                 __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint i = get_global_id(0);
    int active = i < count && state[i].alive;
    RT_COUNT_ACTIVE(active_counter, active);
    if (!active) return;
    float4 o = origin[i], d = direction[i];
    RayHit h;
    h.t = d.w;
    h.u = h.v = 0.0f;
    rt_traverse8(nodes, blocks, o, d, o.w, d.w, state[i].from_prim, 0, &h);
    hits[i] = h;
}

__kernel void intersect_shadow8(uint count, __global const Bvh8Node* nodes,
                                __global const Triangle4* blocks,
                                __global const float4* origin,
                                __global const float4* direction,
                                __global RayState* state, __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint i = get_global_id(0);
    int active = i < count && state[i].alive;
    RT_COUNT_ACTIVE(active_counter, active);
    if (!active) return;
    float4 o = origin[i], d = direction[i];
    RayHit h;
    if (rt_traverse8(nodes, blocks, o, d, o.w, d.w, state[i].from_prim, 1, &h))
        state[i].alive = 0u;
}
