/* film.h: what a sample adds up while its rays are in flight, and the per-pixel sums the
 * film keeps (on whole samples, so per-pixel variance is exact). */
#ifndef RT_FILM_H
#define RT_FILM_H
#include "compat.h"

/* A sample's running total: rgb in xyz, alpha (coverage) in w. */
typedef struct SampleTotal {
    rt_float4 value;
} SampleTotal;

typedef struct PixelAccum {
    rt_float4 sum;    /* rgb + alpha */
    rt_float4 sum_sq; /* per channel squares, for the variance */
    uint32_t count;   /* whole samples retired */
    uint32_t nonfinite; /* samples dropped because a channel was NaN or Inf */
    uint32_t pad[2];
} PixelAccum;

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(SampleTotal, 16);
RT_ASSERT_SIZE(PixelAccum, 48);
#endif
#endif
