/* displace_vertices.cl: true displacement's second half (host/render/true_displacement.h):
 * the displacement shader of each diced surface (host/scene/dice_displaced.h) run at its
 * vertices, as a REYES renderer runs it on a grid's points. A vertex is a corner of one
 * of its diced triangles: its globals are those the shade stage would take there (P,
 * N, s, t, Cs, per-point parameters...), seen from the eye along one camera ray, with
 * neighbours a pixel's footprint away for derivatives. The moved P and the shader's N
 * (normalised; the moved surface's when the shader sets none) come back; a texture
 * lookup that met an absent tile lists the vertex to run again once the host has served
 * it. Part of the shading program, only for scenes with truly displaced surfaces. */
#if defined(RT_HAS_DISPLACEMENT) && defined(RT_HAS_DERIVATIVES)
__kernel void displace_vertices(uint count,
                                __global const uint* pending,     /* vertex indices */
                                __global const uint2* vertex_corner, /* (triangle, corner) */
                                __global float4* moved,           /* by vertex */
                                __global float4* moved_normal,    /* the shader's N */
                                float4 eye, float eye_width,      /* the camera ray's */
                                __global const Triangle* tris,
                                __global const TriangleAttr* attrs,
                                __global const float4* normals,
                                __global const float4* vertex_st,
                                __global const float4* vertex_cs,
                                __global const float4* vertex_os,
                                __global const Material* materials,
                                __global const float* material_channels,
                                __global const Quadric* quadrics,
                                __global const float4* quadric_primvars,
                                __global const float4* quadric_motion,
                                __global const Triangle* tris_end,
                                __global const float* params,
                                __global const uint* tri_params,
                                __global const float4* point_params,
                                __global const int* param_layout,
                                RD_TEXTURE_KERNEL_ARGS,
                                __global uint* retry,       /* [0] count, then vertices */
                                __global uint* active_counter) {
    uint j = get_global_id(0);
    RT_COUNT_RANGE(active_counter, count);
    if (j >= count) return;
    const uint vi = pending[j];
    const uint2 vc = vertex_corner[vi];
    const uint tri = vc.x;
    RayHit h;
    h.prim = tri;
    h.u = vc.y == 1u ? 1.0f : 0.0f;
    h.v = vc.y == 2u ? 1.0f : 0.0f;
    float4 P = vc.y == 0u ? tris[tri].v0 : (vc.y == 1u ? tris[tri].v1 : tris[tri].v2);
    P.w = 0.0f;
    float4 dir = P - eye;
    dir.w = 0.0f;
    h.t = sqrt(rt_dot3(dir, dir));
    dir = h.t > 0.0f ? dir / h.t : (float4)(0.0f, 0.0f, 1.0f, 0.0f);
    /* a moving piece is displaced on its first key, from where its offset is carried to
     * the others (host/render/true_displacement.cpp) */
    float time = 0.0f;
#ifdef RT_HAS_MOTION
    if (attrs[tri].flags & RT_QF_MOVING) time = tris_end[tri].v0.w;
#endif
    const uint inst = RT_NO_HIT;
    float4 org = eye;
#undef RD_HIT_BUFFERS
#define RD_HIT_BUFFERS org, dir, time, inst, tris, attrs, normals, vertex_st, vertex_cs, \
    vertex_os, materials, material_channels, quadrics, quadric_primvars, quadric_motion, tris_end, tri_params, \
    point_params, param_layout
    Material m;
    RslGlobals g;
    rd_surface_globals(&g, &m, h, RD_HIT_BUFFERS);
    /* (the piece's own material: rd_surface_globals clears its shader, already run) */
    const uint disp = (materials[attrs[tri].material].flags & RT_MATERIAL_DISPLACEMENT_MASK) >>
                      RT_MATERIAL_DISPLACEMENT_SHIFT;
    int loops_cut = 0;
    g.loops_cut = &loops_cut;
    g.rng_pixel = vi; /* random() in a displacement: one stream per vertex */
    g.rng_sample = 0u;
    g.rng_depth = 0u;
    g.ray_depth = 0u;
    g.scene_params = params;
#ifdef RT_HAS_TEXTURES
    struct RslTexContext texc;
    rd_tex_context_init(&texc, tex_info, tex_pages, tex_tiles, tex_requests, tex_counters,
                        tex_used, 0u, RD_SCENE_WORLD_ORIGIN(params));
    struct RslTexContext* tc = &texc;
    g.texctx = tc;
#else
    struct RslTexContext* tc = 0;
    g.texctx = 0;
#endif
    float4 out = g.P;
    float4 n = g.N;
    if (disp) {
        struct {
            float width;
        } rs = {eye_width};
        RslGlobals g1, g2;
        RD_NEIGHBOUR_GLOBALS(g, g1, g2, h, rs, dir, RD_HIT_BUFFERS);
        g1.loops_cut = g2.loops_cut = &loops_cut;
        rd_displace_lanes((int)disp - 1, &g, &g1, &g2, params, tc, &out);
        n = g.N; /* what the shader made of N (the moved surface's, if it set none) */
    }
#ifdef RT_HAS_TEXTURES
    rd_tex_context_done(&texc);
    if (texc.miss) { /* run again once the tiles are there */
        retry[1u + atomic_inc(&retry[0])] = vi;
        return;
    }
#endif
    out.w = 0.0f;
    moved[vi] = out;
    n.w = 0.0f;
    moved_normal[vi] = n;
}
#endif
