/* accumulate.cl: adds the shadow rays that reached their light into their samples. */
#include "atomics.clh"
#include "counters.clh"
#include "film.h"
#include "ray.h"

/* Adds every shadow ray that reached its light into its sample: ray i owns the slots
 * i * light_count + l and adds their sum once (one atomic per ray, not per light). */
__kernel void accumulate_shadows(uint count, uint light_count,
                                 __global const uint* ray_sample,
                                 __global const float4* shadow_weight,
                                 __global RayState* shadow_state,
                                 __global SampleTotal* total,
                                 __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint i = get_global_id(0);
    RT_COUNT_ACTIVE(active_counter, i < count);
    if (i >= count) return;
    float4 sum = (float4)(0.0f);
    for (uint l = 0; l < light_count; ++l) {
        uint j = i * light_count + l;
        if (shadow_state[j].alive) {
            sum += shadow_weight[j];
            shadow_state[j].alive = 0u;
        }
    }
    rt_atomic_add_float4(&total[ray_sample[i]].value, sum);
}
