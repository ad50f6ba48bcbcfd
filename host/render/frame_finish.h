// frame_finish.h: the end of a frame, after its last pass (DESIGN.md section 3): the
// Imager shader on the finished film, the film, AOVs and counters read back, the
// kernels' figures collected, and the summaries --stats reports.
#pragma once
#include <chrono>

#include "device_film_sums.h"
#include "device_pixel_tests.h"
#include "render_loop.h"
#include "renderer.h"
#include "sampling.h"

namespace rd {

// What the end of a frame reads beside the FrameDevice.
struct FrameEnd {
    Film& film;
    cl_program shadeProgram;       // holds the imager's kernel (shader_set.cpp)
    DevicePixelTests* pixelTests;  // null: the host tested the pixels
    DeviceFilmSums* filmSums;      // null: the host sums the film's error
    const SamplePlanner& planner;
    bool twoSamplesAPixel;         // the film's error can be estimated
};

// Leaves `film` holding the frame's image (and its imaged picture when the scene has
// an Imager) and `st` its figures. Also after a stopped frame.
void finishFrame(const FrameDevice& d, const FrameEnd& e, RenderStats& st,
                 rib::Diagnostics& diag, std::chrono::steady_clock::time_point t0);

}  // namespace rd
