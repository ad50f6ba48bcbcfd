// film.h: the float film on the host: per-pixel sums over whole samples (sum, sum of
// squares, count) as the retire kernel leaves them, resolved to RGBA for output.
#pragma once
#include <vector>

#include "cl/include/film.h"

namespace rd {

struct Rgba {
    float r, g, b, a;
};

struct Film {
    int width = 0, height = 0;
    std::vector<PixelAccum> pixels;

    // Mean of each pixel's samples; black and transparent where no sample landed.
    std::vector<Rgba> resolve() const;
    uint64_t sampleCount() const;
    uint64_t nonfiniteCount() const;
};

}  // namespace rd
