/* shade_rsl.cl: the shade stage for one compiled surface shader; the host makes one copy
 * per shader, with the shader's name in place of the word SURFACE. Fire and forget
 * (DESIGN.md section 4): the shader runs in base mode for its emission E and opacity Oi,
 * which go to the sample at once; once per light, whose coefficient times the light's
 * Cl becomes the weight of a shadow ray toward it (unless the base evaluation gave
 * every light's coefficient: RD_LIGHT_COEFS_SURFACE, rsl_abi.h LIGHT COEFFICIENTS);
 * once per trace() it asked for, whose
 * coefficient becomes the weight of the traced ray. Oi < 1 continues the ray straight on
 * with weight (1 - Oi). The kernel runs over this shader's run of the sorted ray list. */
__kernel void shade_SURFACE(uint begin, uint count,
                            __global const uint* sorted,  /* ray indices, by shader */
                            __global const uint* ray_key, /* classify's shader per ray */
                            __global const Triangle* tris,
                            __global const TriangleAttr* attrs,
                            __global const float4* normals,
                            __global const float4* vertex_st, /* RT_HAS_VERTEX_* only */
                            __global const float4* vertex_cs,
                            __global const float4* vertex_os,
                            __global const Material* materials,
                            __global const float* material_channels, /* > 3 channels only */
                            __global const Quadric* quadrics, /* RT_HAS_QUADRICS only */
                            __global const float4* quadric_primvars,
                            __global const float4* quadric_motion, /* RT_HAS_MOTION only */
                            __global const Triangle* tris_end,
                            __global const float* sample_time,
                            __global const uint* sample_pixel, /* roulette, area lights */
                            __global const uint* sample_index,
                            __global const uint* hit_instance, /* RT_HAS_INSTANCES only */
                            __global const float* params,
                            /* RSL_MAX_PARAM_PRIMVARS only: parameters given per point */
                            __global const uint* tri_params,
                            __global const float4* point_params,
                            __global const int* param_layout,
                            __global const float4* origin,
                            __global const float4* direction,
                            __global const rt_weight* weight,
                            __global const RayState* state,
                            __global const uint* ray_sample,
                            __global const RayHit* hits,
                            __global SampleTotal* total,
                            __global float4* next_origin, /* slot r * RT_SPAWN_SLOTS + k */
                            __global float4* next_direction,
                            __global rt_weight* next_weight,
                            __global RayState* next_state,
                            __global uint* next_sample,
                            __global uint* spawn_mask, /* bit k: slot k filled */
                            __global uint* slot_rays,  /* + one per ray spawned */
                            /* slot r * light_count + l (with volume shadows light_count
                             * is twice the lights: volume.clh) */
                            __global float4* shadow_origin,
                            __global float4* shadow_direction,
                            __global rt_weight* shadow_weight,
                            __global RayState* shadow_state,
                            __global SampleAov* aov,
                            /* RT_SHADER_AOVS floats a sample slot, and a shadow ray */
                            __global float* aov_values,
                            __global float* shadow_aov,
                            /* RT_RAY_AOVS only: AOV weights (ray_aovs.clh), a pool
                             * ray's and a spawn slot's */
                            __global const float* ray_aovw,
                            __global float* next_aovw,
                            uint light_count,
                            __global uint* numerics, /* numerics.clh counters */
                            /* RT_HAS_TEXTURES only: the texture state (texture.h), and
                             * the points to shade again once missing tiles are there,
                             * at begin + their rank in this shader's run */
                            RD_TEXTURE_KERNEL_ARGS,
                            __global uint* retry_sorted,
                            __global uint* retry_count,
                            uint shader_index,
                            __global uint* active_counter) {
    uint j = get_global_id(0);
#ifdef RT_VOLUME_SHADOWS
    const uint lights = light_count / 2u; /* a ray's second shadow slots: its volume's */
#else
    const uint lights = light_count;
#endif
    (void)lights;
    /* a scene with one shader skips the sort: its run is every ray, with misses and hits
     * on surfaces with no shader among them (their key is not this shader's) */
    RT_COUNT_GROUP(active_counter, q, q < count && ray_key[sorted[begin + q]] == shader_index);
    if (j >= count) return;
    uint r = sorted[begin + j];
    if (ray_key[r] != shader_index) return;
    RayHit h = hits[r];
    float4 org = origin[r], dir = direction[r];
    rsl_color w = rt_weight_color(weight[r]); /* alpha in RSL_CW */
    RayState rs = state[r];
    uint sample = ray_sample[r];
#ifdef RT_SHADER_SHADOWS
    /* a shadow ray handed over at a surface whose shader says what it lets through (ray.h
     * RT_ALIVE_SHADOW): the shader runs for its Oi alone */
    const int shadow_ray = rs.alive == RT_ALIVE_SHADOW;
#else
    int shadow_ray = 0; /* (not const: a constant operand of && makes the compiler warn) */
#endif
#ifdef RT_HAS_MOTION
    const float time = sample_time[sample];
#else
    const float time = 0.0f;
#endif
#ifdef RT_HAS_PROCEDURALS
    /* an archive not loaded yet: the host loads it and renders again */
    if (rt_flag_procedural(h.prim, quadrics, numerics)) return;
#endif
    Material m;
    RslGlobals g;
#ifdef RT_HAS_INSTANCES
    const uint inst = hit_instance[r];
#else
    const uint inst = RT_NO_HIT;
#endif
#define RD_HIT_BUFFERS org, dir, time, inst, tris, attrs, normals, vertex_st, vertex_cs, \
    vertex_os, materials, material_channels, quadrics, quadric_primvars, quadric_motion, tris_end, tri_params, \
    point_params, param_layout
    rd_surface_globals(&g, &m, h, RD_HIT_BUFFERS);
    int loops_cut = 0; /* a shader loop left after RSL_MAX_LOOP_ITERATIONS (rsl_abi.h) */
    g.loops_cut = &loops_cut;
    g.rng_pixel = sample_pixel[sample]; /* area lights pick their points by the sample */
    g.rng_sample = sample_index[sample];
    g.rng_depth = RT_TRACE_DEPTH(rs) + RT_TRANSPARENT_DEPTH(rs);
    g.ray_depth = RT_TRACE_DEPTH(rs) | (shadow_ray ? RSL_SHADOW_RAY : 0u);
    g.texctx = 0; /* set below when the scene has textures */
    g.scene_params = params; /* the scene block and the lights' lead the buffer */
    float4 Ngf = rt_dot3(dir, g.Ng) < 0.0f ? g.Ng : -g.Ng; /* facing the ray */
#ifdef RT_HAS_DERIVATIVES
    const float width_at_hit = rs.width + RT_PIXEL_SPREAD * h.t; /* the rays it spawns start this wide */
#else
    const float width_at_hit = 0.0f;
#endif
#ifdef RT_HAS_AOVS
    if (!shadow_ray && !aov[sample].hit) {
        aov[sample].z *= h.t;
        aov[sample].normal = rt_dot3(dir, g.N) < 0.0f ? g.N : -g.N;
        aov[sample].hit = 1u;
    }
#endif
    /* holdout: opaque, black, no alpha (its shadow as any surface's) */
    if ((m.flags & RT_MATERIAL_MATTE) && !shadow_ray) return;
    __global const float* p = params + m.params;
    /* Sides 1: the back of a one-sided surface is not there; the ray goes on unchanged */
#ifdef RT_HAS_ONE_SIDED
    int culled = (m.flags & RT_MATERIAL_ONE_SIDED) && rt_dot3(dir, g.Ng) > 0.0f;
#else
    int culled = 0; /* (not const: a constant operand of && makes the compiler warn) */
#endif
#ifdef RT_HAS_INVISIBLE
    /* not visible to this kind of ray: it goes on unchanged, as past a culled back */
    culled = culled || (m.flags & (RT_TRACE_DEPTH(rs) == 0u          ? RT_MATERIAL_NO_CAMERA
                                   : rs.alive == RT_ALIVE_DIFFUSE ? RT_MATERIAL_NO_DIFFUSE
                                                                  : RT_MATERIAL_NO_TRACE));
#ifdef RT_HAS_VISIBILITY_RAYS
    /* (classify sends only these here) */
    culled = culled || rs.alive == RT_ALIVE_VISIBILITY || rs.alive == RT_ALIVE_DISTANCE;
#endif
#endif
#ifdef RT_CLIP_PLANES
    /* ClippingPlane: camera rays do not see what lies on a plane's clipped side */
    if (RT_TRACE_DEPTH(rs) == 0u)
        for (int k = 0; k < RT_CLIP_PLANES; ++k) {
            float4 c = vload4(0, params + RD_SCENE_CLIP_PLANES + 4 * k);
            culled = culled || rt_dot3(c, g.P) + c.w > 0.0f;
        }
#endif
    culled = culled && !shadow_ray; /* (shadow rays see what casts a shadow) */
    RslEval ev;
    RslDeriv* dsites = 0; /* the surface shader's derivatives, when it takes any */
#ifdef RT_HAS_TEXTURES
    struct RslTexContext texc;
    rd_tex_context_init(&texc, tex_info, tex_pages, tex_tiles, tex_requests, tex_counters,
                        tex_used, shader_index, RD_SCENE_WORLD_ORIGIN(params));
    struct RslTexContext* tc = &texc;
    g.texctx = tc; /* light shaders' shadow maps and textures */
#else
    struct RslTexContext* tc = 0;
#endif
#ifdef RT_HAS_DERIVATIVES
    RslDeriv deriv;
    uint disp = (m.flags & RT_MATERIAL_DISPLACEMENT_MASK) >> RT_MATERIAL_DISPLACEMENT_SHIFT;
    /* (a variable: a constant operand of && makes the compiler print a warning) */
    int take_derivs = RSL_DERIVS_SURFACE || disp;
    if (!culled && take_derivs) {
        RslGlobals g1, g2;
        RD_NEIGHBOUR_GLOBALS(g, g1, g2, h, rs, dir, RD_HIT_BUFFERS);
        g1.loops_cut = g2.loops_cut = &loops_cut;
#ifdef RT_HAS_DISPLACEMENT
        if (disp) rd_displace_lanes((int)disp - 1, &g, &g1, &g2, params, tc, 0);
#endif
        if (RSL_DERIVS_SURFACE) { /* the neighbours first: they record what the point differences */
            dsites = &deriv;
            for (int lane = 1; lane <= 2; ++lane) {
                RslGlobals gl = lane == 1 ? g1 : g2;
                deriv.lane = lane;
                deriv.count = 0;
                rd_eval_init(&ev, dsites, tc, -1, -1);
                rsl_surface_SURFACE(&gl, p, &ev);
            }
            deriv.lane = 0;
            deriv.count = 0;
        }
    }
#endif
    rd_eval_init(&ev, dsites, tc, -1, -1);
#if RD_LIGHT_COEFS_SURFACE
    ev.coefs = 1; /* the base evaluation gives every light's coefficient too */
#ifdef RT_SHADER_SHADOWS
    ev.coefs = !shadow_ray; /* (a shadow ray's evaluation is for Oi alone) */
#endif
#endif
    RslLightCache light_cache;
    if (!culled) rd_fill_light_cache(&g, &light_cache);
    RslGlobals base = g;
    if (!culled) rsl_surface_SURFACE(&base, p, &ev);
#ifdef RT_HAS_TEXTURES
    rd_tex_context_done(&texc);
    if (texc.miss) { /* a tile was not there: commit nothing, shade this point again */
        retry_sorted[begin + atomic_inc(&retry_count[shader_index])] = r;
        return;
    }
#endif
#ifdef RT_SHADER_SHADOWS
    if (shadow_ray) {
        /* what gets through goes on toward the light as a shadow ray again (intersect_shadow's
         * walk, the next layer), from this ray's first shadow slot; a surface whose shader
         * is not asked (a tie in t found it first) lets through what the walk's would */
        float most;
        rsl_color through =
            (m.flags & RT_MATERIAL_SHADOW_MASK) == RT_MATERIAL_SHADER_SHADOW
                ? clamp(rsl_f2c(1.0f) - base.Oi, 0.0f, 1.0f)
                : rt_weight_color(rt_transmittance((uint)g.material, materials,
                                                   material_channels, &most));
        rsl_color sw = rt_sanitize_c(w * through, numerics);
        RSL_CW(sw) = 0.0f;
        const uint s = r * light_count;
#if defined(RT_RAY_AOVS) && defined(RT_SHADER_AOVS)
        /* the lights' parts of the sample's AOVs it brings, on as a shadow ray's parts
         * (its alpha lane marks them) */
        if (rs.depth & RT_CARRIES_AOVS) {
            float a[RT_AOV_PAYLOAD], parts[RT_SHADER_AOVS];
            rt_aov_load(a, ray_aovw + (size_t)r * RT_AOV_PAYLOAD);
            if (rt_aov_parts(parts, a, through)) RSL_CW(sw) = 1.0f;
            for (int c = 0; c < RT_SHADER_AOVS; ++c)
                shadow_aov[(size_t)s * RT_SHADER_AOVS + c] = parts[c];
        }
#endif
        if (!rsl_cnonzero(sw) && RSL_CW(sw) == 0.0f) return;
        org.w = h.t;
        shadow_origin[s] = org;
        shadow_direction[s] = dir;
        shadow_weight[s] = rt_weight_of(sw);
        RayState ss = {1u, (rs.depth & ~RT_AOV_FLAGS) + RT_ONE_TRANSPARENT, h.prim, 0.0f};
        shadow_state[s] = ss;
        return;
    }
#endif
    if (dsites) dsites->lane = 3; /* every other mode replays the point's derivatives */
#ifdef RT_RAY_AOVS
    /* a ray below a trace() call of an AOV surface brings back part of the AOVs (its AOV
     * weights); a camera ray behind one composites the next (its scales): ray_aovs.clh */
    float ain[RT_AOV_PAYLOAD];
    const int carries_in = (rs.depth & RT_CARRIES_AOVS) != 0u;
    const int composites_in = (rs.depth & RT_COMPOSITES_AOVS) != 0u;
    if (carries_in || composites_in) rt_aov_load(ain, ray_aovw + (size_t)r * RT_AOV_PAYLOAD);
#endif
#ifdef RT_SHADER_AOVS
    /* The surfaces a camera ray is shaded at give the sample's shader AOVs: the first
     * one's in full, each behind it (RT_RAY_AOVS) scaled by what those in front let
     * through. The output variables' values without the lights go in now, the lights'
     * parts ride on their shadow rays (close_round), the trace() calls' on their rays. */
    float aov_scale[RT_SHADER_AOVS];
    for (int c = 0; c < RT_SHADER_AOVS; ++c) aov_scale[c] = 1.0f;
    int aov_surface = !culled && RT_TRACE_DEPTH(rs) == 0u && !aov[sample].shaded;
#ifdef RT_RAY_AOVS
    if (composites_in) {
        for (int c = 0; c < RT_SHADER_AOVS; ++c) aov_scale[c] = ain[c];
        aov_surface = !culled;
    }
#endif
    if (aov_surface) {
        aov[sample].shaded = 1u;
        float out[RT_SHADER_AOVS];
        for (int c = 0; c < RT_SHADER_AOVS; ++c) out[c] = 0.0f;
        RD_AOV_OUTPUTS_SURFACE(out, ev, g);
        /* the first is the sample's only ray; behind it, rays below an earlier surface
         * may add in the same launch */
        __global float* dst = aov_values + sample * RT_SHADER_AOVS;
        for (int c = 0; c < RT_SHADER_AOVS; ++c) {
#ifdef RT_RAY_AOVS
            if (composites_in) {
                rt_atomic_add_float(&dst[c], aov_scale[c] * out[c]);
                continue;
            }
#endif
            dst[c] = out[c];
        }
    }
#endif
    rsl_color E = culled ? (rsl_color)(0.0f) : rsl_cw0(base.Ci);
    rsl_color Oi = culled ? (rsl_color)(0.0f) : base.Oi;
    /* the atmosphere between the ray's origin and P: Ci' = a Ci + b (affine in Ci, as
     * fog and depthcue are), so it scales every contribution and adds b once */
    rsl_color atmo_a = (rsl_color)(1.0f);
#if defined(RT_HAS_ATMOSPHERE) || defined(RT_HAS_INTERIOR) || defined(RT_HAS_EXTERIOR)
    uint atmo = 0u, inside = 0u, outside = 0u;
#ifdef RT_HAS_ATMOSPHERE
    atmo = (m.flags & RT_MATERIAL_ATMOSPHERE_MASK) >> RT_MATERIAL_ATMOSPHERE_SHIFT;
#endif
#ifdef RT_HAS_INTERIOR
    /* a hit on the back of a surface with an Interior shader: the ray came through the
     * object's inside, whose shader takes the segment in place of the atmosphere */
    const uint interior = (m.flags & RT_MATERIAL_INTERIOR_MASK) >> RT_MATERIAL_INTERIOR_SHIFT;
    if (interior && rt_dot3(dir, g.Ng) > 0.0f) atmo = interior, inside = 1u;
#endif
#ifdef RT_HAS_EXTERIOR
    /* a ray that left a surface with an Exterior shader and does not end on that surface's
     * own back (the segment inside it) crossed its outside: the Exterior takes it */
    if (!inside && rs.from_prim != RT_NO_HIT) {
        const uint from = rs.from_prim;
        const uint fm = (from & RT_OBJECT_BIT) ? quadrics[from & RT_OBJECT_MASK].material
                                               : attrs[from].material;
        const int own_back = fm == (uint)g.material && rt_dot3(dir, g.Ng) > 0.0f;
        __global const float* table = params + as_int(params[RD_SCENE_EXTERIORS]);
        const uint exterior = own_back ? 0u : (uint)table[fm];
        if (exterior) atmo = exterior, outside = 1u;
    }
#endif
    if (atmo && !culled) {
        const uint vkind = inside    ? RD_VOLUME_INTERIOR
                           : outside ? RD_VOLUME_EXTERIOR
                                     : RD_VOLUME_ATMOSPHERE;
        RslGlobals g0 = base, g1 = base;
        g0.Ci = rsl_f2c(0.0f);
        g1.Ci = rsl_f2c(1.0f);
        /* the volume at Ci = 0 and 1: its b and a + b; with volume shadows without the
         * lights, whose parts come from their shadow rays */
        RslEval ve;
        rd_volume(vkind, (int)atmo - 1, &g0, params, RD_VOLUME_LIGHTS, -1.0f, &ve);
        rd_volume(vkind, (int)atmo - 1, &g1, params, RD_VOLUME_LIGHTS, -1.0f, &ve);
        atmo_a = g1.Ci - g0.Ci;
        RSL_CW(atmo_a) = 1.0f;
        E = rsl_cw0(atmo_a * E + g0.Ci);
        Oi = g0.Oi;
#ifdef RT_VOLUME_SHADOWS
        E += rd_volume_light_rays(vkind, (int)atmo - 1, &base, rsl_cw0(g0.Ci), params, w,
                                  lights, r * light_count + lights, Ngf, shadow_origin,
                                  shadow_direction, shadow_weight, shadow_state, numerics);
#endif
    }
#endif
    rsl_color add = culled ? (rsl_color)(0.0f) : w * E;
    RSL_CW(add) = RSL_CW(w) * RSL_CHANNEL_MEAN(Oi); /* coverage */
    rt_atomic_add_float4(&total[sample].value, rt_sanitize(rt_total_of(add), numerics));
#ifdef RT_RAY_AOVS
    if (carries_in && !culled) rt_aov_add(aov_values + sample * RT_SHADER_AOVS, ain, E);
#endif

#ifdef RT_HAS_SHADOW_RAYS
    for (uint l = 0; l < (culled ? 0u : lights); ++l) {
        float4 toward;
        rsl_color lcl;
        rd_light_at((int)l, &g, g.P, &toward, &lcl);
        int solar = RSL_CW(lcl) == 1.0f;
        if (rd_light_is_ambient((int)l) || !rsl_cnonzero(lcl)) continue;
#if RD_LIGHT_COEFS_SURFACE
        rsl_color coef = ev.Ci_light[l];
#else
        RslEval le;
        rd_eval_init(&le, dsites, tc, (int)l, -1);
        if (dsites) dsites->count = 0;
        RslGlobals lgl = g;
        rsl_surface_SURFACE(&lgl, p, &le);
        rsl_color coef = lgl.Ci - base.Ci;
#endif
#ifdef RT_SHADER_AOVS
        float aov_part[RT_SHADER_AOVS];
        for (int c = 0; c < RT_SHADER_AOVS; ++c) aov_part[c] = 0.0f;
#if !RD_LIGHT_COEFS_SURFACE
        if (aov_surface) {
            RD_AOV_LIGHT_SURFACE(aov_part, le, ev);
            for (int c = 0; c < RT_SHADER_AOVS; ++c) aov_part[c] *= aov_scale[c];
        }
#endif
#ifdef RT_RAY_AOVS
        if (carries_in) rt_aov_parts(aov_part, ain, atmo_a * coef);
#endif
#endif
        rsl_color sw = w * atmo_a * coef;
        RSL_CW(sw) = 0.0f;
        sw = rt_sanitize_c(sw, numerics);
#ifdef RT_SHADER_AOVS
        int carries = 0; /* parts of the sample's AOVs: traced even when Ci takes nothing */
        for (int c = 0; c < RT_SHADER_AOVS; ++c) carries |= aov_part[c] != 0.0f;
        if (!rsl_cnonzero(sw) && !carries) continue;
#else
        if (!rsl_cnonzero(sw)) continue;
#endif
        if (!rd_light_traces_shadows((int)l)) { /* its shadow map did the shadowing */
            rt_atomic_add_float4(&total[sample].value, rt_total_of(sw));
#ifdef RT_SHADER_AOVS
            for (int c = 0; c < RT_SHADER_AOVS; ++c)
                rt_atomic_add_float(&aov_values[sample * RT_SHADER_AOVS + c], aov_part[c]);
#endif
            continue;
        }
        float4 so, sd;
        if (!rd_shadow_ray_to(g.P, Ngf, toward, solar, &so, &sd)) continue;
        uint s = r * light_count + l;
        shadow_origin[s] = so;
        shadow_direction[s] = sd;
#ifdef RT_SHADER_AOVS
        /* its alpha lane (0 in a shadow ray's weight) marks the parts: still there if it
         * reaches the light, as every traversal zeroes an occluded ray's whole weight */
        if (carries) RSL_CW(sw) = 1.0f;
#endif
        shadow_weight[s] = rt_weight_of(sw);
        RayState ss = {1u, 0u, h.prim, 0.0f};
        shadow_state[s] = ss;
#ifdef RT_SHADER_AOVS
        for (int c = 0; c < RT_SHADER_AOVS; ++c) shadow_aov[s * RT_SHADER_AOVS + c] = aov_part[c];
#endif
    }
#endif

    uint spawned = 0u; /* spawn_mask: the slots filled below */
#if RT_SPAWN_SLOTS > 1
    /* trace(): one ray per call the base evaluation recorded */
    int traces = min(ev.trace_count, RSL_MAX_TRACE);
    if (ev.trace_count > RSL_MAX_TRACE) /* (their rays are not traced: say so) */
        atomic_add(&numerics[RT_NUM_TRACE_LIMIT], (uint)(ev.trace_count - RSL_MAX_TRACE));
    /* Attribute "trace" "maxspeculardepth": the object's own, where objects differ */
#ifdef RT_MATERIAL_DEPTHS
    const uint depth_limit = (uint)params[as_int(params[RD_SCENE_DEPTHS]) + g.material];
#else
    const uint depth_limit = RT_MAX_SPECULAR_DEPTH;
#endif
    if (traces > 0 && RT_TRACE_DEPTH(rs) >= depth_limit)
        atomic_add(&numerics[RT_NUM_SPECULAR_DEPTH], (uint)traces);
    for (int i = 0; i < traces && RT_TRACE_DEPTH(rs) < depth_limit; ++i) {
        RslEval te;
        rd_eval_init(&te, dsites, tc, -1, i);
        if (dsites) dsites->count = 0;
        RslGlobals tg = g;
        rsl_surface_SURFACE(&tg, p, &te);
        rsl_color tw = w * atmo_a * (tg.Ci - base.Ci);
        RSL_CW(tw) = 0.0f;
        /* (a weight below zero is no fault: Ci = occlusion() is 1 from the base
         * evaluation less a part for each ray that escapes; rt_sanitize judges a colour
         * by its magnitude) */
        tw = rt_sanitize_c(tw, numerics);
        int child_carries = 0; /* the ray brings back part of the AOVs */
#ifdef RT_RAY_AOVS
        /* the AOVs' part in this call: an AOV surface's outputs' own (their value when
         * trace() returns 1, less the base value), or the weights brought here */
        float achild[RT_AOV_PAYLOAD];
        if (aov_surface) {
            for (int c = 0; c < RT_AOV_PAYLOAD; ++c) achild[c] = 0.0f;
            RD_AOV_TRACE_SURFACE(achild, te, ev);
            for (int c = 0; c < RT_AOV_PAYLOAD; ++c) {
                achild[c] *= aov_scale[c / RSL_CHANNELS];
                child_carries |= achild[c] != 0.0f;
            }
        } else if (carries_in)
            child_carries = rt_aov_scale(achild, ain, atmo_a * (tg.Ci - base.Ci));
#endif
#ifdef RT_ROULETTE_DEPTH
        /* Russian roulette from the given depth on: a ray survives with probability p =
         * its largest weight (at least 0.05, at most 1) and carries weight / p, so the
         * estimate stays unbiased while dim paths end early; the random number is the
         * sample's own (pixel, sample, depth, call), never the pool slot's */
        if (RT_TRACE_DEPTH(rs) + 1u >= RT_ROULETTE_DEPTH) {
            float surv = rsl_cmax(fabs(tw));
#ifdef RT_RAY_AOVS
            if (child_carries) surv = fmax(surv, rt_aov_largest(achild));
#endif
            surv = clamp(surv, 0.05f, 1.0f);
            uint dim = 1024u + 16u * RT_TRACE_DEPTH(rs) + (uint)i;
            if (rt_random(sample_pixel[sample], sample_index[sample], dim) >= surv) {
                atomic_inc(&numerics[RT_NUM_ROULETTE]);
                continue;
            }
            tw /= surv;
#ifdef RT_RAY_AOVS
            for (int c = 0; c < RT_AOV_PAYLOAD; ++c) achild[c] /= surv;
#endif
        }
#endif
        if (rsl_cmax(fabs(tw)) < 1e-6f && !child_carries) continue;
#ifdef RT_MAX_DIFFUSE_DEPTH
        /* Attribute "trace" "maxdiffusedepth" 0 or 1: no diffuse ray past that many */
        if (ev.trace_org[i].w > 2.5f &&
            (RT_MAX_DIFFUSE_DEPTH == 0 || (rs.depth & RT_DIFFUSE_BOUNCED))) {
            atomic_inc(&numerics[RT_NUM_SPECULAR_DEPTH]);
            continue;
        }
#endif
        float4 td = rt_normalize3(ev.trace_dir[i]);
        /* a zero direction (refract() under total internal reflection) traces nothing */
        if (!(rt_dot3(td, td) > 0.5f)) continue;
        float4 tp = ev.trace_org[i];
        /* (rsl_abi.h TRACE: the ray's kind, its reach, 0 for no limit) */
        const uint alive = tp.w > 2.5f   ? RT_ALIVE_DIFFUSE
                           : tp.w > 1.5f ? RT_ALIVE_DISTANCE
                           : tp.w > 0.5f ? RT_ALIVE_VISIBILITY
                                         : 1u;
        const float reach = ev.trace_dir[i].w;
        tp.w = 0.0f;
        float4 to = rt_offset_ray(tp, rt_dot3(td, Ngf) >= 0.0f ? Ngf : -Ngf);
        to.w = 0.0f;
        td.w = reach > 0.0f ? reach : INFINITY;
        uint s = r * RT_SPAWN_SLOTS + 1 + (uint)i;
        next_origin[s] = to;
        next_direction[s] = td;
        next_weight[s] = rt_weight_of(tw);
        RayState ts = {alive, (rs.depth + 1u) | (alive == RT_ALIVE_DIFFUSE ? RT_DIFFUSE_BOUNCED : 0u),
                       h.prim, width_at_hit};
#ifdef RT_RAY_AOVS
        ts.depth = (ts.depth & ~RT_AOV_FLAGS) | (child_carries ? RT_CARRIES_AOVS : 0u);
        if (child_carries) rt_aov_store(next_aovw + (size_t)s * RT_AOV_PAYLOAD, achild);
#endif
        next_state[s] = ts;
        next_sample[s] = sample;
        spawned |= 2u << i;
    }
#endif

#ifdef RT_HAS_TRANSPARENCY
    /* Oi < 1: the same ray continues behind the surface with the transmitted weight */
    rsl_color wt = w * (rsl_f2c(1.0f) - Oi);
    RSL_CW(wt) = RSL_CW(w) * (1.0f - RSL_CHANNEL_MEAN(Oi));
    wt = rt_sanitize_c(wt, numerics);
    int goes_on = rsl_cmax(fabs(wt)) > 1e-6f; /* (a weight may be negative) */
#ifdef RT_RAY_AOVS
    /* behind the surface, the weights brought here times what it lets through, or the
     * AOV scales of the surfaces behind an AOV surface */
    float acont[RT_AOV_PAYLOAD];
    int cont_carries = 0, cont_composites = 0;
    if (carries_in)
        cont_carries = rt_aov_scale(acont, ain, rsl_f2c(1.0f) - Oi);
#ifdef RT_SHADER_AOVS
    else if (composites_in || aov_surface)
        cont_composites = rt_aov_composite(acont, aov_scale, rsl_f2c(1.0f) - Oi);
#endif
    goes_on = goes_on || cont_carries || cont_composites;
#endif
    if (goes_on && RT_TRANSPARENT_DEPTH(rs) >= RT_MAX_TRANSPARENT_DEPTH)
        atomic_inc(&numerics[RT_NUM_TRANSPARENT_DEPTH]);
    else if (goes_on) {
        float4 o = rt_offset_ray(g.P, -Ngf);
        o.w = 0.0f;
        float4 d = dir;
        d.w = dir.w - h.t;
#if defined(RT_HAS_VISIBILITY_RAYS) && defined(RT_HAS_INVISIBLE)
        if (rs.alive == RT_ALIVE_DISTANCE) { /* its distance counts from where it started */
            o = org;
            o.w = h.t; /* (past the surface: fromSurface below skips it) */
            d.w = dir.w;
        }
#endif
        uint s = r * RT_SPAWN_SLOTS;
        next_origin[s] = o;
        next_direction[s] = d;
        next_weight[s] = rt_weight_of(wt);
        /* (an occlusion() ray going through stays one) */
        RayState cs = {rs.alive, rs.depth + RT_ONE_TRANSPARENT, h.prim, width_at_hit};
#ifdef RT_RAY_AOVS
        cs.depth = (cs.depth & ~RT_AOV_FLAGS) | (cont_carries ? RT_CARRIES_AOVS : 0u) |
                   (cont_composites ? RT_COMPOSITES_AOVS : 0u);
        if (cont_carries || cont_composites)
            rt_aov_store(next_aovw + (size_t)s * RT_AOV_PAYLOAD, acont);
#endif
        next_state[s] = cs;
        next_sample[s] = sample;
        spawned |= 1u;
    }
#endif
    spawn_mask[r] = spawned;
    /* counted now, so the retire stage may run before the compaction keeps them */
    if (spawned) atomic_add(&slot_rays[sample], popcount(spawned));
    if (loops_cut) atomic_inc(&numerics[RT_NUM_LOOP_CUT]);
}
