/* compact.cl: stream compaction of the rays the shade stage spawned (the AR250's "rays
 * that hit are compacted onto a stack"). Each shaded ray leaves a mask of the spawn slots
 * it filled (spawn_mask; classify clears it, so a ray reads one word, not its every
 * slot). close_round (close_round.cl) sums live rays per work-group of traced rays
 * (the host reads the sums for the total); compact_scatter's work-group adds up the
 * sums before its own for its offset (a strided sum over at most a few thousand
 * numbers, no upload), then moves each live ray to its offset, keeping their order, so
 * the image does not depend on scheduling. They go behind the next round's eye rays, when
 * the host queued those first (`base`), so that neither waits for the round's count.
 * Live rays beyond the pool's capacity (a shader tracing several rays per hit) go onto
 * the spill stack, traced in later rounds; past the stack's capacity they are dropped,
 * never written out of bounds, and their sample is marked to be issued again. The shade
 * stage counted every spawned ray in its sample's rays in flight; a dropped ray is taken
 * off again.
 * Work-groups are RT_COMPACT_GROUP wide. */
#include "counters.clh"
#include "ray.h"
#include "ray_aovs.clh"
#ifdef RT_RAY_AOVS
/* a ray's AOV weights go with it, when it has any */
inline void rt_move_aovw(__global float* dst, uint to, __global const float* src, uint from,
                         RayState s) {
    if (!(s.depth & RT_AOV_FLAGS)) return;
    for (int c = 0; c < RT_AOV_PAYLOAD; ++c)
        dst[(size_t)to * RT_AOV_PAYLOAD + c] = src[(size_t)from * RT_AOV_PAYLOAD + c];
}
#endif

__kernel __attribute__((reqd_work_group_size(RT_COMPACT_GROUP, 1, 1)))
void compact_scatter(uint count, /* traced rays; ray i's spawn slots are i * RT_SPAWN_SLOTS + k */
                     uint base, /* the first pool position (~0u: fit[1]): eye rays lie before */
                     __global const uint* fit,
                     uint capacity, /* the pool: live rays past it go to the spill stack */
                     uint spill_top,
                     uint spill_capacity,
                     __global const uint* group_live, /* close_round's */
                     __global const uint* spawn_mask,
                     __global const float4* src_origin,
                     __global const float4* src_direction,
                     __global const rt_weight* src_weight,
                     __global const RayState* src_state,
                     __global const uint* src_sample,
                     __global float4* dst_origin,
                     __global float4* dst_direction,
                     __global rt_weight* dst_weight,
                     __global RayState* dst_state,
                     __global uint* dst_sample,
                     __global float4* spill_origin,
                     __global float4* spill_direction,
                     __global rt_weight* spill_weight,
                     __global RayState* spill_state,
                     __global uint* spill_sample,
                     /* RT_RAY_AOVS only: the AOV weights of rays that carry them */
                     __global const float* src_aovw,
                     __global float* dst_aovw,
                     __global float* spill_aovw,
                     __global uint* slot_rays,
                     __global uint* slot_abort,
                     /* RT_SHADER_SHADOWS only: the shadow rays intersect_shadow handed to
                      * the pool (ray.h RT_SHADOW_HANDOFF), ray i's at i * light_count + l */
                     uint light_count,
                     __global const float4* shadow_origin,
                     __global const float4* shadow_direction,
                     __global const rt_weight* shadow_weight,
                     __global const RayState* shadow_state,
                     __global const float* shadow_aov, /* and RT_RAY_AOVS: their parts */
                     __global uint* active_counter) {
    __local uint live[RT_COMPACT_GROUP];
    uint i = get_global_id(0), lid = get_local_id(0);
    __local uint groups_before[RT_COMPACT_GROUP];
    const uint group = get_group_id(0);
    uint sum = 0;
    for (uint g = lid; g < group; g += RT_COMPACT_GROUP) sum += group_live[g];
    groups_before[lid] = sum;
    const uint mask = i < count ? spawn_mask[i] : 0u;
    RT_COUNT_GROUP(active_counter, j, j < count && spawn_mask[j] != 0u);
    uint handed = 0u; /* (as close_round counted them) */
#ifdef RT_SHADER_SHADOWS
    for (uint l = 0; i < count && l < light_count; ++l)
        handed += shadow_state[i * light_count + l].alive == RT_SHADOW_HANDOFF;
#endif
    live[lid] = popcount(mask) + handed;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (!mask && !handed) return;
    /* the group's offset and the position among its live rays: fixed-length loops PoCL
     * can vectorise */
    uint before = base == ~0u ? fit[1] : base;
    for (uint k = 0; k < RT_COMPACT_GROUP; ++k)
        before += groups_before[k] + ((k < lid) ? live[k] : 0u);
    uint j = before;
    /* live ray j goes to pool position j, past the pool's capacity onto the spill stack;
     * past the stack's it is dropped: no longer in flight, and its sample goes again */
#define RT_PUT_RAY(o, d, w, st, sample, put_aovw)                                             \
    {                                                                                     \
        const int spill = j >= capacity;                                                  \
        const uint to = spill ? spill_top + (j - capacity) : j;                           \
        if (!spill || to < spill_capacity) {                                              \
            (spill ? spill_origin : dst_origin)[to] = (o);                                \
            (spill ? spill_direction : dst_direction)[to] = (d);                          \
            (spill ? spill_weight : dst_weight)[to] = (w);                                \
            (spill ? spill_state : dst_state)[to] = (st);                                 \
            (spill ? spill_sample : dst_sample)[to] = (sample);                           \
            put_aovw(spill ? spill_aovw : dst_aovw, to);                                  \
        } else {                                                                          \
            slot_abort[sample] = 1u;                                                      \
            atomic_dec(&slot_rays[sample]);                                               \
        }                                                                                 \
        ++j;                                                                              \
    }
    /* (a spawned ray's AOV weights go with it; a handed shadow ray's parts become some) */
#ifdef RT_RAY_AOVS
#define RT_SPAWNED_AOVW(dst, to) rt_move_aovw(dst, to, src_aovw, from, src_state[from])
#else
#define RT_SPAWNED_AOVW(dst, to)
#endif
#if defined(RT_RAY_AOVS) && defined(RD_AOV_CHANNELS)
#define RT_HANDED_AOVW(dst, to) \
    if (hs.depth & RT_CARRIES_AOVS) rt_aov_store((dst) + (size_t)(to) * RT_AOV_PAYLOAD, aw)
#else
#define RT_HANDED_AOVW(dst, to)
#endif
    for (uint k = 0; k < RT_SPAWN_SLOTS; ++k) {
        if (!(mask & (1u << k))) continue;
        const uint from = i * RT_SPAWN_SLOTS + k;
        RT_PUT_RAY(src_origin[from], src_direction[from], src_weight[from], src_state[from],
                   src_sample[from], RT_SPAWNED_AOVW);
    }
#ifdef RT_SHADER_SHADOWS
    /* the handed shadow rays, in light order: pool rays of their own kind */
    for (uint l = 0; handed && l < light_count; ++l) {
        const uint from = i * light_count + l;
        RayState hs = shadow_state[from];
        if (hs.alive != RT_SHADOW_HANDOFF) continue;
        const uint sample = as_uint(hs.width);
        hs.alive = RT_ALIVE_SHADOW;
        hs.width = 0.0f;
#if defined(RT_RAY_AOVS) && defined(RD_AOV_CHANNELS)
        float aw[RT_AOV_PAYLOAD], parts[RT_SHADER_AOVS];
        if (hs.depth & RT_CARRIES_AOVS) {
            for (int c = 0; c < RT_SHADER_AOVS; ++c)
                parts[c] = shadow_aov[(size_t)from * RT_SHADER_AOVS + c];
            rt_aov_weights_of_parts(aw, parts);
        }
#endif
        RT_PUT_RAY(shadow_origin[from], shadow_direction[from], shadow_weight[from], hs,
                   sample, RT_HANDED_AOVW);
    }
#endif
}
