/* generate_eye.cl: the refill stage. New eye samples fill the free end of the ray pool:
 * new sample i is sample new_sample[2i + 1] of pixel new_sample[2i] (the host's sample
 * plan, one upload),
 * its eye ray goes to pool slot ray_offset + i and its record to sample slot
 * (slot_base + i) modulo slot_capacity, placed in the pixel by the pixel's random
 * sequence (rng.clh), never by where it lands. Its running total starts at zero and its
 * count of rays in flight at one. */
#include "counters.clh"
#include "math.clh"
#include "rng.clh"
#include "film.h"
#include "ray.h"
#include "scene_types.h"

/* A place along one axis from the filter's inverse cumulative table (Camera::filter_icdf),
 * linear between entries; where the filter is negative the sample's weight changes sign
 * (the same trip count in every work-item). */
inline float rt_filter_place(__constant Camera* cam, int axis, float u, float* weight) {
    int negative = (int)cam->filter_negative_start[axis];
    for (int f = 0; f < RT_FILTER_FLIPS; ++f) negative ^= u >= cam->filter_flips[axis][f];
    if (negative) *weight = -*weight;
    const float x = clamp(u, 0.0f, 1.0f) * (float)RT_FILTER_TABLE;
    const int k = min((int)x, RT_FILTER_TABLE - 1);
    return mix(cam->filter_icdf[axis][k], cam->filter_icdf[axis][k + 1], x - (float)k);
}

__kernel void generate_eye(__constant Camera* cam,
                           uint count, /* ~0u: fit[1], what fit_refill found fits */
                           __global const uint* fit,
                           uint ray_offset,
                           uint slot_base,
                           uint slot_capacity,
                           __global const uint* new_sample, /* (pixel, index) pairs */
                           __global uint* sample_pixel, /* per sample slot */
                           __global uint* sample_index,
                           __global uint* slot_rays,
                           __global uint* slot_abort,
                           __global float4* origin,      /* xyz, w = tmin */
                           __global float4* direction,   /* xyz, w = tmax */
                           __global rt_weight* weight,
                           __global RayState* state,
                           __global uint* ray_sample,
                           __global SampleTotal* total,
                           __global SampleAov* aov, /* used with RT_HAS_AOVS */
                           __global float* aov_values, /* RT_SHADER_AOVS a slot */
                           __global float* sample_time, /* RT_HAS_MOTION: in the shutter */
                           __global uint* active_counter) {
    uint k = get_global_id(0);
    if (count == ~0u) count = fit[1];
    RT_COUNT_RANGE(active_counter, count);
    if (k >= count) return;
    const uint pixel = new_sample[2 * k], s = new_sample[2 * k + 1];
    const uint slot = rt_ring_add(slot_base, k, slot_capacity), i = ray_offset + k;
    sample_pixel[slot] = pixel;
    sample_index[slot] = s;
    slot_rays[slot] = 1u;
    slot_abort[slot] = 0u;
    int px = (int)(pixel % (uint)cam->width), py = (int)(pixel / (uint)cam->width);
    float2 j = rt_pixel_sample(pixel, s);
    /* PixelFilter by importance: the sample's place about the pixel's centre drawn from
     * the filter (Camera::filter_*), its weight the filter's sign times filter_weight */
    float jx, jy, filter_w = 1.0f;
    if (cam->filter_table == 2u) {
        /* a radial filter (disk, bessel): the distance from the table, the angle uniform,
         * stretched along y as the filter is */
        float r = rt_filter_place(cam, 0, j.x, &filter_w), c, sn = sincos(6.28318531f * j.y, &c);
        jx = 0.5f + r * c;
        jy = 0.5f + r * sn * (cam->filter_width[1] / cam->filter_width[0]);
        filter_w *= cam->filter_weight;
    } else if (cam->filter_table) {
        jx = 0.5f + rt_filter_place(cam, 0, j.x, &filter_w);
        jy = 0.5f + rt_filter_place(cam, 1, j.y, &filter_w);
        filter_w *= cam->filter_weight;
    } else {
        /* (a box a pixel wide: the sample's own place, bit for bit) */
        jx = cam->filter_width[0] == 1.0f ? j.x : 0.5f + (j.x - 0.5f) * cam->filter_width[0];
        jy = cam->filter_width[1] == 1.0f ? j.y : 0.5f + (j.y - 0.5f) * cam->filter_width[1];
    }
    /* raster -> screen window: x grows right, y grows up */
    float sx = cam->screen[0] + ((float)px + jx) / (float)cam->width *
                                    (cam->screen[1] - cam->screen[0]);
    float sy = cam->screen[3] - ((float)py + jy) / (float)cam->height *
                                    (cam->screen[3] - cam->screen[2]);
    /* (scalars, no private array and scalar stores: PoCL keeps a work-item's private
     * arrays in memory, its context; the float4 form with the camera matrix in an array
     * took 1.2-1.4x the time, `ab_binaries.sh ... generate_eye`, same images, and float4
     * and struct stores of the scalar results 1.4x) */
    float ox, oy, oz, dx, dy, dz, tmin, tmax;
    if (cam->perspective) {
        ox = oy = oz = 0.0f;
        float vx = sx * cam->tan_half_fov, vy = sy * cam->tan_half_fov, vz = 1.0f;
        float len2 = vx * vx + vy * vy + vz * vz;
        float inv = len2 > 0.0f ? rsqrt(len2) : 0.0f;
        dx = vx * inv, dy = vy * inv, dz = vz * inv;
#ifdef RT_HAS_DEPTH_OF_FIELD
        /* thin lens: start on the lens disc, aim at where the pinhole ray meets the plane
         * in focus (uniform disc sampling by the square-root map) */
        const float2 lens = rt_random2(pixel, s, 1u); /* dimensions 2 and 3 */
        float r = cam->lens_radius * sqrt(lens.x);
        float phi = 6.28318531f * lens.y;
        float f = cam->focal_distance / dz;
        float fx = dx * f, fy = dy * f, fz = dz * f;
        ox = r * cos(phi), oy = r * sin(phi);
        vx = fx - ox, vy = fy - oy, vz = fz - oz;
        len2 = vx * vx + vy * vy + vz * vz;
        inv = len2 > 0.0f ? rsqrt(len2) : 0.0f;
        dx = vx * inv, dy = vy * inv, dz = vz * inv;
#endif
        /* Clipping planes are z distances: convert them to distances along the ray */
        tmin = cam->clip_near / dz;
        tmax = cam->clip_far / dz;
    } else {
        ox = sx, oy = sy, oz = 0.0f;
        dx = 0.0f, dy = 0.0f, dz = 1.0f;
        tmin = cam->clip_near;
        tmax = cam->clip_far;
    }
    __constant float* c2w = (__constant float*)cam->camera_to_world;
    float m00 = c2w[0], m01 = c2w[1], m02 = c2w[2], m03 = c2w[3];
    float m10 = c2w[4], m11 = c2w[5], m12 = c2w[6], m13 = c2w[7];
    float m20 = c2w[8], m21 = c2w[9], m22 = c2w[10], m23 = c2w[11];
#ifdef RT_HAS_MOTION
    const float time = mix(cam->shutter[0], cam->shutter[1], rt_random(pixel, s, 4));
    if (cam->moving) { /* the camera's placement at the sample's time */
        float t0 = cam->motion_times[0], t1 = cam->motion_times[1];
        __constant float* e = (__constant float*)cam->camera_to_world_end;
        /* the keys around it (as motion.clh picks them; the same trip count in every
         * work-item, no break) */
        int found = 0;
        for (uint k = 0; k < cam->between; ++k) {
            __constant float* b = (__constant float*)cam->camera_to_world_between[k];
            const float tk = cam->between_times[k];
            if (!found && time >= tk) {
                t0 = tk;
                m00 = b[0], m01 = b[1], m02 = b[2], m03 = b[3], m10 = b[4], m11 = b[5];
                m12 = b[6], m13 = b[7], m20 = b[8], m21 = b[9], m22 = b[10], m23 = b[11];
            } else if (!found) {
                t1 = tk;
                e = b;
                found = 1;
            }
        }
        float a = t1 > t0 ? clamp((time - t0) / (t1 - t0), 0.0f, 1.0f) : 0.0f;
        m00 = mix(m00, e[0], a), m01 = mix(m01, e[1], a), m02 = mix(m02, e[2], a);
        m03 = mix(m03, e[3], a), m10 = mix(m10, e[4], a), m11 = mix(m11, e[5], a);
        m12 = mix(m12, e[6], a), m13 = mix(m13, e[7], a), m20 = mix(m20, e[8], a);
        m21 = mix(m21, e[9], a), m22 = mix(m22, e[10], a), m23 = mix(m23, e[11], a);
    }
#endif
    const float wox = m00 * ox + m01 * oy + m02 * oz + m03,
                woy = m10 * ox + m11 * oy + m12 * oz + m13,
                woz = m20 * ox + m21 * oy + m22 * oz + m23;
    const float wdx = m00 * dx + m01 * dy + m02 * dz, wdy = m10 * dx + m11 * dy + m12 * dz,
                wdz = m20 * dx + m21 * dy + m22 * dz;
    /* the world direction is renormalised, so camera-space distances grow by its length */
    float len = sqrt(wdx * wdx + wdy * wdy + wdz * wdz);
    __global float* o = (__global float*)(origin + i);
    __global float* d = (__global float*)(direction + i);
    o[0] = wox, o[1] = woy, o[2] = woz, o[3] = tmin * len;
    d[0] = wdx / len, d[1] = wdy / len, d[2] = wdz / len, d[3] = tmax * len;
    __global float* w = (__global float*)(weight + i);
    for (int c = 0; c < (int)(sizeof(rt_weight) / sizeof(float)); ++c) w[c] = filter_w;
    /* an eye ray's footprint: a pixel wide where an orthographic ray starts; a
     * perspective one starts as a point and widens by RT_PIXEL_SPREAD per unit */
    state[i].alive = 1u;
    state[i].depth = 0u;
    state[i].from_prim = RT_NO_HIT;
    state[i].width =
        cam->perspective ? 0.0f : (cam->screen[1] - cam->screen[0]) / (float)cam->width * len;
    ray_sample[i] = slot;
#ifdef RT_HAS_MOTION
    sample_time[slot] = time;
#endif
    __global float* tot = (__global float*)(total + slot);
    tot[0] = tot[1] = tot[2] = tot[3] = 0.0f;
#ifdef RT_HAS_AOVS
    /* camera z per unit of world ray distance: the unit camera direction's z over len */
    aov[slot].normal = (float4)(0.0f);
    aov[slot].z = dz / len;
    aov[slot].hit = 0u;
    aov[slot].shaded = 0u;
#endif
#ifdef RT_SHADER_AOVS
    for (uint a = 0; a < RT_SHADER_AOVS; ++a) aov_values[slot * RT_SHADER_AOVS + a] = 0.0f;
#endif
}

/* A refill queued before the round's wait (so that the device works on while the host
 * wakes up) does not know how many rays the round spawned: this counts them (close_round's
 * sums per group) and finds how many of the staged jobs fit within round_cap beside them
 * and the rays the pool takes back from the spill stack, as the host would (with no ray
 * held, one job whatever the cap). fit = {jobs, their samples, rays spawned};
 * generate_eye and compact_scatter read the samples, the host all three after its wait.
 * One work-group. */
__kernel __attribute__((reqd_work_group_size(RT_COMPACT_GROUP, 1, 1)))
void fit_refill(uint groups, __global const uint* group_live,
                uint capacity, /* the pool */
                uint spill_top, uint jobs,
                __global const uint* ends, /* increasing */
                uint round_cap, __global uint* fit, __global uint* active_counter) {
    __local uint part[RT_COMPACT_GROUP];
    const uint lid = get_local_id(0);
    RT_COUNT_RANGE(active_counter, 1u);
    uint sum = 0;
    for (uint g = lid; g < groups; g += RT_COMPACT_GROUP) sum += group_live[g];
    part[lid] = sum;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (lid != 0) return;
    uint spawned = 0;
    for (uint k = 0; k < RT_COMPACT_GROUP; ++k) spawned += part[k];
    const uint held = spawned < capacity ? spawned + min(capacity - spawned, spill_top) : spawned;
    uint lo = 0, hi = jobs; /* jobs [0, lo) fit; none past hi does */
    while (lo < hi) {
        const uint mid = (lo + hi + 1u) / 2u;
        if (held <= round_cap && ends[mid - 1u] <= round_cap - held) lo = mid;
        else hi = mid - 1u;
    }
    if (lo == 0 && held == 0 && jobs > 0) lo = 1;
    fit[0] = lo;
    fit[1] = lo > 0 ? ends[lo - 1u] : 0u;
    fit[2] = spawned;
}
