// color_samples.h: the scene's colour channels (RiColorSamples) and their conversions to
// and from RGB, for the scene, the shaders' bindings and the film's colour AOVs.
#pragma once
#include <vector>

namespace rd {

// ColorSamples n, n <= 3: colours are n channels through shading, rays and sample totals
// (three lanes, those past n repeating the last); a sample reaches the film as RGB.
// Both matrices are padded to 3x3, row-vector convention (out_j = sum_i in_i m[3i + j]):
// toRgb's rows past n are zero; fromRgb's columns past n repeat its last column.
struct ColorSamples {
    static constexpr int kMaxChannels = 15;  // an rsl_color of 16 lanes, the last kept
    int n = 3;
    // n <= 3: both 3 x 3, padded (rsl_color_samples.clh); n > 3: n x 3 and 3 x n
    std::vector<float> toRgb{1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::vector<float> fromRgb{1, 0, 0, 0, 1, 0, 0, 0, 1};
    bool isRgb() const;  // three channels, identity matrices: nothing to convert
    // a colour's floats as the renderer keeps it (n padded to three: rsl_abi.h COLOURS)
    int slots() const { return n > 3 ? n : 3; }
    int lanes() const { return n <= 3 ? 4 : n <= 7 ? 8 : 16; }  // RSL_COLOR_LANES
    // from nRGB (n x 3) and RGBn (3 x n) as RiColorSamples gives them; false if n > 15
    bool set(const std::vector<float>& nRGB, const std::vector<float>& RGBn);
    // in place: an RGB triple in c[0..3) to the channels c[0..slots()), and back
    void fromRgbValues(float* c) const;
    void toRgbValues(float* c) const;
};

}  // namespace rd
