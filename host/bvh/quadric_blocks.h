// quadric_blocks.h: the records that let the trace kernels intersect an object block's
// plain quadrics four at once (cl/include/quadric.h QuadricBlock, cl/lib/quadric4.clh).
#pragma once
#include <vector>

#include "cl/include/quadric.h"
#include "cl/include/scene_types.h"

namespace rd {

// Can this quadric go in a QuadricBlock: one quadratic clipped by z, or a disk (by its
// radius), any sweep (a hyperboloid only the full circle), not moving: the crossings the
// lane loop's rt_quadric_uv_test accepts by z or radius and by angle alone.
bool isPlainQuadric(const Quadric& q);

// Appends a QuadricBlock (two Triangle4 slots) for every object block of `blocks` whose
// lanes are all quadrics of `objects`, one of them at least plain, and points the block at
// it (v2x.x); a lane that is not plain (a torus, an annulus, a partly swept hyperboloid,
// a moving quadric) is marked by a NaN sweep and intersected on its own. Returns how many
// blocks got one.
size_t appendQuadricBlocks(std::vector<Triangle4>& blocks, const std::vector<Quadric>& objects);

}  // namespace rd
