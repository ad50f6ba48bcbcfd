/* intersect.cl: the trace stage over the resident BVH. intersect_closest finds each live
 * ray's nearest hit; intersect_shadow zeroes the weight of the shadow rays that meet an
 * occluder (close_round adds the rest into their samples). */
#include "numerics.clh"
#include "counters.clh"
#include "quadric.h"
#include "traverse.clh"
#include "ray_aovs.clh"
#include "transmittance.clh"
#if defined(RT_SHADOW_PACKETS) || defined(RT_CLOSEST_PACKETS)
#include "packet_traverse.clh"
/* A packet with fewer live rays than this traces them one at a time. */
#ifndef RT_PACKET_MIN_LIVE
#define RT_PACKET_MIN_LIVE 3
#endif

/* Gathers a packet's rays from their slots (slot[j] = count: no ray): pl[j] is -1 for a
 * live ray, its origin, direction and fromSurface in po, pd, ps. Returns how many live. */
inline int rt_packet_gather(const uint* slot, uint count, __global const RayState* state,
                            __global const float4* origin, __global const float4* direction,
                            float4* po, float4* pd, uint* ps, int* pl) {
    int live = 0;
    for (int j = 0; j < RT_PACKET; ++j) {
        uint r = slot[j];
        pl[j] = r < count && state[r].alive ? -1 : 0;
        live -= pl[j];
        r = pl[j] ? r : 0u;
        po[j] = origin[r], pd[j] = direction[r], ps[j] = state[r].from_prim;
    }
    return live;
}
#endif

/* The object scene a kernel's traversal sees: its quadric, CSG and triangle buffers. */
#ifdef RT_HAS_QUADRICS
#define RT_OBJECT_SCENE_ARG , &objs
#ifdef RT_HAS_MOTION
#define RT_RAY_TIME(i) sample_time[ray_sample[i]]
#else
#define RT_RAY_TIME(i) 0.0f
#endif
#define RT_DECLARE_OBJECT_SCENE(ray) \
    const ObjectScene objs = {quadrics, csg, tris, quadric_motion, tris_end, RT_RAY_TIME(ray)}
#else
#define RT_OBJECT_SCENE_ARG
#define RT_DECLARE_OBJECT_SCENE(ray)
#endif
/* Which rays walk their nodes' lanes (coherent: eye rays, mirror and glass rays, whose
 * neighbours in the pool train the branch predictor) and which the hit masks (the rays of
 * shaders that trace in sampled directions, RT_INCOHERENT_TRACE; traverse.clh). */
#ifdef RT_INCOHERENT_TRACE
#define RT_COHERENT(rs) (RT_TRACE_DEPTH(rs) == 0u)
#else
#define RT_COHERENT(rs) 1
#endif
#ifdef RT_HAS_INSTANCES
#define RT_INSTANCE_ARG , &inst
#else
#define RT_INSTANCE_ARG
#endif

/* intersect_closest's arguments, the same in its one-ray and packet forms. */
#define RT_INTERSECT_CLOSEST_PARAMS                                                        \
    uint count, __global const RT_BVH_NODE* nodes, /* RT_BVH8: Bvh8Node */                \
        __global const Triangle4* blocks, __global const float4* origin,                  \
        __global const float4* direction, __global const RayState* state,                \
        __global RayHit* hits, __global const Quadric* quadrics, /* RT_HAS_QUADRICS */     \
        __global const uint* csg, __global const Triangle* tris,                          \
        __global const float4* quadric_motion, /* RT_HAS_MOTION */                         \
        __global const Triangle* tris_end, __global const uint* ray_sample,               \
        __global const float* sample_time,                                                 \
        __global uint* hit_instance, /* RT_HAS_INSTANCES only */                           \
        __global uint* active_counter

#ifndef RT_CLOSEST_PACKETS
__kernel void intersect_closest(RT_INTERSECT_CLOSEST_PARAMS) {
    uint i = get_global_id(0);
    int active = i < count && state[i].alive;
    RT_COUNT_GROUP(active_counter, j, j < count && state[j].alive);
    if (!active) return;
    RT_DECLARE_OBJECT_SCENE(i);
    float4 o = origin[i], d = direction[i];
    RayHit h; /* all of it written by rt_traverse: no hit is t = tmax, u = v = 0 */
    uint inst = RT_NO_HIT;
    rt_traverse(nodes, blocks, o, d, o.w, d.w, state[i].from_prim, 0, RT_COHERENT(state[i]),
                &h RT_OBJECT_SCENE_ARG RT_INSTANCE_ARG);
    hits[i] = h;
#ifdef RT_HAS_INSTANCES
    hit_instance[i] = inst;
#endif
}
#else
/* intersect_closest with a work-item for RT_PACKET consecutive rays (packet_traverse.clh;
 * triangle scenes, eight- or sixteen-wide BVH; the host launches ceil(count / RT_PACKET)
 * work-items).
 * When at least RT_PACKET_MIN_LIVE of them are live, coherent (RT_COHERENT) and share
 * their direction signs they are traced as a packet, otherwise one at a time; every ray's
 * hit is the one-ray kernel's. */
__kernel void intersect_closest(RT_INTERSECT_CLOSEST_PARAMS) {
    uint w = get_global_id(0);
    RT_COUNT_PACKET_GROUP(active_counter, RT_PACKET, g, l,
                          g * RT_PACKET + l < count && state[g * RT_PACKET + l].alive);
    float4 po[RT_PACKET], pd[RT_PACKET];
    uint ps[RT_PACKET], slot[RT_PACKET];
    int pl[RT_PACKET];
    for (int j = 0; j < RT_PACKET; ++j) slot[j] = min(w * RT_PACKET + j, count);
    int live = rt_packet_gather(slot, count, state, origin, direction, po, pd, ps, pl);
    if (!live) return;
    int coherent = 1;
    for (int j = 0; j < RT_PACKET; ++j) coherent &= !pl[j] || RT_COHERENT(state[slot[j]]);
    RtPacket p;
    int8 traced;
    if (live < RT_PACKET_MIN_LIVE || !coherent ||
        (traced = rt_packet_setup(&p, po, pd, ps, vload8(0, pl)), !p.uniform)) {
        for (int j = 0; j < RT_PACKET; ++j) {
            if (!pl[j]) continue;
            RayHit h;
            rt_traverse(nodes, blocks, po[j], pd[j], po[j].w, pd[j].w, ps[j], 0,
                        RT_COHERENT(state[slot[j]]), &h);
            hits[slot[j]] = h;
        }
        return;
    }
    float8 hu, hv;
    uint8 hp;
    rt_packet_closest(nodes, blocks, &p, po, traced, &hu, &hv, &hp);
    float tl[RT_PACKET], ul[RT_PACKET], vl[RT_PACKET];
    uint pr[RT_PACKET];
    vstore8(p.tmax, 0, tl);
    vstore8(hu, 0, ul);
    vstore8(hv, 0, vl);
    vstore8(hp, 0, pr);
    for (int j = 0; j < RT_PACKET; ++j) {
        if (!pl[j]) continue;
        /* a lane not traced (a zero or non-finite direction) misses at its tmax */
        RayHit h = {pr[j] == RT_NO_HIT ? pd[j].w : tl[j], ul[j], vl[j], pr[j]};
        hits[slot[j]] = h;
    }
}
#endif

/* intersect_shadow's arguments, the same in its one-ray and packet forms. */
#define RT_INTERSECT_SHADOW_PARAMS                                                         \
    uint count, __global const RT_BVH_NODE* nodes, /* RT_BVH8: Bvh8Node */                \
        __global const Triangle4* blocks, /* origin, state: written by a hand-off */      \
        __global float4* origin, __global const float4* direction, __global RayState* state, \
        __global rt_weight* weight, /* zeroed when occluded */                                \
        __global const Quadric* quadrics, __global const uint* csg,                       \
        __global const Triangle* tris, __global const float4* quadric_motion,             \
        __global const Triangle* tris_end, __global const uint* ray_sample,               \
        __global const float* sample_time,                                                 \
        uint light_count,        /* shadow ray i: shaded ray i / count */                  \
        __global uint* numerics, /* RT_HAS_PROCEDURALS: flags */                           \
        __global const TriangleAttr* attrs, /* RT_HAS_TRANSPARENT_SHADOWS only */          \
        __global const Material* materials,                                               \
        __global const float* material_channels, /* and more than three channels */      \
        __global float* shadow_aov, /* RT_SHADER_AOVS, transparent shadows: parts it carries */ \
        __global uint* slot_rays, /* RT_SHADER_SHADOWS: rays in flight a sample */          \
        __global uint* active_counter

#ifndef RT_SHADOW_PACKETS
__kernel void intersect_shadow(RT_INTERSECT_SHADOW_PARAMS) {
    uint i = get_global_id(0);
    int active = i < count && state[i].alive;
    RT_COUNT_GROUP(active_counter, j, j < count && state[j].alive);
    if (!active) return;
    RT_DECLARE_OBJECT_SCENE(i / light_count);
    float4 o = origin[i], d = direction[i];
    RayHit h;
    uint inst = RT_NO_HIT;
#ifdef RT_HAS_TRANSPARENT_SHADOWS
    /* Surfaces that let light through: the nearest hit, its transmittance, then on from
     * it, up to the transparent depth; an opaque one ends the ray. (A closest-hit walk:
     * only scenes with such surfaces trace their shadows so.) */
    rt_weight through = (rt_weight)(1.0f);
    float tmin = o.w;
    uint skip = state[i].from_prim;
    int occluded = 1;
    /* (a ray a transmission shader sent on has passed some layers already) */
    for (uint layer = RT_TRANSPARENT_DEPTH(state[i]); layer <= RT_MAX_TRANSPARENT_DEPTH;
         ++layer) {
        inst = RT_NO_HIT;
        if (!rt_traverse(nodes, blocks, o, d, tmin, d.w, skip, 0, 1,
                         &h RT_OBJECT_SCENE_ARG RT_INSTANCE_ARG)) {
            occluded = 0;
            break;
        }
#ifdef RT_HAS_PROCEDURALS
        if (rt_flag_procedural(h.prim, quadrics, numerics)) break;
#endif
        const uint mat = rt_shadow_material(h.prim, inst, attrs, quadrics);
#ifdef RT_SHADER_SHADOWS
        if ((materials[mat].flags & RT_MATERIAL_SHADOW_MASK) == RT_MATERIAL_SHADER_SHADOW) {
            rt_hand_shadow_over(i, through, tmin, skip, layer, weight, origin, state,
                                shadow_aov, ray_sample, light_count, slot_rays);
            return;
        }
#endif
        float most;
        through *= rt_transmittance(mat, materials, material_channels, &most);
        if (!(most > 0.0f)) break; /* (opaque: nothing gets through) */
        tmin = h.t;
        skip = h.prim;
    }
    rt_shadow_passes(i, occluded, through, weight, shadow_aov);
#else
    /* shadow rays converge on their light: the lane walk */
    if (rt_traverse(nodes, blocks, o, d, o.w, d.w, state[i].from_prim, 1, 1,
                    &h RT_OBJECT_SCENE_ARG RT_INSTANCE_ARG)) {
        /* an occluded ray carries nothing; its state stays as the group count read it */
        weight[i] = (rt_weight)(0.0f);
#ifdef RT_HAS_PROCEDURALS
        rt_flag_procedural(h.prim, quadrics, numerics);
#endif
    }
#endif
}
#else
/* Lane j of packet w: the shadow ray toward light w % lights of shaded ray
 * (w / lights) * RT_PACKET + j, so that a packet's rays leave neighbouring points for one
 * light. Returns the slot, or count when the lane has no ray. */
inline uint rt_shadow_packet_slot(uint w, uint j, uint count, uint lights) {
    uint shaded = (w / lights) * RT_PACKET + j;
    return shaded < count / lights ? shaded * lights + w % lights : count;
}

/* intersect_shadow with a packet of RT_PACKET shadow rays a work-item (packet_traverse.clh;
 * triangle scenes, eight- or sixteen-wide BVH). The host launches ceil(shaded rays /
 * RT_PACKET) * lights work-items; results equal the one-ray kernel's. A packet with fewer
 * than RT_PACKET_MIN_LIVE live rays traces them one at a time. */
__kernel void intersect_shadow(RT_INTERSECT_SHADOW_PARAMS) {
    uint w = get_global_id(0);
    RT_COUNT_PACKET_GROUP(active_counter, RT_PACKET, g, l,
                          rt_shadow_packet_slot(g, l, count, light_count) < count &&
                              state[rt_shadow_packet_slot(g, l, count, light_count)].alive);
    float4 po[RT_PACKET], pd[RT_PACKET];
    uint ps[RT_PACKET], slot[RT_PACKET];
    int pl[RT_PACKET];
    for (int j = 0; j < RT_PACKET; ++j) slot[j] = rt_shadow_packet_slot(w, j, count, light_count);
    int live = rt_packet_gather(slot, count, state, origin, direction, po, pd, ps, pl);
    if (!live) return;
    if (live < RT_PACKET_MIN_LIVE) { /* a ray or two: one at a time */
        for (int j = 0; j < RT_PACKET; ++j) {
            RayHit h;
            if (pl[j] && rt_traverse(nodes, blocks, po[j], pd[j], po[j].w, pd[j].w, ps[j], 1, 1, &h))
                weight[slot[j]] = (rt_weight)(0.0f);
        }
        return;
    }
    RtPacket p;
    int8 traced = rt_packet_setup(&p, po, pd, ps, vload8(0, pl));
    int8 occ = rt_packet_occluded(nodes, blocks, &p, po, traced);
    int ol[RT_PACKET];
    vstore8(occ, 0, ol);
    /* an occluded ray carries nothing; its state stays as the group count read it */
    for (int j = 0; j < RT_PACKET; ++j)
        if (ol[j]) weight[slot[j]] = (rt_weight)(0.0f);
}
#endif
