// imager_stage.h: the RI Imager shader, run by the kernel imager_apply (generated with
// the shading program, shader_set.cpp) over every pixel of the finished image, before
// Exposure (RI 3.2 order: pixel -> imager -> exposure -> quantize).
#pragma once
#include <vector>

#include "film/film.h"
#include "ocl/kernel.h"

namespace rd {

// The imager's picture of film.means(): colour and alpha per pixel.
std::vector<Rgba> applyImager(const ClContext& ctx, cl_program program, Profiler& prof,
                              const Film& film, const DeviceBuffer<float>& params);

}  // namespace rd
