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

__kernel void generate_eye(__constant Camera* cam,
                           uint count,
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
                           __global float* sample_time, /* RT_HAS_MOTION: in the shutter */
                           __global uint* active_counter) {
    uint k = get_global_id(0);
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
    float jx = j.x, jy = j.y;
    /* raster -> screen window: x grows right, y grows up */
    float sx = cam->screen[0] + ((float)px + jx) / (float)cam->width *
                                    (cam->screen[1] - cam->screen[0]);
    float sy = cam->screen[3] - ((float)py + jy) / (float)cam->height *
                                    (cam->screen[3] - cam->screen[2]);
    float4 o_cam, d_cam;
    float tmin, tmax;
    if (cam->perspective) {
        o_cam = (float4)(0.0f, 0.0f, 0.0f, 1.0f);
        d_cam = rt_normalize3(rt_vec(sx * cam->tan_half_fov, sy * cam->tan_half_fov, 1.0f));
#ifdef RT_HAS_DEPTH_OF_FIELD
        /* thin lens: start on the lens disc, aim at where the pinhole ray meets the plane
         * in focus (uniform disc sampling by the square-root map) */
        float r = cam->lens_radius * sqrt(rt_random(pixel, s, 2));
        float phi = 6.28318531f * rt_random(pixel, s, 3);
        float4 focus = d_cam * (cam->focal_distance / d_cam.z);
        o_cam = (float4)(r * cos(phi), r * sin(phi), 0.0f, 1.0f);
        d_cam = rt_normalize3(focus - o_cam);
#endif
        /* Clipping planes are z distances: convert them to distances along the ray */
        tmin = cam->clip_near / d_cam.z;
        tmax = cam->clip_far / d_cam.z;
    } else {
        o_cam = (float4)(sx, sy, 0.0f, 1.0f);
        d_cam = rt_vec(0.0f, 0.0f, 1.0f);
        tmin = cam->clip_near;
        tmax = cam->clip_far;
    }
    float4 r0 = cam->camera_to_world[0], r1 = cam->camera_to_world[1],
           r2 = cam->camera_to_world[2];
#ifdef RT_HAS_MOTION
    const float time = mix(cam->shutter[0], cam->shutter[1], rt_random(pixel, s, 4));
    if (cam->moving) { /* the camera's placement at the sample's time */
        float t0 = cam->motion_times[0], t1 = cam->motion_times[1];
        float a = t1 > t0 ? clamp((time - t0) / (t1 - t0), 0.0f, 1.0f) : 0.0f;
        r0 = mix(r0, cam->camera_to_world_end[0], a);
        r1 = mix(r1, cam->camera_to_world_end[1], a);
        r2 = mix(r2, cam->camera_to_world_end[2], a);
    }
#endif
    float4 o = (float4)(dot(r0, o_cam), dot(r1, o_cam), dot(r2, o_cam), 0.0f);
    float4 dw = (float4)(rt_dot3(r0, d_cam), rt_dot3(r1, d_cam), rt_dot3(r2, d_cam), 0.0f);
    /* the world direction is renormalised, so camera-space distances grow by its length */
    float len = sqrt(rt_dot3(dw, dw));
    float4 d = dw / len;
    o.w = tmin * len;
    d.w = tmax * len;
    origin[i] = o;
    direction[i] = d;
    weight[i] = (rt_weight)(1.0f);
    /* an eye ray's footprint: a pixel wide where an orthographic ray starts; a
     * perspective one starts as a point and widens by RT_PIXEL_SPREAD per unit */
    float width = cam->perspective ? 0.0f : (cam->screen[1] - cam->screen[0]) / (float)cam->width * len;
    RayState st = {1u, 0u, RT_NO_HIT, width};
    state[i] = st;
    ray_sample[i] = slot;
#ifdef RT_HAS_MOTION
    sample_time[slot] = time;
#endif
    total[slot].value = (float4)(0.0f);
#ifdef RT_HAS_AOVS
    /* camera z per unit of world ray distance: the unit camera direction's z over len */
    SampleAov a = {(float4)(0.0f), d_cam.z / len, 0u, {0u, 0u}};
    aov[slot] = a;
#endif
}
