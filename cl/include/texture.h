/* texture.h: textures on the device (issue 9). Every texture of the scene is a tiled
 * mip-map of float RGBA texels; its tiles (RT_TEX_TILE x RT_TEX_TILE texels) live in a
 * fixed-size tile cache, found through a page table: one entry per tile of every level,
 * the cache slot holding it or RT_TEX_ABSENT. A lookup that meets an absent tile asks the
 * host for it (a TexRequest) and the shading point is shaded again once it is there. */
#ifndef RT_TEXTURE_H
#define RT_TEXTURE_H
#include "compat.h"

#define RT_TEX_TILE 32
#define RT_TEX_TILE_TEXELS (RT_TEX_TILE * RT_TEX_TILE)
#define RT_TEX_MAX_LEVELS 16
#define RT_TEX_ABSENT 0xffffffffu

/* wrap modes (RI MakeTexture swrap/twrap) */
#define RT_WRAP_BLACK 0u
#define RT_WRAP_PERIODIC 1u
#define RT_WRAP_CLAMP 2u

/* TexInfo.flags */
#define RT_TEX_BROKEN 1u    /* not found or unreadable: lookups give the default */
#define RT_TEX_LATLONG 2u   /* a lat-long environment map */
#define RT_TEX_SHADOW 4u    /* a depth map with its light's projection */

typedef struct TexInfo {
    uint32_t width, height;   /* level 0 */
    uint32_t levels;          /* mip levels, each half the one before (at least 1x1) */
    uint32_t channels;        /* 1..4 */
    uint32_t wrap_s, wrap_t;  /* RT_WRAP_* */
    uint32_t flags;           /* RT_TEX_* */
    uint32_t page_base;       /* this texture's first page table entry */
    uint32_t level_page[RT_TEX_MAX_LEVELS];   /* a level's first entry, from page_base */
    uint32_t level_tiles_x[RT_TEX_MAX_LEVELS]; /* tiles across a level */
    /* RT_TEX_SHADOW: the columns of the light's "worldtoscreen" and "worldtocamera"
     * matrices (row vectors: p' = p M, so output j = dot(p, column j)) */
    rt_float4 world_to_screen[4];
    rt_float4 world_to_camera[4];
} TexInfo;

/* One tile a lookup asked for: texture index, and (level << 24 | ty << 12 | tx). */
typedef struct TexRequest {
    uint32_t tex;
    uint32_t tile;
} TexRequest;

#define RT_TEX_TILE_CODE(level, tx, ty) (((uint32_t)(level) << 24) | ((uint32_t)(ty) << 12) | (uint32_t)(tx))

#ifndef __OPENCL_C_VERSION__
RT_ASSERT_SIZE(TexInfo, 32 + 128 + 128);
RT_ASSERT_SIZE(TexRequest, 8);
#endif
#endif
