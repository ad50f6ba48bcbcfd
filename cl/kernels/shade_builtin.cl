/* shade_builtin.cl: the shade stage, for now a built-in stand-in for the standard RSL
 * "constant", "matte" and "plastic" surfaces lit by "ambientlight", "distantlight" and
 * "pointlight". It follows the fire-and-forget rule of DESIGN.md section 4: what needs no
 * ray (emission, ambient) is added to the sample at once; each light's diffuse/specular
 * coefficient times Cl becomes the weight of a shadow ray, added only if the ray reaches
 * the light; Oi < 1 continues the ray straight on with weight (1 - Oi). rsl2cl output
 * replaces this file (issue 4); it must not grow. */
#include "atomics.clh"
#include "counters.clh"
#include "math.clh"
#include "film.h"
#include "ray.h"
#include "scene_types.h"


__kernel void shade(uint count,
                    __global const Triangle* tris,
                    __global const TriangleAttr* attrs,
                    __global const float4* normals, /* 3 per smooth triangle */
                    __global const Material* materials,
                    __global const Light* lights,
                    uint light_count,
                    __global const float4* origin,
                    __global const float4* direction,
                    __global const float4* weight,
                    __global const RayState* state,
                    __global const uint* ray_sample,
                    __global const RayHit* hits,
                    __global SampleTotal* total,
                    __global float4* next_origin, /* the ray's continuation, slot i */
                    __global float4* next_direction,
                    __global float4* next_weight,
                    __global RayState* next_state,
                    __global uint* next_sample,
                    __global float4* shadow_origin, /* slot i * light_count + light */
                    __global float4* shadow_direction,
                    __global float4* shadow_weight,
                    __global RayState* shadow_state,
                    __global SampleAov* aov, /* used with RT_HAS_AOVS */
                    __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint i = get_global_id(0);
    int alive = i < count && state[i].alive;
    RT_COUNT_ACTIVE(active_counter, alive && hits[i].prim != RT_NO_HIT);
    if (i >= count) return;
    next_state[i].alive = 0u;
    for (uint l = 0; l < light_count; ++l) shadow_state[i * light_count + l].alive = 0u;
    if (!alive) return;
    RayHit h = hits[i];
    if (h.prim == RT_NO_HIT) return;
    uint sample = ray_sample[i];
    float4 d = direction[i], w = weight[i];
    __global const Triangle* tri = &tris[h.prim];
    TriangleAttr attr = attrs[h.prim];
    Material m = materials[attr.material];
    float b0 = 1.0f - h.u - h.v;
    float4 P = b0 * tri->v0 + h.u * tri->v1 + h.v * tri->v2;
    P.w = 0.0f;
    float4 Ng = rt_normalize3(rt_cross3(tri->v1 - tri->v0, tri->v2 - tri->v0));
    float4 N = Ng;
#ifdef RT_HAS_SMOOTH_NORMALS
    if (attr.has_normals) {
        float4 n = b0 * normals[3 * h.prim] + h.u * normals[3 * h.prim + 1] +
                   h.v * normals[3 * h.prim + 2];
        N = rt_normalize3(n);
        if (rt_dot3(N, N) == 0.0f) N = Ng;
    }
#endif
    /* faceforward(N, I) with Ng as reference, as RSL defines it */
    float facing = rt_dot3(d, Ng) < 0.0f ? 1.0f : -1.0f;
    float4 Nf = facing * N, Ngf = facing * Ng;
#ifdef RT_HAS_AOVS
    if (!aov[sample].hit) {
        aov[sample].z *= h.t;
        aov[sample].normal = Nf;
        aov[sample].hit = 1u;
    }
#endif
    float4 V = -d;
    V.w = 0.0f;
    if (m.flags & RT_MATERIAL_MATTE) return; /* holdout: opaque, black, no alpha */
    float4 os = m.os, cs = m.cs;
    float4 emitted = (float4)(0.0f);
    if (m.shader == RT_SHADER_CONSTANT) {
        emitted = os * cs;
    } else {
        float4 ambient = (float4)(0.0f);
        for (uint l = 0; l < light_count; ++l)
            if (lights[l].type == RT_LIGHT_AMBIENT) ambient += lights[l].color;
        emitted = os * cs * m.ka * ambient;
    }
    float4 add = w * emitted;
    add.w = w.w * os.w; /* coverage: what this surface hides of what lies behind it */
    rt_atomic_add_float4(&total[sample].value, add);

#ifdef RT_HAS_SHADOW_RAYS
    if (m.shader != RT_SHADER_CONSTANT) {
        float4 Pofs = rt_offset_ray(P, Ngf);
        for (uint l = 0; l < light_count; ++l) {
            Light lt = lights[l];
            if (lt.type == RT_LIGHT_AMBIENT) continue;
            float4 L;
            float dist;
            float4 Cl = lt.color;
            if (lt.type == RT_LIGHT_DISTANT) {
                L = -lt.direction;
                dist = INFINITY;
            } else {
                L = lt.position - P;
                float d2 = rt_dot3(L, L);
                dist = sqrt(d2);
                Cl = Cl / d2;
                L = L / dist;
            }
            L.w = 0.0f;
            float ndotl = rt_dot3(Nf, L);
            if (ndotl <= 0.0f) continue; /* illuminance cone: the hemisphere around Nf */
            float4 coef = m.kd * cs * ndotl;
            if (m.shader == RT_SHADER_PLASTIC) {
                float4 H = rt_normalize3(L + V);
                float spec = pow(fmax(0.0f, rt_dot3(Nf, H)), 1.0f / m.roughness);
                coef += m.specularcolor * m.ks * spec;
            }
            float4 sw = w * os * coef * Cl;
            sw.w = 0.0f;
            if (rt_max3(sw) <= 0.0f) continue;
            uint j = i * light_count + l;
            float4 so = Pofs;
            so.w = 0.0f;
            /* stop short of a point light: it is not geometry, nothing beyond it shadows */
            float4 sd = L;
            sd.w = isinf(dist) ? INFINITY : dist * (1.0f - 1e-5f);
            shadow_origin[j] = so;
            shadow_direction[j] = sd;
            shadow_weight[j] = sw;
            RayState ss = {1u, 0u, h.prim, 0u};
            shadow_state[j] = ss;
        }
    }
#endif

#ifdef RT_HAS_TRANSPARENCY
    /* Oi < 1: the same ray continues behind the surface with the transmitted weight */
    float4 wt = w * ((float4)(1.0f) - os);
    uint depth = state[i].depth + 1;
    if (rt_max3(wt) > 1e-6f && depth < RT_MAX_TRANSPARENT_DEPTH) {
        float4 o = rt_offset_ray(P, -Ngf);
        o.w = 0.0f;
        next_origin[i] = o;
        d.w = d.w - h.t;
        next_direction[i] = d;
        next_weight[i] = wt;
        RayState st = {1u, depth, h.prim, 0u};
        next_state[i] = st;
        next_sample[i] = sample;
    }
#endif
}

/* Adds every shadow ray that reached its light into its sample: ray i owns the slots
 * i * light_count + l and adds their sum once (one atomic per ray, not per light). */
__kernel void accumulate_shadows(uint count, uint light_count,
                                 __global const uint* ray_sample,
                                 __global const float4* shadow_weight,
                                 __global RayState* shadow_state,
                                 __global SampleTotal* total,
                                 __global uint* active_counter) {
    RT_DECLARE_ACTIVE_COUNTER;
    uint i = get_global_id(0);
    RT_COUNT_ACTIVE(active_counter, i < count);
    if (i >= count) return;
    float4 sum = (float4)(0.0f);
    for (uint l = 0; l < light_count; ++l) {
        uint j = i * light_count + l;
        if (shadow_state[j].alive) {
            sum += shadow_weight[j];
            shadow_state[j].alive = 0u;
        }
    }
    rt_atomic_add_float4(&total[ray_sample[i]].value, sum);
}
