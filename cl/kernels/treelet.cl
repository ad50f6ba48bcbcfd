/* treelet.cl: the treelet-streamed trace stage (DESIGN.md section 3, issue 5), built only
 * with RT_HAS_TREELETS (host/render/treelet_trace.h drives it). A round runs
 * treelet_closest or treelet_shadow over the queued (ray, treelet) pairs, grouped by
 * treelet (treelet_scatter, from the per-treelet counts the round before left); rays
 * entering other treelets are queued for the next round. The first round
 * (treelet_closest_root, treelet_shadow_root) takes the rays themselves into the root
 * treelet. After the last round treelet_resolve turns each ray's closest-hit key into
 * its RayHit, recomputing u, v for the winning triangle or object. Shadow rays of scenes
 * with surfaces that let light through walk them a layer a trace, as intersect_shadow
 * does: treelet_shadow_walk_begin, then per layer a closest-hit trace
 * (treelet_walk_root, treelet_walk, treelet_resolve) and treelet_shadow_walk_step. */
#ifdef RT_HAS_TREELETS
#include "counters.clh"
#include "ray.h"
#include "transmittance.clh"
#include "treelet_traverse.clh"

/* The pair work-item i handles: in the first round (root_only) ray i in the root
 * treelet, else pairs[first + i]. Returns 0 when there is none or the ray is dead. */
inline int rt_treelet_pair(uint i, uint first, uint count, uint root_only,
                           __global const TreeletPair* pairs, __global const RayState* state,
                           TreeletPair* p) {
    if (i >= count) return 0;
    if (root_only) {
        p->ray = i;
        p->treelet = 0u;
        p->tnear = -INFINITY;
    } else {
        *p = pairs[first + i];
    }
    return state[p->ray].alive != 0u;
}
inline int rt_treelet_pair_live(uint i, uint first, uint count, uint root_only,
                                __global const TreeletPair* pairs,
                                __global const RayState* state) {
    TreeletPair p;
    return rt_treelet_pair(i, first, count, root_only, pairs, state, &p);
}

/* One (ray, treelet) pair, closest hit: the ray's key lowered to the best hit found. */
inline void rt_treelet_closest(TreeletPair p, uint root_only, __global const TreeletRef* refs,
                               __global const RT_BVH_NODE* nodes, __global const Triangle4* blocks,
                               __global const float4* origin, __global const float4* direction,
                               __global const RayState* state, __global ulong* keys,
                               __global TreeletPair* next, uint next_cap,
                               __global uint* counters, uint treelets, uint resident_links
                               RT_TL_OBJECTS_PARAM) {
    float4 o = origin[p.ray], d = direction[p.ray];
    ulong key = root_only ? RT_NO_KEY : keys[p.ray];
    const ulong before = key;
    /* entered behind the best hit: nothing in this treelet can be nearer (rt_beyond: the
     * entry distance may come out a little beyond a hit on the box's face; unpadded, SPD
     * gears lost triangles 1 ulp nearer than the hit at 30 of its pixels) */
    if (rt_beyond(p.tnear, rt_key_t(key, d.w))) return;
    rt_treelet_traverse(refs, p.treelet, nodes, blocks, resident_links, o, d, o.w, d.w,
                        state[p.ray].from_prim, 0, &key, p.ray, next, next_cap, counters,
                        treelets RT_TL_OBJECTS_ARG);
    if (root_only) keys[p.ray] = key; /* the ray's only pair this round */
    else if (key < before) rt_key_min((volatile __global ulong*)&keys[p.ray], key);
}

/* One pair, any hit: an occluded ray's weight is zeroed (as intersect_shadow does; its
 * state stays as the group count read it), and its other queued pairs are skipped. */
inline void rt_treelet_shadow(TreeletPair p, __global const TreeletRef* refs,
                              __global const RT_BVH_NODE* nodes, __global const Triangle4* blocks,
                              __global const float4* origin, __global const float4* direction,
                              __global const RayState* state, __global rt_weight* weight,
                              __global TreeletPair* next, uint next_cap, __global uint* counters,
                              uint treelets, uint resident_links RT_TL_OBJECTS_PARAM) {
    /* (an occluder met through another of its pairs, or a ray that carries nothing) */
    if (!any(weight[p.ray] != (rt_weight)(0.0f))) return;
    float4 o = origin[p.ray], d = direction[p.ray];
    ulong key = RT_NO_KEY;
    if (rt_treelet_traverse(refs, p.treelet, nodes, blocks, resident_links, o, d, o.w, d.w,
                            state[p.ray].from_prim, 1, &key, p.ray, next, next_cap, counters,
                            treelets RT_TL_OBJECTS_ARG))
        weight[p.ray] = (rt_weight)(0.0f);
}

/* What object blocks need (RT_HAS_QUADRICS; placeholders otherwise): the object scene
 * and each ray's shutter time, from its sample (shadow ray i: shaded ray i / light_count). */
#define RT_TL_SCENE_PARAMS                                                                 \
    __global const Quadric *quadrics, __global const uint *csg, __global const Triangle *tris, \
        __global const float4 *quadric_motion, __global const Triangle *tris_end,           \
        __global const uint *ray_sample, __global const float *sample_time, uint light_count
#ifdef RT_HAS_QUADRICS
#ifdef RT_HAS_MOTION
#define RT_TL_TIME(ray) sample_time[ray_sample[(ray) / light_count]]
#else
#define RT_TL_TIME(ray) 0.0f
#endif
#define RT_TL_DECLARE_OBJECTS(ray)                                                          \
    const ObjectScene os = {quadrics, csg, tris, quadric_motion, tris_end, RT_TL_TIME(ray)}; \
    const ObjectScene* objs = &os
#else
#define RT_TL_DECLARE_OBJECTS(ray)
#endif

/* A pair kernel's start: its pair p, counted when its ray is live (else it returns), and
 * the object scene at the ray's time. The count needs no barrier: no pair kernel writes
 * the states it reads (RT_COUNT_GROUP). */
#define RT_TREELET_PAIR_BEGIN_COUNTED(root_only, COUNT)                                   \
    TreeletPair p;                                                                        \
    int active = rt_treelet_pair(get_global_id(0), first, count, root_only, pairs, state, &p); \
    COUNT;                                                                                \
    if (!active) return;                                                                  \
    RT_TL_DECLARE_OBJECTS(p.ray)
#define RT_TREELET_PAIR_BEGIN(root_only)                                                  \
    RT_TREELET_PAIR_BEGIN_COUNTED(root_only,                                              \
        RT_COUNT_GROUP(active_counter, j,                                                 \
                       rt_treelet_pair_live(j, first, count, root_only, pairs, state)))

/* The kernels: *_root is the first round (work-item i: ray i in the root treelet; its
 * active count is the rays traced), the others run a round's queued pairs [first,
 * first + count) (their active count is the pairs). Both take the same arguments, which
 * begin with the pairs, the cut and the rays. */
#define RT_TL_PAIR_PARAMS                                                                  \
    uint first, uint count, __global const TreeletPair *pairs,                            \
        __global const TreeletRef *refs, __global const RT_BVH_NODE *nodes,                \
        __global const Triangle4 *blocks, __global const float4 *origin,                  \
        __global const float4 *direction, __global const RayState *state
/* A pair kernel: its own output buffer (out_param), then the next round's queue, the
 * counters, whether linked treelets in device memory are entered in place
 * (rt_treelet_traverse) and the object scene; its body the pair's work (after
 * RT_TREELET_PAIR_BEGIN). */
#define RT_TREELET_PAIR_KERNEL(name, root_only, out_param, ...)                            \
    __kernel void name(RT_TL_PAIR_PARAMS, out_param, __global TreeletPair* next,          \
                       uint next_cap, __global uint* counters, uint treelets,             \
                       uint resident_links, RT_TL_SCENE_PARAMS,                           \
                       __global uint* active_counter) {                                   \
        RT_TREELET_PAIR_BEGIN(root_only);                                                 \
        __VA_ARGS__;                                                                      \
    }
#define RT_TREELET_CLOSEST_KERNEL(name, root_only)                                         \
    RT_TREELET_PAIR_KERNEL(name, root_only, __global ulong* keys,                         \
                           rt_treelet_closest(p, root_only, refs, nodes, blocks, origin,  \
                                              direction, state, keys, next, next_cap,     \
                                              counters, treelets,                         \
                                              resident_links RT_TL_OBJECTS_ARG))
#define RT_TREELET_SHADOW_KERNEL(name, root_only)                                          \
    RT_TREELET_PAIR_KERNEL(name, root_only, __global rt_weight* weight,                      \
                           rt_treelet_shadow(p, refs, nodes, blocks, origin, direction,   \
                                             state, weight, next, next_cap, counters,     \
                                             treelets, resident_links RT_TL_OBJECTS_ARG))
RT_TREELET_CLOSEST_KERNEL(treelet_closest_root, 1u)
RT_TREELET_CLOSEST_KERNEL(treelet_closest, 0u)
RT_TREELET_SHADOW_KERNEL(treelet_shadow_root, 1u)
RT_TREELET_SHADOW_KERNEL(treelet_shadow, 0u)

#ifdef RT_HAS_TRANSPARENT_SHADOWS
/* The transparent walk's closest-hit traces, named apart so that --stats counts their
 * rays as shadow rays' layers, not as closest-hit rays. */
RT_TREELET_CLOSEST_KERNEL(treelet_walk_root, 1u)
RT_TREELET_CLOSEST_KERNEL(treelet_walk, 0u)

/* The walk's start: each live shadow ray that carries something walks from its own
 * origin, having let everything through so far. (Its active count is the shadow rays.) */
__kernel void treelet_shadow_walk_begin(uint count, __global const float4* origin,
                                        __global const RayState* state,
                                        __global const rt_weight* weight,
                                        __global float4* walk_origin,
                                        __global RayState* walk_state,
                                        __global rt_weight* through,
                                        __global uint* active_counter) {
    uint i = get_global_id(0);
    int active = i < count && state[i].alive;
    RT_COUNT_GROUP(active_counter, j, j < count && state[j].alive);
    if (i >= count) return;
    RayState s = state[i];
    s.alive = active && any(weight[i] != (rt_weight)(0.0f));
    walk_state[i] = s;
    walk_origin[i] = origin[i];
    through[i] = (rt_weight)(1.0f);
}

/* Layer `layer` of the walk (the first 0), after the closest-hit trace of the rays still
 * walking: a ray that met nothing reaches its light with what got through; an opaque
 * surface, or a transparent one at the ray's last layer (as intersect_shadow's loop ends,
 * at the transparent depth `max_depth` counted from the layers the ray passed before:
 * RT_TRANSPARENT_DEPTH), occludes it; past any other it goes on from there (its origin's
 * t and fromSurface moved to the hit), counted in *walking. With RT_SHADER_SHADOWS, a
 * surface whose shader says what gets through takes the ray from the walk as
 * intersect_shadow does: handed to the pool (ray.h RT_SHADOW_HANDOFF) from this layer,
 * with its state, origin's t and weight so far. */
__kernel void treelet_shadow_walk_step(uint count, uint layer, uint max_depth,
                                       __global const RayHit* hits,
                                       __global float4* walk_origin,
                                       __global RayState* walk_state,
                                       __global rt_weight* through, __global rt_weight* weight,
                                       __global float* shadow_aov,
                                       __global const TriangleAttr* attrs,
                                       __global const Material* materials,
                                       __global const float* material_channels,
                                       __global const Quadric* quadrics,
                                       __global uint* walking,
                                       /* RT_SHADER_SHADOWS only: the shadow rays' own
                                        * origins and states, the shaded rays' samples
                                        * (shadow ray i: i / light_count), their rays in
                                        * flight */
                                       __global float4* origin, __global RayState* state,
                                       __global const uint* ray_sample, uint light_count,
                                       __global uint* slot_rays,
                                       __global uint* active_counter) {
    uint i = get_global_id(0);
    int active = i < count && walk_state[i].alive;
    RT_COUNT_GROUP(active_counter, j, j < count && walk_state[j].alive);
    if (!active) return;
    const RayHit h = hits[i];
    rt_weight th = through[i];
    const uint depth = RT_TRANSPARENT_DEPTH(walk_state[i]) + layer;
    int ends = 1, occluded = 0;
    if (h.prim != RT_NO_HIT) {
        const uint mat = rt_shadow_material(h.prim, RT_NO_HIT, attrs, quadrics);
#ifdef RT_SHADER_SHADOWS
        if ((materials[mat].flags & RT_MATERIAL_SHADOW_MASK) == RT_MATERIAL_SHADER_SHADOW) {
            rt_hand_shadow_over(i, th, walk_origin[i].w, walk_state[i].from_prim, depth,
                                weight, origin, state, shadow_aov, ray_sample, light_count,
                                slot_rays);
            walk_state[i].alive = 0u;
            return;
        }
#endif
        float most;
        th *= rt_transmittance(mat, materials, material_channels, &most);
        occluded = !(most > 0.0f) || depth >= max_depth;
        ends = occluded;
    }
    if (ends) {
        rt_shadow_passes(i, occluded, th, weight, shadow_aov);
        walk_state[i].alive = 0u;
        return;
    }
    through[i] = th;
    walk_origin[i].w = h.t;
    walk_state[i].from_prim = h.prim;
    atomic_inc(walking);
}
#endif

/* Groups a round's queue by treelet: cursor[t] starts at treelet t's offset. */
__kernel void treelet_scatter(uint count,
                              __global const TreeletPair* in,
                              __global uint* cursor,
                              __global TreeletPair* out,
                              __global uint* active_counter) {
    uint i = get_global_id(0);
    RT_COUNT_RANGE(active_counter, count);
    if (i >= count) return;
    TreeletPair p = in[i];
    out[atomic_inc(&cursor[p.treelet])] = p;
}

/* The closest hit of each live ray as intersect_closest writes it: t from the key; u, v
 * from the scalar watertight test of the winning triangle, whose edge functions and
 * 1 / det are those of the four-wide test that found it, or from the winning object
 * intersected again (which also gives the primitive to report). */
__kernel void treelet_resolve(uint count,
                              __global const float4* origin,
                              __global const float4* direction,
                              __global const RayState* state,
                              __global const ulong* keys,
                              __global RayHit* hits,
                              RT_TL_SCENE_PARAMS,
                              __global uint* active_counter) {
    uint i = get_global_id(0);
    int active = i < count && state[i].alive;
    RT_COUNT_GROUP(active_counter, j, j < count && state[j].alive);
    if (!active) return;
    float4 o = origin[i], d = direction[i];
    ulong key = keys[i];
    RayHit h;
    h.t = d.w;
    h.u = h.v = 0.0f;
    h.prim = RT_NO_HIT;
    if (key != RT_NO_KEY) {
        h.prim = (uint)(key & 0xffffffffUL);
        h.t = rt_key_t(key, d.w);
        WatertightRay w = rt_watertight_setup(d);
        float t, u, v;
        int again;
#ifdef RT_HAS_QUADRICS
        if (h.prim & RT_OBJECT_BIT) {
            RT_TL_DECLARE_OBJECTS(i);
            uint hp;
            again = rt_object_hit(objs, &w, h.prim, o, d, o.w, d.w, &t, &u, &v, &hp);
            h.prim = hp;
        } else
#endif
        {
            Triangle tri = tris[h.prim];
            again = rt_intersect_triangle(&w, o, tri.v0, tri.v1, tri.v2, -INFINITY, INFINITY,
                                          &t, &u, &v);
        }
        if (again) {
            h.u = u;
            h.v = v;
        }
    }
    hits[i] = h;
}
#endif
