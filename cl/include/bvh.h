/* bvh.h: the flattened binary BVH node shared by the host builder (host/bvh/) and the
 * device traversal. 32 bytes, two to a cache line. An interior node stores its left child
 * at `left_or_first` and its right child at left_or_first + 1 (children are adjacent);
 * a leaf stores the first primitive index and `count` > 0 primitives. */
#ifndef RT_BVH_H
#define RT_BVH_H
#include "compat.h"

typedef struct BvhNode {
    float bmin[3];
    int32_t left_or_first; /* interior: index of the left child; leaf: first primitive */
    float bmax[3];
    int32_t count; /* 0 for an interior node, number of primitives for a leaf */
} BvhNode;

/* Four-wide node, the layout traversal uses: the four children's boxes as structure of
 * arrays, so one float4 operation tests all four (SIMD within a work-item, which is what
 * a per-ray traversal on a CPU device can use). planes: lo_x[4], lo_y[4], lo_z[4], hi_x[4],
 * hi_y[4], hi_z[4], one array, as the box tests index it at per-ray offsets (an index
 * past a smaller member array is out of bounds in C; Oclgrind reports it). child[k] is a
 * node index for an interior child; for a leaf child, child[k] is its first primitive
 * and count[k] > 0; an unused slot has count[k] = -1 (and an empty box). 128 bytes, two
 * cache lines. */
typedef struct Bvh4Node {
    float planes[24];
    int32_t child[4];
    int32_t count[4]; /* 0 interior, > 0 leaf primitive count, -1 unused */
} Bvh4Node;

/* Eight-wide node: the same as Bvh4Node for eight children, one float8 operation per
 * plane (AVX on a CPU device). 256 bytes, four cache lines. */
typedef struct Bvh8Node {
    float planes[48];
    int32_t child[8];
    int32_t count[8]; /* 0 interior, > 0 leaf block count, -1 unused */
} Bvh8Node;

/* Sixteen-wide node (RT_BVH16): the same for sixteen children, one float16 operation per
 * plane (AVX-512 on a CPU device, where the renderer takes it: bench_trace 1.01-1.07x the
 * eight-wide rate on every ray kind, benchmarks/README session 38). 512 bytes, eight
 * cache lines. */
typedef struct Bvh16Node {
    float planes[96];
    int32_t child[16];
    int32_t count[16];
} Bvh16Node;

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(Bvh16Node, 512);
RT_ASSERT_SIZE(Bvh8Node, 256);
RT_ASSERT_SIZE(BvhNode, 32);
RT_ASSERT_SIZE(Bvh4Node, 128);
#endif
#endif
