/* film.h: what a sample adds up while its rays are in flight, and the per-pixel sums the
 * film keeps (on whole samples, so per-pixel variance is exact). */
#ifndef RT_FILM_H
#define RT_FILM_H
#include "compat.h"

/* A sample's running total: rgb in xyz, alpha (coverage) in w. */
typedef struct SampleTotal {
    rt_float4 value;
} SampleTotal;

/* The film's sums (the brightness floor's, the error estimate's) are taken a batch of
 * this many pixels at a time in pixel order, and the batches added in order, on the host
 * and on the device alike (film_error_batch.h, pixel_tests.cl, film_sums.cl): the same
 * bits wherever they are taken. */
#define RT_FILM_BATCH 64

typedef struct PixelAccum {
    rt_float4 sum;    /* rgb + alpha */
    rt_float4 sum_sq; /* per channel squares, for the variance */
    /* Under the Sobol sampler (RT_SAMPLER_SOBOL) a pixel's even and odd samples are two
     * independently scrambled sequences: the odd ones' rgb sum (xyz) and number (w), so
     * that the film's error is estimated from two independent means (film_error.h);
     * zero under independent samples. */
    rt_float4 sum_odd;
    uint32_t count;   /* whole samples retired */
    uint32_t nonfinite; /* samples dropped because a channel was NaN or Inf */
    uint32_t pad[2];
} PixelAccum;

/* Geometric AOVs of a pixel, summed over the samples whose eye ray hit something
 * (allocated only when an AOV is asked for). */
typedef struct AovAccum {
    rt_float4 normal_sum; /* world-space shading normal of the first hit */
    float z_sum;          /* camera-space depth of the first hit */
    uint32_t hits;
    uint32_t pad[2];
} AovAccum;

/* Per-sample AOV record: z is the camera depth per unit of ray distance until the eye ray
 * hits, then the depth; hit = 1 once it has. shaded = 1 once the first surface a camera
 * ray is shaded at has written the shader AOVs (RT_SHADER_AOVS floats a sample, in a
 * buffer of their own: its output variables, and the parts of them that depend on a
 * light, added when the light's shadow ray reaches it). */
typedef struct SampleAov {
    rt_float4 normal;
    float z;
    uint32_t hit;
    uint32_t shaded;
    uint32_t pad;
} SampleAov;

/* A pixel job: `count` consecutive samples of one pixel, in the sample slots
 * [first_slot, first_slot + count) of the slot ring (modulo its capacity). It retires to
 * the film, its samples summed in order, once none of its slots has a ray in flight. */
typedef struct PixelJob {
    uint32_t pixel;
    uint32_t first_slot;
    uint32_t count;
    uint32_t state; /* RT_JOB_* */
} PixelJob;
#define RT_JOB_IN_FLIGHT 0u
#define RT_JOB_RETIRED 1u
#define RT_JOB_ABORTED 2u   /* a ray of it was dropped: issue it again */
#define RT_JOB_LAST_TRY 3u  /* in flight, issued again: retires with what it has */
/* Or'ed into an in-flight state: the pixel's only job in its pass, so no other job adds
 * to its film entry at the same time and retiring it needs no atomics. */
#define RT_JOB_EXCLUSIVE 0x100u
/* Or'ed in too: the job's first sample has an odd index in its pixel's sequence (the
 * Sobol sampler's second scramble; film.h sum_odd). */
#define RT_JOB_ODD_FIRST 0x200u
#define RT_JOB_STATE_MASK 0xffu
/* A job retire_samples retired or aborted carries that launch's tag in bits 16-31 (never
 * 0: the host's own states carry none), so its occupancy count, which may read the state
 * before or after the write, counts the job as active either way (no barrier). */
#define RT_JOB_TAG_SHIFT 16u
#define RT_JOB_TAG(launch) ((((launch) & 0x7fffu) | 0x8000u) << RT_JOB_TAG_SHIFT)
#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(SampleTotal, 16);
RT_ASSERT_SIZE(PixelJob, 16);
RT_ASSERT_SIZE(PixelAccum, 64);
RT_ASSERT_SIZE(AovAccum, 32);
RT_ASSERT_SIZE(SampleAov, 32);
#endif
#endif
