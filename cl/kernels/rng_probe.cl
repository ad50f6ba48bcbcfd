/* rng_probe.cl: the sampler's numbers for tests/host/rng_test.cpp: rt_random2 of (pixel,
 * sample, pair) for `count` samples of one pixel, and the bit reversal it rests on. */
#include "rng.clh"

__kernel void rng_probe(uint pixel, uint pair, uint count, __global float2* points,
                        __global uint* reversed, __global uint* active_counter) {
    const uint i = get_global_id(0);
    if (i >= count) return;
    points[i] = rt_random2(pixel, i, pair);
#ifdef RT_SAMPLER_SOBOL
    reversed[i] = rt_reverse_bits(i * 0x9e3779b9u + 12345u);
#else
    reversed[i] = 0u;
#endif
}
