/* scene_types.h: the scene as the device sees it: triangles, their per-triangle attributes,
 * shader instances ("materials" until rsl2cl lands), lights and the camera. One definition
 * for OpenCL C and C++; sizes are asserted on the host and offsets probed on the device. */
#ifndef RT_SCENE_TYPES_H
#define RT_SCENE_TYPES_H
#include "compat.h"

/* Vertices in world space; w is unused (0). Kept as vertices, not edges, because the
 * watertight test shears vertices relative to the ray origin. */
typedef struct Triangle {
    rt_float4 v0, v1, v2;
} Triangle;

/* Four triangles of a BVH leaf as structure of arrays, the layout intersection uses:
 * one float4 operation tests all four against a ray (the watertight test's shear is the
 * same for every lane). prim[k] is the triangle's index in the Triangle array, or
 * RT_EMPTY_LANE for an unused lane. 160 bytes. */
typedef struct Triangle4 {
    rt_float4 v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
    uint32_t prim[4];
} Triangle4;
#define RT_EMPTY_LANE 0xffffffffu

typedef struct TriangleAttr {
    uint32_t material;    /* index into the Material array */
    uint32_t has_normals; /* 1: smooth normals at index 3*tri in the normals buffer */
    uint32_t primvars;    /* RT_PRIMVAR_*: per-vertex values at 3*tri in their buffers */
    uint32_t flags;       /* RT_QF_* (quadric.h): triangles that belong to a CSG solid */
} TriangleAttr;

/* Per-vertex primitive variables a triangle carries (else s,t = u,v; Cs, Os from the
 * attributes). Their buffers exist only when some triangle of the scene has them. */
#define RT_PRIMVAR_ST 1u
#define RT_PRIMVAR_CS 2u
#define RT_PRIMVAR_OS 4u

/* A shader instance as the device sees it: which compiled surface shader runs (its shade
 * kernel), where its parameter block starts in the parameter buffer, and the colour and
 * opacity attributes current when the geometry was declared. */
typedef struct Material {
    rt_float4 cs;      /* Cs */
    rt_float4 os;      /* Os; w = mean opacity */
    uint32_t shader;   /* index of the compiled surface shader (its shade kernel) */
    uint32_t params;   /* first float of its parameter block */
    uint32_t flags;    /* RT_MATERIAL_* */
    uint32_t lights_off; /* bit l: light l turned off by Illuminate for this surface */
} Material;

/* Matte 1: a holdout. It hides what is behind it but adds neither colour nor alpha. */
#define RT_MATERIAL_MATTE 1u
/* Sides 1: hits on the back (the side its normal points away from) are ignored. */
#define RT_MATERIAL_ONE_SIDED 2u
/* Attribute "visibility" "int camera" [0] / "int trace" [0] (PRMan): camera rays (and
 * their continuations through transparent surfaces), or traced rays, go through it. */
#define RT_MATERIAL_NO_CAMERA 4u
#define RT_MATERIAL_NO_TRACE 8u
/* "int diffuse" [0]: the rays of occlusion() and indirectdiffuse() go through it
 * ("int specular" [0] is RT_MATERIAL_NO_TRACE: trace() and gather() rays; "int trace"
 * [0] both). */
#define RT_MATERIAL_NO_DIFFUSE 128u
/* What a shadow ray sees of it, a two-bit field (RT_MATERIAL_SHADOW_MASK): none of the
 * bits, its constant opacity Os (PRMan's "primitive" transmission); */
#define RT_MATERIAL_SHADOW_MASK 48u
/* Attribute "visibility" "int transmission" [0]: shadow rays go through it (it casts no
 * shadow); */
#define RT_MATERIAL_NO_TRANSMISSION 16u
/* "string transmission" "opaque": a full shadow whatever its opacity Os; */
#define RT_MATERIAL_OPAQUE_SHADOW 32u
/* both, "string transmission" "shader" (or "shade" "transmissionhitmode" "shader"): its
 * surface shader's Oi, the shader run where a shadow ray meets it (RT_SHADER_SHADOWS). */
#define RT_MATERIAL_SHADER_SHADOW 48u
/* Displaced truly (host/scene/dice_displaced.h): diced and moved before rendering, so
 * the shade stage leaves its displacement shader alone. */
#define RT_MATERIAL_TRUE_DISPLACEMENT 64u
/* Bits 8..15: 1 + the index of the surface's Atmosphere shader, 0 for none. */
#define RT_MATERIAL_ATMOSPHERE_SHIFT 8u
#define RT_MATERIAL_ATMOSPHERE_MASK 0xff00u
/* Bits 16..23: 1 + the index of the surface's Displacement shader, 0 for none. */
#define RT_MATERIAL_DISPLACEMENT_SHIFT 16u
#define RT_MATERIAL_DISPLACEMENT_MASK 0xff0000u
/* Bits 24..31: 1 + the index of the surface's Interior volume shader, 0 for none: it runs
 * on what a ray brings back from this surface's back, the segment inside the object. */
#define RT_MATERIAL_INTERIOR_SHIFT 24u
#define RT_MATERIAL_INTERIOR_MASK 0xff000000u

/* Camera: rays start in camera space (RenderMan: left-handed, looking down +z) and are
 * moved to world space by the 3x4 matrix camera_to_world (rows, column-vector convention). */
/* The camera's motion keys between its first and last (more are left out, with a
 * warning) */
#define RT_CAMERA_MAX_BETWEEN 8
#define RT_FILTER_TABLE 128
#define RT_FILTER_FLIPS 16 /* sign changes a filter may have per axis */

typedef struct Camera {
    rt_float4 camera_to_world[3];
    float screen[4];        /* ScreenWindow left, right, bottom, top */
    float clip_near, clip_far;
    float tan_half_fov; /* perspective: scale from screen window to the z=1 plane */
    uint32_t perspective;   /* 1 perspective, 0 orthographic */
    int32_t width, height;  /* Format */
    int32_t spp_x, spp_y;   /* PixelSamples */
    float lens_radius;      /* DepthOfField: focallength / (2 fstop); 0 = pinhole */
    float focal_distance;   /* camera-space z of the plane in focus */
    float shutter[2];       /* Shutter open, close: each sample's time is uniform in it */
    /* A moving camera (MotionBegin around the camera transform): camera_to_world is the
     * placement at motion_times[0], this one at motion_times[1], and `between` keys
     * between them at between_times; interpolated linearly from key to key */
    rt_float4 camera_to_world_end[3];
    float motion_times[2];
    uint32_t moving;
    uint32_t between;
    rt_float4 camera_to_world_between[RT_CAMERA_MAX_BETWEEN][3];
    float between_times[RT_CAMERA_MAX_BETWEEN];
    /* PixelFilter, by filter importance sampling (host/scene/pixel_filter.h): a sample's
     * place about its pixel's centre is drawn from the filter's |f|, so each pixel is the
     * plain mean of its samples. With filter_table 0 the place is uniform over a box of
     * filter_width pixels. Else along axis a it is filter_icdf[a] at u * RT_FILTER_TABLE
     * (linear between entries: the inverse of the cumulative |f|), a sample in a cell
     * where the filter is negative counts negatively (its sign: filter_negative_start[a]
     * at u = 0, flipped at each u of filter_flips[a], 2 past the last), and every sample
     * weighs filter_weight (the integral of |f| over that of f, per axis). */
    float filter_width[2];
    float filter_weight;
    uint32_t filter_table;
    uint32_t filter_negative_start[2];
    uint32_t filter_pad[2];
    float filter_icdf[2][RT_FILTER_TABLE + 4]; /* RT_FILTER_TABLE + 1 used */
    float filter_flips[2][RT_FILTER_FLIPS];
} Camera;

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(Triangle, 48);
RT_ASSERT_SIZE(Triangle4, 160);
RT_ASSERT_SIZE(TriangleAttr, 16);
RT_ASSERT_SIZE(Material, 48);
RT_ASSERT_SIZE(Camera, 176 + RT_CAMERA_MAX_BETWEEN * (48 + 4) + 32 +
                           2 * (RT_FILTER_TABLE + 4) * 4 + 2 * RT_FILTER_FLIPS * 4);
#endif
#endif
