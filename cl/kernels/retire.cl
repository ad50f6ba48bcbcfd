/* retire.cl: the retire stage. Each pixel of the batch adds its whole samples to the film
 * (sum, sum of squares, count). A batch lists each pixel once, its samples in the pool
 * slots [first[k], first[k+1]), so one work-item per pixel needs no atomics and sums in a
 * fixed order (the image is bit-identical from run to run). A sample with a NaN or Inf
 * channel never reaches the film: it is counted instead. */
#include "counters.clh"
#include "film.h"
#include "math.clh"

__kernel void retire_samples(uint pixel_count,
                             __global const uint* batch_pixel,
                             __global const uint* batch_first, /* pixel_count + 1 */
                             __global const SampleTotal* total,
                             __global PixelAccum* film,
                             __global const SampleAov* aov,   /* used with RT_HAS_AOVS */
                             __global AovAccum* aov_film,
                             __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint k = get_global_id(0);
    RT_COUNT_ACTIVE(active_counter, k < pixel_count);
    if (k >= pixel_count) return;
    __global PixelAccum* acc = &film[batch_pixel[k]];
    float4 sum = acc->sum, sum_sq = acc->sum_sq;
    uint n = acc->count, bad = acc->nonfinite;
    for (uint i = batch_first[k]; i < batch_first[k + 1]; ++i) {
        float4 v = total[i].value;
        if (rt_all_finite(v)) {
            sum += v;
            sum_sq += v * v;
            ++n;
        } else {
            ++bad;
        }
    }
    acc->sum = sum;
    acc->sum_sq = sum_sq;
    acc->count = n;
    acc->nonfinite = bad;
#ifdef RT_HAS_AOVS
    __global AovAccum* a = &aov_film[batch_pixel[k]];
    float4 nsum = a->normal_sum;
    float zsum = a->z_sum;
    uint hits = a->hits;
    for (uint i = batch_first[k]; i < batch_first[k + 1]; ++i) {
        if (aov[i].hit) {
            nsum += aov[i].normal;
            zsum += aov[i].z;
            ++hits;
        }
    }
    a->normal_sum = nsum;
    a->z_sum = zsum;
    a->hits = hits;
#endif
}
