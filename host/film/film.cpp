// film.cpp: resolving the accumulated film.
#include "film.h"

namespace rd {

std::vector<Rgba> Film::resolve() const {
    std::vector<Rgba> out(pixels.size(), Rgba{0, 0, 0, 0});
    for (size_t i = 0; i < pixels.size(); ++i) {
        const PixelAccum& p = pixels[i];
        if (p.count == 0) continue;
        float inv = 1.0f / float(p.count);
        out[i] = {p.sum.x * inv, p.sum.y * inv, p.sum.z * inv, p.sum.w * inv};
    }
    return out;
}

uint64_t Film::sampleCount() const {
    uint64_t n = 0;
    for (const PixelAccum& p : pixels) n += p.count;
    return n;
}

uint64_t Film::nonfiniteCount() const {
    uint64_t n = 0;
    for (const PixelAccum& p : pixels) n += p.nonfinite;
    return n;
}

}  // namespace rd
