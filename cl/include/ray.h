/* ray.h: the AR250 ray record as the device ray pool holds it, structure of arrays: one
 * buffer per field so a kernel touches only the fields it needs. A pool slot i holds
 * the ray of sample i (its eye ray, then its continuation through transparent surfaces);
 * shadow rays live in a second pool, slot i * light_count + light. */
#ifndef RT_RAY_H
#define RT_RAY_H
#include "compat.h"

/* origin: xyz, w = tmin.  direction: xyz (unit), w = tmax.
 * weight: the colour channels, then the alpha (coverage) weight. Under ColorSamples 1
 * (RSL_COLOR_SAMPLES == 1) two floats, the channel and alpha; with more than three
 * channels (RSL_COLOR_LANES 8 or 16) the scene's colour vector, alpha in its last lane;
 * otherwise four, up to three channels in xyz (lanes past the scene's repeat its last)
 * and alpha in w. Shading works on colour vectors (ray_weight.clh). */
#ifdef __OPENCL_C_VERSION__
#if defined(RSL_COLOR_SAMPLES) && RSL_COLOR_SAMPLES == 1
typedef float2 rt_weight;
#elif defined(RSL_COLOR_LANES) && RSL_COLOR_LANES == 8
typedef float8 rt_weight;
#elif defined(RSL_COLOR_LANES) && RSL_COLOR_LANES == 16
typedef float16 rt_weight;
#else
typedef float4 rt_weight;
#endif
#endif

typedef struct RayHit {
    float t, u, v;  /* distance and barycentrics of the closest hit */
    uint32_t prim;  /* triangle index, RT_NO_HIT on a miss */
} RayHit;

/* Per-ray state word: alive flag, depths, fromSurface (the primitive the ray left,
 * skipped by the intersector so a ray never hits the surface it started on), and the
 * ray's footprint where it starts (its width, world units: a ray cone whose spread is
 * the scene's pixel angle RT_PIXEL_SPREAD; written only when shaders take derivatives). */
typedef struct RayState {
    uint32_t alive;
    uint32_t depth;     /* bits 0-12: trace() depth; 13: RT_DIFFUSE_BOUNCED; 14, 15:
                         * RT_COMPOSITES_AOVS, RT_CARRIES_AOVS; 16-31: transparent
                         * surfaces passed */
    uint32_t from_prim; /* RT_NO_HIT for eye rays */
    float width;
} RayState;

#define RT_TRACE_DEPTH(s) ((s).depth & 0x1fffu) /* (at most 4096) */
/* The ray's path went through a diffuse bounce (an indirectdiffuse() ray): with
 * RT_MAX_DIFFUSE_DEPTH 1 its hits send no more diffuse rays */
#define RT_DIFFUSE_BOUNCED 0x2000u
#define RT_TRANSPARENT_DEPTH(s) ((s).depth >> 16)
#define RT_ONE_TRANSPARENT 0x10000u
/* The ray brings back part of its sample's shader AOVs (ray_aovs.clh): its AOV weights
 * wait in the pool's AOV payload. */
#define RT_CARRIES_AOVS 0x8000u
/* A camera ray behind a surface that gave the sample's AOVs: the next surface it is
 * shaded at adds its own, scaled by what the payload says the ones in front let through.
 */
#define RT_COMPOSITES_AOVS 0x4000u
#define RT_AOV_FLAGS (RT_CARRIES_AOVS | RT_COMPOSITES_AOVS)

#define RT_NO_HIT 0xffffffffu

/* RayState::alive of a traced ray that only asks whether it escapes (occlusion()): its
 * weight goes to its sample when it meets nothing within its reach, and what it meets is
 * not shaded (classify_hits) */
#define RT_ALIVE_VISIBILITY 3u
/* ... and one that asks how far it goes (gather()'s "ray:length"): its weight times the
 * distance to what it meets goes to its sample, nothing when it escapes; never shaded */
#define RT_ALIVE_DISTANCE 5u
/* ... and a traced ray of indirectdiffuse(): shaded like any, but it sees the surfaces
 * visible to diffuse rays (RT_MATERIAL_NO_DIFFUSE), as occlusion()'s do */
#define RT_ALIVE_DIFFUSE 7u
/* ... and a shadow ray that met a surface whose shader says what it lets through
 * (RT_MATERIAL_SHADER_SHADOW, RT_SHADER_SHADOWS): the surface's shade kernel takes its
 * Oi and sends the rest of the way on as a shadow ray again; its weight goes to its
 * sample when it meets nothing short of its light */
#define RT_ALIVE_SHADOW 9u
/* A shadow ray's RayState::alive as intersect_shadow hands it over to the pool as such
 * a ray (its sample in `width`'s bits); the compaction moves it there. */
#define RT_SHADOW_HANDOFF 2u

/* Compaction works on groups of this many traced rays (close_round.cl, compact.cl); the
 * host sizes its per-group counts by it. */
#define RT_COMPACT_GROUP 64

/* The packet kernels' work-items take this many rays each (cl/lib/packet_traverse.clh):
 * intersect_shadow with RT_SHADOW_PACKETS the rays to one light from consecutive shaded
 * rays, intersect_closest with RT_CLOSEST_PACKETS consecutive rays. */
#define RT_PACKET_RAYS 8

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(RayHit, 16);
RT_ASSERT_SIZE(RayState, 16);
#endif
#endif
