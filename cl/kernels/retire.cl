/* retire.cl: the retire stage. Each pixel of the tile adds its whole samples to the film
 * (sum, sum of squares, count). A sample with a NaN or Inf channel never reaches the film:
 * it is counted instead. One work-item per pixel, so no atomics and a fixed summation
 * order (the image is bit-identical from run to run). */
#include "counters.clh"
#include "film.h"
#include "math.clh"

__kernel void retire_samples(int tile_x, int tile_y, int tile_w, uint pixel_count,
                             int image_w, int spp,
                             __global const SampleTotal* total,
                             __global PixelAccum* film,
                             __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint p = get_global_id(0);
    RT_COUNT_ACTIVE(active_counter, p < pixel_count);
    if (p >= pixel_count) return;
    int px = tile_x + (int)p % tile_w, py = tile_y + (int)p / tile_w;
    __global PixelAccum* acc = &film[py * image_w + px];
    float4 sum = acc->sum, sum_sq = acc->sum_sq;
    uint n = acc->count, bad = acc->nonfinite;
    for (int s = 0; s < spp; ++s) {
        float4 v = total[p * (uint)spp + (uint)s].value;
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
}
