/* pixel_tests.cl: the adaptive planner's test of every pixel (host/render/sampling.h), on
 * the device: the first adaptive pass tests all of a frame's pixels, which on the host
 * left the device idle for 3.5 ms of SPD tetra's 110 ms frame, and on a GPU needs none of
 * the film on the host. The arithmetic is the host's, operation for operation, so that
 * the planner's answers are the same bits whichever tests (Sampling/IncrementalPlan.IsExact):
 * means and standard errors in double, float divisions taken in double and rounded once
 * (a correctly rounded quotient, where OpenCL allows float division 2.5 ulp), and no
 * contraction into fused multiply-adds. Only with cl_khr_fp64: without it
 * the host tests (DeviceInfo::fp64). */
#include "counters.clh"
#include "film.h"

#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF
#include "film_stats.clh"

/* Each pixel's pixelMean (film_error.h), -1 without samples, as the planner keeps it; what
 * its test starts from: -inf at the most samples (never tested again), NaN under the
 * least (sampled without a test), else its pixelStdError (0 under two samples); and the
 * samples it would be given (SamplePlanner::nextPass: to twice its number, within the
 * least and the most) and the first of their indices (after those dropped as NaN/Inf).
 * Four pixels a work-item (film_stats.clh). */
__kernel void film_means(uint count, uint min_samples, uint max_samples,
                         __global const PixelAccum* film, __global float* mean_of,
                         __global float* error_of, __global uint* more,
                         __global uint* active) {
    const uint p0 = 4u * (uint)get_global_id(0);
    if (p0 < count) {
        const RtPixels4 px = rt_load_pixels4(film, p0, count);
        const uint4 n = px.n;
        const float4 mean = n != 0u ? rt_pixel_mean4(&px) : (float4)(-1.0f);
        const float4 error = n >= max_samples ? (float4)(-INFINITY)
                             : n < min_samples ? (float4)(NAN)
                             : n >= 2u         ? rt_pixel_std_error4(&px)
                                               : (float4)(0.0f);
        const uint4 target = min(max((uint4)(min_samples), max((uint4)(1u), 2u * n)),
                                 (uint4)(max_samples));
        /* (read only where the pixel needs more, and then target > n; a saturating form
         * becomes llvm.usub.sat, which Oclgrind 21.10 does not know) */
        const uint4 samples = target - n;
        const uint4 first = n + px.nonfinite;
        const float m[4] = {mean.x, mean.y, mean.z, mean.w};
        const float e[4] = {error.x, error.y, error.z, error.w};
        const uint k[4] = {samples.x, samples.y, samples.z, samples.w};
        const uint f[4] = {first.x, first.y, first.z, first.w};
        for (uint l = 0; l < 4u && p0 + l < count; ++l) {
            mean_of[p0 + l] = m[l];
            error_of[p0 + l] = e[l];
            more[2u * (p0 + l)] = k[l];
            more[2u * (p0 + l) + 1u] = f[l];
        }
    }
    RT_COUNT_RANGE(active, (count + 3u) / 4u);
}

/* SamplePlanner::contrasts */
inline int rt_contrasts(float m, float mq, float contrast) {
    const float mid = 0.5f * (m + mq);
    return (mq >= 0.0f) & (fabs(m - mq) > contrast * (0.1f < mid ? mid : 0.1f));
}

/* For group g of RT_FILM_BATCH pixels (in pixel order): the sum of the means of its pixels
 * with samples, in order, and their number (the host adds the groups in order:
 * SamplePlanner::brightnessFloor); and each pixel's edge[p]: whether its mean contrasts
 * with one of its four neighbours' (a neighbour off the image is the pixel itself: no
 * contrast). A group's pixels walked in order, its row followed without a division. */
__kernel void film_mean_sums(uint width, uint height, __global const float* mean_of,
                             __global double* group_sum, __global double* group_count,
                             __global uchar* edge, float contrast, __global uint* active) {
    const uint g = (uint)get_global_id(0), count = width * height;
    const uint groups = (count + RT_FILM_BATCH - 1) / RT_FILM_BATCH;
    if (g < groups) {
        double s = 0.0, c = 0.0;
        const uint first = g * RT_FILM_BATCH, end = min(count, first + RT_FILM_BATCH);
        uint y = first / width, x = first - y * width;
        for (uint p = first; p < end; ++p) {
            const float m = mean_of[p];
            if (m >= 0.0f) {
                s += (double)m;
                c += 1.0;
            }
            edge[p] = (uchar)(rt_contrasts(m, mean_of[x > 0 ? p - 1u : p], contrast) |
                              rt_contrasts(m, mean_of[x + 1u < width ? p + 1u : p], contrast) |
                              rt_contrasts(m, mean_of[y > 0 ? p - width : p], contrast) |
                              rt_contrasts(m, mean_of[y + 1u < height ? p + width : p],
                                           contrast));
            if (++x == width) x = 0, ++y;
        }
        group_sum[g] = s;
        group_count[g] = c;
    }
    RT_COUNT_RANGE(active, groups);
}

/* Each pixel p of the planner's order (rank[p] its place in it; ~0 off the crop window):
 * request[2 rank] the samples of its request and request[2 rank + 1] their first index
 * (film_means' `more`) when it needs more (SamplePlanner::needsMore on its relative error
 * against `floor`, and its edge), (~0, 0) when it is busy (busy[p], when use_busy), else
 * (0, 0); and rel_err[p] the error the planner keeps for it: -inf at the most samples,
 * NaN where it keeps its own (busy, under the least samples, off the window). In pixel
 * order, each request scattered to its place: in the planner's order every pixel's
 * neighbours were gathers, and their loads most of the kernel's time. */
__kernel void film_tests(uint count, __global const uint* rank, __global const float* mean_of,
                         __global const float* error_of, __global const uchar* edge,
                         __global const uint* more, __global const uchar* busy,
                         uint use_busy, float floor_, float pixel_error,
                         __global float* rel_err, __global uint* request,
                         __global uint* active) {
    const uint p = (uint)get_global_id(0);
    if (p < count) {
        const uint r = rank[p];
        const float e = error_of[p], m = mean_of[p];
        /* (-inf, the most samples, and NaN, under the least, stay as they are) */
        const float kept = (float)((double)e / (double)(m < floor_ ? floor_ : m));
        const int set_aside = (use_busy != 0u) & (busy[p] != 0);
        const int yes = (e != e) | ((e != -INFINITY) & ((kept > pixel_error) | (edge[p] != 0)));
        rel_err[p] = (set_aside | (r == ~0u)) ? NAN : kept;
        if (r != ~0u) {
            request[2u * r] = set_aside ? ~0u : yes ? more[2u * p] : 0u;
            request[2u * r + 1u] = (set_aside | !yes) ? 0u : more[2u * p + 1u];
        }
    }
    RT_COUNT_RANGE(active, count);
}

#endif
