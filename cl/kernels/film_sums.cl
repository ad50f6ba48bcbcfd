/* film_sums.cl: the film's error estimate and tally at the end of a frame, summed on the
 * device: each batch of RT_FILM_BATCH pixels' part of estimateFilmErrors and Film::tally
 * (host/film/film_error.h, film.h) in pixel order, the same bits as the host's
 * (film_stats.clh); the host adds the batches in order. At the end of SPD tetra's frame
 * the host took 1.3 ms for them with the device idle. Only with cl_khr_fp64. */
#include "counters.clh"
#include "film.h"

#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF
#include "film_stats.clh"

/* Batch b: sums[3b ..] the squared standard errors (pixels of two samples or more), the
 * means (pixels with samples) and the replicate variances (pixels with samples of both
 * replicates); counts[4b ..] those three numbers of pixels and the unsampled pixels inside
 * the crop window [crop.x, crop.y) x [crop.z, crop.w); tally[2b ..] the samples and the
 * samples dropped as NaN/Inf. */
__kernel void film_sums(uint count, uint width, uint4 crop, __global const PixelAccum* film,
                        __global double* sums, __global uint* counts, __global ulong* tally,
                        __global uint* active) {
    const uint b = (uint)get_global_id(0);
    const uint batches = (count + RT_FILM_BATCH - 1) / RT_FILM_BATCH;
    if (b < batches) {
        double var = 0.0, mean = 0.0, replicate_var = 0.0;
        uint with_var = 0, with_mean = 0, with_replicates = 0, unsampled = 0;
        ulong samples = 0, nonfinite = 0;
        const uint first = b * RT_FILM_BATCH, end = min(count, first + RT_FILM_BATCH);
        uint y = first / width, x = first - y * width;
        for (uint p0 = first; p0 < end; p0 += 4u) {
            const RtPixels4 px = rt_load_pixels4(film, p0, count);
            const float4 m4 = rt_pixel_mean4(&px), e4 = rt_pixel_std_error4(&px);
            const double4 v4 = rt_replicate_variance4(&px);
            const uint n[4] = {px.n.x, px.n.y, px.n.z, px.n.w};
            const uint nf[4] = {px.nonfinite.x, px.nonfinite.y, px.nonfinite.z,
                                px.nonfinite.w};
            const float m[4] = {m4.x, m4.y, m4.z, m4.w}, e[4] = {e4.x, e4.y, e4.z, e4.w};
            const double v[4] = {v4.x, v4.y, v4.z, v4.w};
            for (uint l = 0; l < 4u && p0 + l < end; ++l) {
                samples += n[l];
                nonfinite += nf[l];
                unsampled += n[l] == 0u && x >= crop.x && x < crop.y && y >= crop.z &&
                             y < crop.w;
                if (++x == width) x = 0, ++y;
                if (n[l] == 0u) continue;
                mean += (double)m[l];
                ++with_mean;
                if (n[l] >= 2u) {
                    var += (double)e[l] * (double)e[l];
                    ++with_var;
                }
                if (v[l] >= 0.0) {
                    replicate_var += v[l];
                    ++with_replicates;
                }
            }
        }
        sums[3u * b] = var;
        sums[3u * b + 1u] = mean;
        sums[3u * b + 2u] = replicate_var;
        counts[4u * b] = with_var;
        counts[4u * b + 1u] = with_mean;
        counts[4u * b + 2u] = with_replicates;
        counts[4u * b + 3u] = unsampled;
        tally[2u * b] = samples;
        tally[2u * b + 1u] = nonfinite;
    }
    RT_COUNT_RANGE(active, batches);
}

#endif
