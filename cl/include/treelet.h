/* treelet.h: the four-wide BVH cut into treelets (host/bvh/treelets.h) as the treelet-
 * streamed traversal sees it (cl/kernels/treelet.cl). Each treelet is one contiguous run
 * of Bvh4Node and one of Triangle4, so it is one upload; inside a treelet, child[k] of an
 * interior child and of a leaf child are indices local to the treelet's own runs, and a
 * child that is the root of another treelet has count[k] = RT_TREELET_LINK and
 * child[k] = that treelet's index. */
#ifndef RT_TREELET_H
#define RT_TREELET_H
#include "compat.h"

#define RT_TREELET_LINK (-2)

/* Where a treelet's nodes and blocks start in the device arrays: its place in the
 * resident layout, or the cache slot it was uploaded to. */
typedef struct TreeletRef {
    int32_t node_base;
    int32_t block_base;
} TreeletRef;

/* One queue entry: ray `ray` is to be traversed through treelet `treelet`, whose root box
 * it enters at distance `tnear` (a round skips the pair when the ray's best hit is nearer). */
typedef struct TreeletPair {
    uint32_t ray;
    uint32_t treelet;
    float tnear;
    uint32_t pad;
} TreeletPair;

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(TreeletRef, 8);
RT_ASSERT_SIZE(TreeletPair, 16);
#endif
#endif
