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

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(BvhNode, 32);
#endif
#endif
