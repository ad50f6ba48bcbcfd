// film.cpp: resolving the accumulated film, filling unreached pixels, and AOV channels.
#include "film.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "film_error.h"

namespace rd {

std::vector<int64_t> Film::nearestSampled() const {
    std::vector<int64_t> src(pixels.size(), -1);
    std::vector<int64_t> queue;
    queue.reserve(pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        if (pixels[i].count > 0 && inCrop(i)) {
            src[i] = int64_t(i);
            queue.push_back(int64_t(i));
        }
    for (size_t head = 0; head < queue.size(); ++head) {
        int64_t i = queue[head];
        int x = int(i % width), y = int(i / width);
        const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
            int nx = x + dx[k], ny = y + dy[k];
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            int64_t j = int64_t(ny) * width + nx;
            if (src[j] >= 0) continue;
            src[j] = src[i];
            queue.push_back(j);
        }
    }
    return src;
}

std::vector<Rgba> Film::resolve() const {
    std::vector<Rgba> out = imaged.size() == pixels.size() ? imaged : means();
    if (exposureGain != 1.0f || exposureGamma != 1.0f)  // the Exposure imager
        for (Rgba& c : out)
            for (float* v : {&c.r, &c.g, &c.b})
                *v = std::pow(std::max(0.0f, exposureGain * *v), 1.0f / exposureGamma);
    return out;
}

std::vector<Rgba> Film::means() const {
    std::vector<Rgba> out(pixels.size(), Rgba{0, 0, 0, 0});
    auto mean = [&](size_t from) {
        const PixelAccum& p = pixels[from];
        float inv = 1.0f / float(p.count);
        return Rgba{p.sum.x * inv, p.sum.y * inv, p.sum.z * inv, p.sum.w * inv};
    };
    // A finished render sampled every pixel: each is its own nearest (the search took 2-3
    // ms of a 512x512 frame's output).
    if (!cropped() && std::all_of(pixels.begin(), pixels.end(),
                                  [](const PixelAccum& p) { return p.count > 0; })) {
        for (size_t i = 0; i < pixels.size(); ++i) out[i] = mean(i);
        return out;
    }
    std::vector<int64_t> src = nearestSampled();
    for (size_t i = 0; i < pixels.size(); ++i)
        if (src[i] >= 0) out[i] = mean(size_t(src[i]));
    return out;
}

std::vector<float> Film::filledMask() const {
    std::vector<float> m(pixels.size(), 0.0f);
    for (size_t i = 0; i < pixels.size(); ++i)
        m[i] = pixels[i].count == 0 && inCrop(i) ? 1.0f : 0.0f;
    return m;
}

Film::Tally Film::tally() const {
    Tally t;
    for (size_t i = 0; i < pixels.size(); ++i) {
        const PixelAccum& p = pixels[i];
        t.samples += p.count;
        t.nonfinite += p.nonfinite;
        t.unsampled += p.count == 0 && inCrop(i);
    }
    return t;
}

std::vector<Channel> Film::aovChannels(const std::string& name) const {
    const size_t n = pixels.size();
    if (name == "samples") {
        Channel c{"samples", std::vector<float>(n)};
        for (size_t i = 0; i < n; ++i) c.values[i] = float(pixels[i].count);
        return {c};
    }
    if (name == "error") {
        Channel c{"error", pixelRelativeErrors(pixels)};
        for (float& v : c.values) v = float(v * errorScale);
        return {c};
    }
    if (name == "filled") return {{"filled", filledMask()}};
    for (const ShaderAov& a : shaderAovs)
        if (a.name == name && name != "z" && name != "N") return shaderAovChannels(a);
    if (name != "z" && name != "N")
        throw std::runtime_error("unknown AOV \"" + name +
                                 "\" (known: z, N, samples, error, filled)");
    if (aovs.size() != n)
        throw std::runtime_error("AOV \"" + name + "\" was not rendered");
    if (name == "z") {
        // Misses have no depth: +inf, as a depth compositor expects for empty pixels.
        Channel c{"Z", std::vector<float>(n, std::numeric_limits<float>::infinity())};
        for (size_t i = 0; i < n; ++i)
            if (aovs[i].hits) c.values[i] = aovs[i].z_sum / float(aovs[i].hits);
        return {c};
    }
    std::vector<Channel> out{{"N.X", std::vector<float>(n)},
                             {"N.Y", std::vector<float>(n)},
                             {"N.Z", std::vector<float>(n)}};
    for (size_t i = 0; i < n; ++i) {
        const rt_float4& s = aovs[i].normal_sum;
        float len = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
        if (len <= 0) continue;
        out[0].values[i] = s.x / len;
        out[1].values[i] = s.y / len;
        out[2].values[i] = s.z / len;
    }
    return out;
}

std::vector<Channel> Film::shaderAovChannels(const ShaderAov& a) const {
    const size_t n = pixels.size();
    if (shaderAovSums.size() != n * size_t(shaderAovFloats))
        throw std::runtime_error("AOV \"" + a.name + "\" was not rendered");
    const bool colour = a.type == "color";
    const int out = a.floats == 1 ? 1 : 3;
    static const char* rgb[] = {".R", ".G", ".B"};
    static const char* xyz[] = {".X", ".Y", ".Z"};
    std::vector<Channel> c(static_cast<size_t>(out));
    for (int j = 0; j < out; ++j)
        c[size_t(j)] = {out == 1 ? a.name : a.name + (colour ? rgb[j] : xyz[j]),
                        std::vector<float>(n)};
    std::vector<float> v(size_t(std::max(a.floats, 3)));
    for (size_t i = 0; i < n; ++i) {
        if (pixels[i].count == 0) continue;
        const float* sums =
            &shaderAovSums[i * size_t(shaderAovFloats) + size_t(a.offset)];
        std::copy(sums, sums + a.floats, v.begin());
        if (colour) colours.toRgbValues(v.data());  // the scene's channels to RGB
        for (int j = 0; j < out; ++j)
            c[size_t(j)].values[i] = v[size_t(j)] / float(pixels[i].count);
    }
    return c;
}

}  // namespace rd
