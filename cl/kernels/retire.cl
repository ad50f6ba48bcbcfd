/* retire.cl: the retire stage. A sample slot counts the rays of its sample still in flight
 * (generate_eye sets 1, the sort stage takes one off for each ray it classifies, the
 * shade stage adds one for each ray it spawns, the compaction takes off those it drops).
 * Each pixel job whose slots all
 * count zero adds its whole samples to the film, summed in slot order: a pixel has one
 * job per pass unless its samples outnumber the largest job, so the film is the same
 * whatever the pool's capacity. A job with a dropped ray (slot_abort: the pool in
 * extremis) leaves no trace in the film and is marked for the host to issue again,
 * unless this was its last try. A sample with a NaN or Inf channel never reaches the
 * film: it is counted instead. A sample's total is RGB whatever the scene's colour
 * channels (ray_weight.clh, rt_total_of). */
#include "atomics.clh"
#include "counters.clh"
#include "film.h"
#include "math.clh"

/* Whether a job was in flight when this launch began: in flight still, or retired or
 * aborted by this launch (its tag). */
inline int rt_job_was_in_flight(uint state, uint tag) {
    const uint s = state & RT_JOB_STATE_MASK;
    return s == RT_JOB_IN_FLIGHT || s == RT_JOB_LAST_TRY ||
           (state & ~((1u << RT_JOB_TAG_SHIFT) - 1u)) == tag;
}

/* window: the jobs in flight, ring positions [window_start, + window_count) modulo
 * job_capacity. Launches alternate between two halves of progress by the parity of
 * `launch` (the host's count of retire launches); each launch clears the other half for
 * the next. A launch may take the window's jobs from `base` on (a window too large for one
 * launch takes several, the first from 0). In its half, [0] (from ~0) becomes the rank of
 * the oldest job still in flight, so the host frees the retired prefix of the rings; [1]
 * counts jobs aborted by this launch, [2] samples left out as NaN/Inf. */
__kernel void retire_samples(uint window_start, uint window_count, uint job_capacity,
                             uint slot_capacity, uint launch, uint base,
                             __global PixelJob* jobs,
                             __global const uint* slot_rays,
                             __global const uint* slot_abort,
                             __global const SampleTotal* total,
                             __global PixelAccum* film,
                             __global const SampleAov* aov,   /* used with RT_HAS_AOVS */
                             __global AovAccum* aov_film,
                             /* RT_SHADER_AOVS floats a slot, and a pixel */
                             __global const float* aov_values,
                             __global float* aov_film_values,
                             __global uint* progress,
                             __global uint* active_counter) {
    const uint parity = launch & 1u, tag = RT_JOB_TAG(launch);
    RT_COUNT_GROUP(active_counter, q,
                   base + q < window_count &&
                       rt_job_was_in_flight(
                           jobs[rt_ring_add(window_start, base + q, job_capacity)].state,
                           tag));
    uint k = base + get_global_id(0);
    if (k == 0) {
        __global uint* next = progress + 3u * (parity ^ 1u);
        next[0] = 0xffffffffu;
        next[1] = 0u;
        next[2] = 0u;
    }
    progress += 3u * parity;
    uint job = rt_ring_add(window_start, k, job_capacity);
    const uint state = k < window_count ? jobs[job].state : RT_JOB_RETIRED;
    if ((state & RT_JOB_STATE_MASK) != RT_JOB_IN_FLIGHT &&
        (state & RT_JOB_STATE_MASK) != RT_JOB_LAST_TRY)
        return;
    const uint first = jobs[job].first_slot, count = jobs[job].count;
    uint in_flight = 0, dropped = 0;
    for (uint s = 0; s < count; ++s) {
        uint slot = rt_ring_add(first, s, slot_capacity);
        in_flight += slot_rays[slot];
        dropped |= slot_abort[slot];
    }
    if (in_flight) {
        atomic_min(&progress[0], k);
        return;
    }
    if (dropped && (state & RT_JOB_STATE_MASK) == RT_JOB_IN_FLIGHT) {
        jobs[job].state = RT_JOB_ABORTED | tag;
        atomic_inc(&progress[1]);
        return;
    }
    jobs[job].state = RT_JOB_RETIRED | tag;
    float4 sum = (float4)(0.0f), sum_sq = (float4)(0.0f);
#ifdef RT_SAMPLER_SOBOL
    float4 sum_odd = (float4)(0.0f);
    const uint odd_first = (state & RT_JOB_ODD_FIRST) ? 1u : 0u;
#endif
    uint n = 0, bad = 0;
    for (uint s = 0; s < count; ++s) {
        float4 v = total[rt_ring_add(first, s, slot_capacity)].value;
        if (rt_all_finite(v)) {
            sum += v;
            sum_sq += v * v;
            ++n;
#ifdef RT_SAMPLER_SOBOL
            /* (sample s of the job is its pixel's sample first + s) */
            if ((s ^ odd_first) & 1u) sum_odd += (float4)(v.xyz, 1.0f);
#endif
        } else {
            ++bad;
        }
    }
    /* atomics only for a pixel with several jobs in the pass (two may retire in one
     * launch); the pixel's only job owns its film entry */
    __global PixelAccum* acc = &film[jobs[job].pixel];
    if (state & RT_JOB_EXCLUSIVE) {
        acc->sum += sum;
        acc->sum_sq += sum_sq;
#ifdef RT_SAMPLER_SOBOL
        acc->sum_odd += sum_odd;
#endif
        acc->count += n;
        acc->nonfinite += bad;
    } else {
        rt_atomic_add_float4(&acc->sum, sum);
        rt_atomic_add_float4(&acc->sum_sq, sum_sq);
#ifdef RT_SAMPLER_SOBOL
        rt_atomic_add_float4(&acc->sum_odd, sum_odd);
#endif
        atomic_add(&acc->count, n);
        atomic_add(&acc->nonfinite, bad);
    }
    if (bad) atomic_add(&progress[2], bad);
#ifdef RT_HAS_AOVS
    float4 nsum = (float4)(0.0f);
    float zsum = 0.0f;
    uint hits = 0;
    for (uint s = 0; s < count; ++s) {
        uint slot = rt_ring_add(first, s, slot_capacity);
        if (aov[slot].hit) {
            nsum += aov[slot].normal;
            zsum += aov[slot].z;
            ++hits;
        }
    }
    __global AovAccum* a = &aov_film[jobs[job].pixel];
    if (state & RT_JOB_EXCLUSIVE) {
        a->normal_sum += nsum;
        a->z_sum += zsum;
        a->hits += hits;
    } else {
        rt_atomic_add_float4(&a->normal_sum, nsum);
        rt_atomic_add_float((volatile __global float*)&a->z_sum, zsum);
        atomic_add(&a->hits, hits);
    }
#endif
#ifdef RT_SHADER_AOVS
    /* the samples the film counted (finite totals): the pixel's value is the sum over
     * its count, misses adding 0, so edges are antialiased as the colour is */
    __global float* af = aov_film_values + (size_t)jobs[job].pixel * RT_SHADER_AOVS;
    for (uint c = 0; c < RT_SHADER_AOVS; ++c) {
        float v = 0.0f;
        for (uint s = 0; s < count; ++s) {
            uint slot = rt_ring_add(first, s, slot_capacity);
            float x = aov_values[slot * RT_SHADER_AOVS + c];
            if (rt_all_finite(total[slot].value) && isfinite(x)) v += x;
        }
        if (state & RT_JOB_EXCLUSIVE)
            af[c] += v;
        else
            rt_atomic_add_float((volatile __global float*)&af[c], v);
    }
#endif
}
