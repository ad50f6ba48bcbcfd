/* numerics_slots.h: the slots of the render's numerics buffer, shared by the kernels
 * (cl/lib/numerics.clh and the stages that count) and the host (render_summary.cpp,
 * renderer.cpp, render_loop.cpp), so that both read the same slot for the same count. */
#ifndef RT_NUMERICS_SLOTS_H
#define RT_NUMERICS_SLOTS_H

#define RT_NUM_NONFINITE 0         /* a NaN or Inf channel */
#define RT_NUM_NEGATIVE 1          /* a negative alpha (a colour may be negative) */
#define RT_NUM_HUGE 2              /* a channel above RT_MAX_RADIANCE */
#define RT_NUM_DENORMAL 3          /* a denormal channel (flushed to zero) */
#define RT_NUM_TRANSPARENT_DEPTH 4 /* continuations cut by maxtransparentdepth */
#define RT_NUM_SPECULAR_DEPTH                                 \
    5 /* traced rays cut by a depth limit (specular, diffuse) \
       */
#define RT_NUM_ROULETTE 6          /* trace() rays ended by Russian roulette */
#define RT_NUM_TRACE_LIMIT 7       /* trace() calls past the RSL_MAX_TRACE a run records */
#define RT_NUM_LOOP_CUT 8          /* shading points where a shader loop was cut (rsl_abi.h) */
#define RT_NUM_COUNTERS 9
/* then one flag per DelayedReadArchive not loaded yet: a ray reached its bound */
#define RT_NUM_PROCEDURAL_BASE RT_NUM_COUNTERS

#endif
