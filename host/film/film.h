// film.h: the float film on the host: per-pixel sums over whole samples (sum, sum of
// squares, count) as the retire kernel leaves them, the optional geometric AOV sums, and
// the resolve to RGBA. Pixels a stopped render never reached are filled from their
// nearest sampled neighbour and flagged.
#pragma once
#include <string>
#include <vector>

#include "cl/include/film.h"

namespace rd {

struct Rgba {
    float r, g, b, a;
};

// One extra image channel for the EXR (an AOV).
struct Channel {
    std::string name;
    std::vector<float> values;
};

struct Film {
    int width = 0, height = 0;
    std::vector<PixelAccum> pixels;
    std::vector<AovAccum> aovs;  // empty unless an AOV was asked for

    // Mean of each pixel's samples; a pixel with none takes its nearest sampled
    // neighbour's value (all transparent black if nothing was sampled).
    std::vector<Rgba> resolve() const;
    // 1 where resolve() filled a pixel from a neighbour.
    std::vector<float> filledMask() const;
    uint64_t sampleCount() const;
    uint64_t nonfiniteCount() const;
    uint64_t unsampledCount() const;

    // AOV channels by name: "z", "N" (N.X, N.Y, N.Z), "samples", "error", "filled".
    // Throws std::runtime_error for an unknown name or a geometric AOV not rendered.
    std::vector<Channel> aovChannels(const std::string& name) const;

private:
    // For each pixel, the index of the nearest pixel with samples (itself if sampled),
    // -1 when the film is empty. Breadth-first from all sampled pixels at once.
    std::vector<int64_t> nearestSampled() const;
};

}  // namespace rd
