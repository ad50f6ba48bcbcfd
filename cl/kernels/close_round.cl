/* close_round.cl: the end of a round, one pass over its traced rays: the shadow rays that
 * reached their light go into their samples, and the rays the shade stage spawned are
 * counted per work-group for the compaction (compact.cl; the host reads the sums for the
 * total). One launch, not two: on PoCL each launch leaves the device idle between
 * kernels, and a small scene's round is only a few milliseconds. */
#include "atomics.clh"
#include "counters.clh"
#include "film.h"
#include "ray_weight.clh"

__kernel __attribute__((reqd_work_group_size(RT_COMPACT_GROUP, 1, 1)))
void close_round(uint count, /* traced rays */
                 uint light_count, /* 0: no shadow rays this round */
                 uint count_spawns, /* 0: the shaders spawn no rays (group_live unused) */
                 __global const uint* ray_sample,
                 __global const rt_weight* shadow_weight, /* ray i's: i * light_count + l */
                 __global RayState* shadow_state,
                 __global SampleTotal* total,
                 /* RT_SHADER_AOVS: the parts of a sample's shader AOVs that a shadow ray
                 * carries (i * light_count + l's), added when it reaches its light */
                 __global const float* shadow_aov,
                 __global float* aov_values,
                 __global const uint* spawn_mask,
                 __global uint* group_live,
                 __global uint* active_counter) {
    __local uint live[RT_COMPACT_GROUP];
    uint i = get_global_id(0), lid = get_local_id(0);
    RT_COUNT_RANGE(active_counter, count);
    uint handed = 0u; /* shadow rays handed to the pool (RT_SHADER_SHADOWS): spawned rays */
#ifdef RT_HAS_SHADOW_RAYS
    /* the lights in order and one atomic per ray, so a sample's total does not depend
     * on which light's ray a work-item happened to add first */
    if (i < count && light_count > 0) {
        rsl_color sum = (rsl_color)(0.0f);
        for (uint l = 0; l < light_count; ++l) {
            uint j = i * light_count + l;
#ifdef RT_SHADER_SHADOWS
            if (shadow_state[j].alive == RT_SHADOW_HANDOFF) { /* (compact_scatter moves it) */
                ++handed;
                continue;
            }
#endif
            if (shadow_state[j].alive) {
                rsl_color w = rt_weight_color(shadow_weight[j]);
                shadow_state[j].alive = 0u;
#ifdef RT_SHADER_AOVS
                /* a ray with AOV parts has its alpha lane set (shade_rsl.cl), zeroed with
                 * the rest if it was occluded; only the ray of the sample's first shaded
                 * surface carries parts (one work-item per sample: no atomics), unless
                 * rays below its trace() calls bring parts back (RT_RAY_AOVS) */
                if (RSL_CW(w) != 0.0f)
                    for (uint c = 0; c < RT_SHADER_AOVS; ++c) {
                        float part = shadow_aov[j * RT_SHADER_AOVS + c];
#ifdef RT_RAY_AOVS /* (rays below trace() calls too: several a sample) */
                        rt_atomic_add_float(&aov_values[ray_sample[i] * RT_SHADER_AOVS + c], part);
#else
                        if (part != 0.0f) aov_values[ray_sample[i] * RT_SHADER_AOVS + c] += part;
#endif
                    }
                RSL_CW(w) = 0.0f;
#endif
                sum += w;
            }
        }
        rt_atomic_add_float4(&total[ray_sample[i]].value, rt_total_of(sum));
    }
#endif
    live[lid] = i < count && count_spawns ? popcount(spawn_mask[i]) + handed : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (lid == 0 && count_spawns) {
        uint sum = 0;
        for (int k = 0; k < RT_COMPACT_GROUP; ++k) sum += live[k];
        group_live[get_group_id(0)] = sum;
    }
}
