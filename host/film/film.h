// film.h: the float film on the host: per-pixel sums over whole samples (sum, sum of
// squares, count) as the retire kernel leaves them, the optional geometric AOV sums, and
// the resolve to RGBA. Pixels a stopped render never reached are filled from their
// nearest sampled neighbour and flagged.
#pragma once
#include <string>
#include <vector>

#include "cl/include/film.h"
#include "host/film/film_error.h"
#include "host/scene/color_samples.h"

namespace rd {

struct Rgba {
    float r, g, b, a;
};

// One extra image channel for the EXR (an AOV).
struct Channel {
    std::string name;
    std::vector<float> values;
};

// An AOV that shaders write (an output variable, or a global: Cs, Os, P, Ng, s, t, u, v):
// its `floats` at `offset` of each sample's and pixel's RT_SHADER_AOVS floats. A colour
// has the scene's colour channels (ColorSamples), made RGB when written.
struct ShaderAov {
    std::string name;
    std::string type = "float";  // float, color, point, vector, normal
    int floats = 1, offset = 0;
};

struct Film {
    int width = 0, height = 0;
    FilmPixels pixels;
    HostVector<AovAccum> aovs;  // empty unless an AOV was asked for (as pixels)
    // Shader AOVs: their layout, and shaderAovFloats sums a pixel over its counted samples
    std::vector<ShaderAov> shaderAovs;
    int shaderAovFloats = 0;
    HostVector<float> shaderAovSums;
    ColorSamples colours;  // the scene's colour channels: a colour AOV's, made RGB
    // The crop window: the pixels rendered and written, [x0, x1) x [y0, y1).
    int cropX0 = 0, cropX1 = 0, cropY0 = 0, cropY1 = 0;
    // (cropX1 == 0: no crop window was set, the whole frame counts)
    bool cropped() const {
        return cropX1 > 0 && (cropX0 > 0 || cropY0 > 0 || cropX1 < width || cropY1 < height);
    }
    size_t cropPixelCount() const {
        return cropX1 > 0 ? size_t(cropX1 - cropX0) * size_t(cropY1 - cropY0)
                          : size_t(width) * size_t(height);
    }
    bool inCrop(size_t i) const {
        if (cropX1 == 0) return true;
        int x = int(i % size_t(width)), y = int(i / size_t(width));
        return x >= cropX0 && x < cropX1 && y >= cropY0 && y < cropY1;
    }
    // Cuts a full-frame channel down to the crop window.
    template <typename T>
    std::vector<T> crop(const std::vector<T>& full) const {
        if (!cropped()) return full;
        std::vector<T> out;
        out.reserve(cropPixelCount());
        for (int y = cropY0; y < cropY1; ++y)
            for (int x = cropX0; x < cropX1; ++x) out.push_back(full[size_t(y) * width + x]);
        return out;
    }

    // The "error" AOV's factor on each pixel's spread-based error: under the Sobol
    // sampler the film's replicate estimate over its spread estimate (the samples' spread
    // overstates a stratified pixel's error; FilmError), 1 for independent samples.
    double errorScale = 1.0;
    // RI Exposure: resolved colour = (gain * colour)^(1 / gamma), alpha untouched.
    float exposureGain = 1.0f, exposureGamma = 1.0f;
    // What the Imager shader made of means() (empty: no imager); resolve() uses it.
    std::vector<Rgba> imaged;
    // Mean of each pixel's samples; a pixel with none takes its nearest sampled
    // neighbour's value (all transparent black if nothing was sampled).
    std::vector<Rgba> means() const;
    // The image: means(), through the Imager shader, through Exposure (RI's order).
    std::vector<Rgba> resolve() const;
    // 1 where resolve() filled a pixel from a neighbour.
    std::vector<float> filledMask() const;
    // Whole samples, samples left out (NaN/Inf) and pixels in the crop with no sample,
    // counted in one pass over the film (12 MB at 512x512).
    struct Tally {
        uint64_t samples = 0, nonfinite = 0, unsampled = 0;
    };
    Tally tally() const;

    // AOV channels by name: "z", "N" (N.X, N.Y, N.Z), "samples", "error", "filled", or a
    // shader AOV (a float "name"; a colour name.R, .G, .B; a point, vector or normal
    // name.X, .Y, .Z: the mean over the pixel's samples, 0 where a sample hit nothing).
    // Throws std::runtime_error for an unknown name or a geometric AOV not rendered.
    std::vector<Channel> aovChannels(const std::string& name) const;

private:
    std::vector<Channel> shaderAovChannels(const ShaderAov& a) const;

    // For each pixel, the index of the nearest pixel with samples (itself if sampled),
    // -1 when the film is empty. Breadth-first from all sampled pixels at once.
    std::vector<int64_t> nearestSampled() const;
};

}  // namespace rd
