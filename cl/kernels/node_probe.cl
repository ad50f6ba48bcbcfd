/* node_probe.cl: the node step's helpers (cl/lib/node_test.clh) on given inputs, for
 * tests/host/node_step_test.cpp: the lane mask of every compare pattern, the lowest lane,
 * the distance order of lanes, and the box test of chosen rays against one node. Built
 * four-wide, eight-wide with RT_BVH8 or sixteen-wide with RT_BVH16. Not part of a render. */
#include "node_test.clh"

/* Pattern i (i < 2^W) sets lane k's compare result when bit k of i is set. Out: the
 * lane mask, the lowest lane (-1 for no lane), and the lanes sorted by distance W
 * entries a pattern (-1 after the last); lane k's distance is (5 k) mod W. */
__kernel void lane_mask_probe(uint count, __global uint* mask_out, __global int* lowest_out,
                              __global int* order_out, __global uint* active_counter) {
    uint i = get_global_id(0);
    if (i >= count) return;
    int lanes[RT_BVH_W];
    float dist[RT_BVH_W];
    for (int k = 0; k < RT_BVH_W; ++k) {
        lanes[k] = ((i >> k) & 1u) ? -1 : 0;
        dist[k] = (float)((5 * k) % RT_BVH_W);
    }
    mask_out[i] = rt_lane_mask(RT_LOADW(lanes));
    lowest_out[i] = i ? rt_lowest_lane(i) : -1;
    int order[RT_BVH_W];
    int n = rt_sort_lanes(i, dist, order);
    for (int j = 0; j < RT_BVH_W; ++j) order_out[i * RT_BVH_W + j] = j < n ? order[j] : -1;
}

/* Ray i (tmin origin.w, tmax direction.w) against the node: the mask of boxes it meets. */
__kernel void node_boxes_probe(uint count, __global const RT_BVH_NODE* node,
                               __global const float4* origin, __global const float4* direction,
                               __global uint* mask_out, __global uint* active_counter) {
    uint i = get_global_id(0);
    if (i >= count) return;
    float4 o = origin[i], d = direction[i];
    RtBoxRay r = rt_box_ray(o, d);
    float dist[RT_BVH_W];
    rt_floatw entry;
    mask_out[i] = rt_node_boxes(node, &r, o.w, d.w, dist, &entry);
}
