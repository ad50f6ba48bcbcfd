/* sort_by_shader.cl: the sort stage. Hit rays are sorted by the compiled surface shader of
 * what they hit (a counting sort: classify counts rays per shader, the host reads the
 * counts to size the shade launches, scatter writes ray indices into each shader's run),
 * so each shade kernel runs over its own contiguous run with no idle work-items; misses
 * are left out. The counts alternate between two halves of key_count by round parity:
 * classify clears the other half and the cursors, scatter sums the offsets itself, so a
 * round costs no fill and no upload, only the one read. Classify
 * also clears the spawn mask and shadow slots the shade stage may fill this round, and takes
 * the ray off its sample's count of rays in flight (what it spawns is counted when the
 * compaction keeps it). */
#include "atomics.clh"
#include "counters.clh"
#include "film.h"
#include "ray.h"
#include "ray_weight.clh"
#include "quadric.h"
#include "scene_types.h"
#include "ray_aovs.clh"

#define RT_MAX_SHADER_KEYS 65 /* 64 shaders + the miss key */

__kernel void classify_hits(uint count, uint shader_count, uint light_count, uint parity,
                            __global const RayHit* hits,
                            __global const TriangleAttr* attrs,
                            __global const Material* materials,
                            __global const Quadric* quadrics, /* RT_HAS_QUADRICS only */
                            __global const uint* hit_instance, /* RT_HAS_INSTANCES only */
                            __global uint* key,          /* per ray: shader, or shader_count */
                            __global uint* key_count,    /* 2 x (shader_count + 1) counters */
                            __global uint* key_cursor,   /* shader_count + 1 */
                            __global uint* spawn_mask,   /* the spawn slots a shader fills */
                            __global RayState* shadow_state,
                            __global const uint* ray_sample,
                            __global uint* slot_rays,
                            /* RT_HAS_VISIBILITY_RAYS, RT_SHADER_SHADOWS only: rays whose
                             * weight counts when they escape */
                            __global const RayState* state,
                            __global const rt_weight* weight,
                            __global SampleTotal* total,
                            /* RT_RAY_AOVS only: AOV weights, and the samples' AOVs */
                            __global const float* ray_aovw,
                            __global float* aov_values,
                            __global uint* active_counter) {
    __local uint hist[RT_MAX_SHADER_KEYS];
    uint r = get_global_id(0), lid = get_local_id(0);
    RT_COUNT_RANGE(active_counter, count);
    for (uint k = lid; k <= shader_count; k += get_local_size(0)) hist[k] = 0;
    /* last round's counts and the cursors are done with */
    for (uint k = r; k <= shader_count; k += get_global_size(0)) {
        key_count[(parity ^ 1u) * (shader_count + 1u) + k] = 0u;
        key_cursor[k] = 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (r < count) {
        uint prim = hits[r].prim;
        uint k = shader_count, mat = 0u;
        if (prim != RT_NO_HIT) {
#ifdef RT_HAS_QUADRICS
            mat = (prim & RT_OBJECT_BIT) ? quadrics[prim & RT_OBJECT_MASK].material
                                         : attrs[prim].material;
#ifdef RT_HAS_INSTANCES
            if (hit_instance[r] != RT_NO_HIT) mat = quadrics[hit_instance[r]].material;
#endif
#else
            mat = attrs[prim].material;
#endif
            k = materials[mat].shader;
        }
#ifdef RT_HAS_VISIBILITY_RAYS
        /* an occlusion() ray: its weight counts when it escaped; it is never shaded, but
         * a surface diffuse rays go through passes it on (its shade kernel) */
        if (state[r].alive == RT_ALIVE_VISIBILITY) {
            if (prim == RT_NO_HIT) {
                rt_atomic_add_float4(&total[ray_sample[r]].value,
                                     rt_total_of(rt_weight_color(weight[r])));
#ifdef RT_RAY_AOVS
                rt_aov_add_ray(aov_values, ray_aovw, r, state[r], ray_sample[r], (rsl_color)(1.0f));
#endif
            }
#ifdef RT_HAS_INVISIBLE
            if (prim == RT_NO_HIT || !(materials[mat].flags & RT_MATERIAL_NO_DIFFUSE))
#endif
                k = shader_count;
        }
        /* a distance ray (gather()'s "ray:length"): its weight times the distance to what
         * it met counts, nothing when it escaped; it is never shaded, but goes on through
         * a surface traced rays go through (its shade kernel), measuring from its start */
        if (state[r].alive == RT_ALIVE_DISTANCE) {
#ifdef RT_HAS_INVISIBLE
            const int passes = prim != RT_NO_HIT && (materials[mat].flags & RT_MATERIAL_NO_TRACE);
#else
            const int passes = 0;
#endif
            if (prim != RT_NO_HIT && !passes) {
                const float t = hits[r].t;
                rt_atomic_add_float4(&total[ray_sample[r]].value,
                                     rt_total_of(rt_weight_color(weight[r]) * t));
#ifdef RT_RAY_AOVS
                rt_aov_add_ray(aov_values, ray_aovw, r, state[r], ray_sample[r], (rsl_color)(t));
#endif
            }
            if (!passes) k = shader_count;
        }
#endif
#ifdef RT_SHADER_SHADOWS
        /* a shadow ray sent on by a transmission shader: its weight counts when it meets
         * nothing short of its light; what it meets is shaded for what gets through */
        if (state[r].alive == RT_ALIVE_SHADOW && prim == RT_NO_HIT) {
            rt_atomic_add_float4(&total[ray_sample[r]].value,
                                 rt_total_of(rt_weight_color(weight[r])));
#ifdef RT_RAY_AOVS
            rt_aov_add_ray(aov_values, ray_aovw, r, state[r], ray_sample[r], (rsl_color)(1.0f));
#endif
        }
#endif
        key[r] = k;
        if (shader_count > 1) atomic_inc(&hist[k]); /* one shader: no sort, no counts */
        spawn_mask[r] = 0u;
        for (uint l = 0; l < light_count; ++l) shadow_state[r * light_count + l].alive = 0u;
        atomic_dec(&slot_rays[ray_sample[r]]);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint k = lid; k <= shader_count; k += get_local_size(0))
        if (hist[k]) atomic_add(&key_count[parity * (shader_count + 1u) + k], hist[k]);
}

__kernel void scatter_by_shader(uint count, uint shader_count, uint parity,
                                __global const uint* key,
                                __global const uint* key_count, /* classify's, this parity */
                                __global uint* key_cursor,      /* cleared by classify */
                                __global uint* sorted,
                                __global uint* active_counter) {
    uint r = get_global_id(0);
    int hit = r < count && key[r] < shader_count;
    RT_COUNT_GROUP(active_counter, j, j < count && key[j] < shader_count);
    if (!hit) return;
    const uint k = key[r];
    __global const uint* counts = key_count + parity * (shader_count + 1u);
    uint offset = 0; /* the run's start: the counts before it, a loop of fixed length */
    for (uint s = 0; s < shader_count; ++s) offset += s < k ? counts[s] : 0u;
    sorted[offset + atomic_inc(&key_cursor[k])] = r;
}
