/* quadric.h: exact RenderMan quadrics (RI 3.2 section 5.3) and CSG solids as the device
 * sees them. A hit on one is a RayHit whose prim is RT_OBJECT_BIT | index into the Quadric
 * array, with u, v the RI surface parameters; P, N, dPdu, dPdv are re-evaluated from
 * (u, v) at shading time, so a shaded point lies on the exact surface.
 *
 * A quadric is intersected in its object space: the ray is moved there with `to_object`
 * (applied to org - center, so objects far from the world origin keep their precision),
 * and the implicit form qx x^2 + qy y^2 + qz z^2 + lz z + c = 0 (all kinds but the disk
 * and torus) gives one quadratic. A CSG solid (kind RT_Q_CSG) is a box in the BVH over
 * its members, which are not in the BVH themselves. */
#ifndef RT_QUADRIC_H
#define RT_QUADRIC_H
#include "compat.h"

#define RT_Q_SPHERE 0u
#define RT_Q_CYLINDER 1u
#define RT_Q_CONE 2u
#define RT_Q_DISK 3u
#define RT_Q_PARABOLOID 4u
#define RT_Q_HYPERBOLOID 5u
#define RT_Q_TORUS 6u
#define RT_Q_CSG 7u
/* A triangle that moves during the shutter (motion blur): its vertices at the first key
 * are in the Triangle array, at the last key in the end-key triangle array (v0.w, v1.w:
 * the two key times); it is reached through this record, hits report the triangle. */
#define RT_Q_MOVING_TRIANGLE 8u
/* An instance of an object (ObjectBegin/ObjectInstance) whose triangles are stored once,
 * in object space, under their own BVH: its placement maps that space to the world,
 * first_member is the root node of the prototype's BVH (in the shared node array) and
 * material the instance's shader. Hits report the prototype's triangle and the instance
 * (cl/lib/traverse.clh). */
#define RT_Q_INSTANCE 9u
/* A DelayedReadArchive not loaded yet: its bound (shape = low corner, shape2 = high,
 * world) is hit like a box; first_member is its index among the scene's procedurals.
 * A ray that reaches it asks the host to load it (the render starts again with it). */
#define RT_Q_PROCEDURAL 10u

/* RayHit.prim of a quadric or solid member; triangles use the indices below it. */
#define RT_OBJECT_BIT 0x40000000u
#define RT_OBJECT_MASK 0x3fffffffu

/* Quadric.flags (and TriangleAttr.flags for triangle members of a solid) */
#define RT_QF_FLIP 1u       /* shading normal reversed: a surface subtracted in a CSG tree */
#define RT_QF_CSG_MEMBER 2u /* reached only through its solid, not from the BVH */
#define RT_QF_MOVING 4u     /* placement (or triangle vertices) interpolated by ray time */
#define RT_QF_PROTOTYPE 8u  /* a triangle of an instanced object: reached through instances */
#define RT_QF_DICED \
    16u /* a triangle replaced by its diced, displaced pieces: not in the BVH */
#define RT_QF_DISPLACED \
    32u /* such a piece: moved by its displacement shader, not bump mapped */

typedef struct Quadric {
    rt_float4 center;       /* world position of the object-space origin */
    rt_float4 to_world[3];  /* rows of the linear object-to-world map */
    rt_float4 to_object[3]; /* rows of its inverse */
    rt_float4 coef;         /* implicit form: qx, qy, qz, lz */
    rt_float4 range;        /* c, zmin, zmax, thetamax (radians, signed) */
    /* per kind: sphere (r, phimin, phimax) with phi in radians; cylinder (r); cone
     * (height, radius); disk (height, radius); paraboloid (rmax, zmin, zmax);
     * hyperboloid point1 (x, y, z) and w = 1 when planar (point1.z == point2.z);
     * torus (major, minor, phimin, phimax) in radians */
    rt_float4 shape;
    rt_float4 shape2;       /* hyperboloid point2 (x, y, z); planar: w = inner radius and
                             * range.z the outer one */
    rt_float4 st_s, st_t;   /* s and t at the (u, v) corners 00, 10, 01, 11 */
    uint32_t kind;          /* RT_Q_* */
    uint32_t material;      /* index into the Material array */
    uint32_t flags;         /* RT_QF_* */
    uint32_t primvars;      /* first of 8 float4 in the quadric primvar buffer (Cs, then Os
                             * at the 4 corners), or RT_NO_QUADRIC_PRIMVARS */
    /* RT_Q_CSG: members at csg[first_member ..] as (prim, leaf) pairs, 2 uints each,
     * count of them; the tree as a postfix program at csg[first_op ..], op_count ops.
     * RT_Q_MOVING_TRIANGLE: first_member is the triangle's index. */
    uint32_t first_member, member_count, first_op, op_count;
    /* RT_QF_MOVING: its placement at the last motion key is at quadric_motion[motion ..]
     * (4 float4: centre with w = first key's time, to_world rows, row 0's w = last key's
     * time, row 1's w = the number of keys between), the keys between (MotionBegin with
     * three times or more) after it, 4 float4 each (centre with w = its time, rows);
     * placements between keys are interpolated linearly (cl/lib/motion.clh). A moving
     * triangle's keys: motion.clh. */
    uint32_t motion;
    /* shader parameters given per point: the first of 4 x K values in the point
     * parameter buffer (scene.h, Scene::pointParamValues), or RT_NO_POINT_PARAMS */
    uint32_t point_params;
    uint32_t pad2[2];
} Quadric;

#define RT_NO_QUADRIC_PRIMVARS 0xffffffffu
#define RT_NO_POINT_PARAMS 0xffffffffu

/* CSG postfix program: a leaf pushes whether the ray is inside leaf solid k (k in the low
 * bits); the operators pop two and push one. At most 32 leaves and depth 32. */
#define RT_CSG_LEAF 0x00000000u
#define RT_CSG_UNION 0x10000000u
#define RT_CSG_INTERSECTION 0x20000000u
#define RT_CSG_DIFFERENCE 0x30000000u
#define RT_CSG_OP_MASK 0xf0000000u
#define RT_CSG_MAX_LEAVES 32

/* The plain quadrics of an object block side by side, lane k of each vector the block's
 * lane k (cl/lib/quadric4.clh intersects them four at once): spheres, cylinders, cones,
 * paraboloids or disks of any sweep, or non-planar hyperboloids swept the full circle,
 * none moving (a disk's lane: its quadratic 0), in a block whose other lanes are
 * quadrics too (tested one at a time). Their records follow the BVH's leaf blocks in the same buffer,
 * two Triangle4 slots each, and such a block's v2x.x holds, as an int's bits, how many
 * slots on its record is (0 for any other block). Empty lanes are zero. */
typedef struct QuadricBlock {
    rt_float4 center[3];    /* x, y, z of each lane's Quadric.center */
    rt_float4 to_object[9]; /* Quadric.to_object: row r, column c at 3 r + c */
    rt_float4 coef[4];      /* Quadric.coef: qx, qy, qz, lz */
    rt_float4 range[3];     /* Quadric.range: c, zmin, zmax; a disk's: 0, height, |radius| */
    rt_float4 sweep;        /* Quadric.range.w: thetamax (radians, signed); NaN: a lane
                             * that is not plain, intersected on its own */
} QuadricBlock;

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(Quadric, 256);
RT_ASSERT_SIZE(QuadricBlock, 320);
#endif
#endif
