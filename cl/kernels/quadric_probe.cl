/* quadric_probe.cl: runs the device's quadric and CSG intersection on given rays against
 * one object, for tests that compare it with analytic and high-precision references
 * (tests/host/quadric_test.cpp). Not part of a render. */
#include "objects.clh"
#include "quadric_shade.clh"

__kernel void quadric_probe(uint count, uint object,
                            __global const Quadric* quadrics,
                            __global const uint* csg,
                            __global const Triangle* tris,
                            __global const float4* origin,    /* w = tmin */
                            __global const float4* direction, /* w = tmax */
                            __global float4* hit,      /* t, u, v, 1 on a hit (else 0) */
                            __global uint* hit_prim,
                            __global float4* position, /* world P at the hit's (u, v) */
                            __global float4* normal,   /* world Ng there (after flips) */
                            __global float4* crossing, /* the first three crossings' t;
                                                        * w = how many there are */
                            __global uint* active_counter) {
    uint i = get_global_id(0);
    if (i >= count) return;
    const ObjectScene os = {quadrics, csg, tris, (__global const float4*)0,
                            (__global const Triangle*)0, 0.0f};
    float4 o = origin[i], d = direction[i];
    WatertightRay w = rt_watertight_setup(d);
    __global const Quadric* q = &quadrics[object];
    float t = 0.0f, u = 0.0f, v = 0.0f;
    uint prim = RT_OBJECT_BIT | object;
    int found = q->kind == RT_Q_CSG
                    ? rt_csg_intersect(&os, &w, q, o, d, o.w, d.w, &t, &u, &v, &prim)
                    : rt_quadric_intersect(q, os.quadric_motion, 0.0f, o, d, o.w, d.w, &t, &u, &v, 1);
    hit[i] = (float4)(t, u, v, found ? 1.0f : 0.0f);
    hit_prim[i] = prim;
    float4 P = (float4)(0.0f), dPdu, dPdv, n = (float4)(0.0f);
    if (found && (prim & RT_OBJECT_BIT)) {
        __global const Quadric* hq = &quadrics[prim & RT_OBJECT_MASK];
        rt_quadric_eval(hq, u, v, &P, &dPdu, &dPdv, &n);
        QFrame f = rt_quadric_frame(hq, os.quadric_motion, 0.0f);
        P = f.center + rt_q_to_world(&f, P);
        n = rt_normalize3(n.x * f.to_object[0] + n.y * f.to_object[1] + n.z * f.to_object[2]);
        if (hq->flags & RT_QF_FLIP) n = -n;
    }
    position[i] = P;
    normal[i] = n;
    float ts[4] = {0.0f, 0.0f, 0.0f, 0.0f}, us[4], vs[4];
    int nc = q->kind == RT_Q_CSG ? 0 : rt_quadric_crossings(q, os.quadric_motion, 0.0f, o, d, ts, us, vs);
    crossing[i] = (float4)(ts[0], ts[1], ts[2], (float)nc);
}

/* One object block (blocks[block], followed in `blocks` by any QuadricBlock records)
 * against each ray, as the traversal's leaf test sees it: hit = (t, u, v, 1) or 0, and
 * the primitive. Tests compare a block of plain quadrics intersected four at once with
 * the same block through the lane loop (its record offset cleared). */
__kernel void object_block_probe(uint count, uint block, uint want_uv,
                                 __global const Triangle4* blocks,
                                 __global const Quadric* quadrics,
                                 __global const float4* origin,    /* w = tmin */
                                 __global const float4* direction, /* w = tmax */
                                 __global float4* hit, __global uint* hit_prim,
                                 __global uint* active_counter) {
    uint i = get_global_id(0);
    if (i >= count) return;
    const ObjectScene os = {quadrics, (__global const uint*)0, (__global const Triangle*)0,
                            (__global const float4*)0, (__global const Triangle*)0, 0.0f};
    float4 o = origin[i], d = direction[i];
    WatertightRay w = rt_watertight_setup(d);
    float4 inv = (float4)(1.0f / d.x, 1.0f / d.y, 1.0f / d.z, 0.0f);
    float t = 0.0f, u = 0.0f, v = 0.0f;
    uint prim = RT_EMPTY_LANE;
    rt_real pt[3];
    int pending = 0;
    int found = rt_intersect_object_block(&os, &w, &blocks[block], o, d, inv, o.w, d.w, &t, &u,
                                          &v, &prim, (int)want_uv, pt, &pending);
    if (found && pending) rt_deferred_uv(&os, prim, pt, &u, &v);
    hit[i] = found ? (float4)(t, u, v, 1.0f) : (float4)(0.0f);
    hit_prim[i] = found ? prim : RT_EMPTY_LANE;
}
