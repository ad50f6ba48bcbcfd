// sampling.cpp: the sample planner and the error estimates it and --stats use.
#include "sampling.h"

#include <algorithm>
#include <cmath>

namespace rd {

SamplePlanner::SamplePlanner(int width, int height, int x0, int x1, int y0, int y1,
                             const SamplingSettings& settings)
    : m_width(width), m_height(height), m_settings(settings) {
    m_settings.firstPassBlock = std::max(1, m_settings.firstPassBlock);
    m_settings.maxSamples = std::max(1u, m_settings.maxSamples);
    m_settings.minSamples = std::clamp(m_settings.minSamples, 1u, m_settings.maxSamples);
    const int tile = 16;
    m_tileOrder.reserve(size_t(width) * size_t(height));
    for (int ty = y0; ty < y1; ty += tile)
        for (int tx = x0; tx < x1; tx += tile)
            for (int y = ty; y < std::min(ty + tile, y1); ++y)
                for (int x = tx; x < std::min(tx + tile, x1); ++x)
                    m_tileOrder.push_back(uint32_t(y) * uint32_t(width) + uint32_t(x));
}

bool SamplePlanner::needsMore(const FilmPixels& film, float floor, int x, int y,
                              float pixelError, float* relErr) const {
    size_t i = size_t(y) * size_t(m_width) + size_t(x);
    uint32_t n = film[i].count;
    if (n >= m_settings.maxSamples) {
        *relErr = -INFINITY;  // never again
        return false;
    }
    if (n < m_settings.minSamples) return true;
    *relErr = pixelRelativeError(film[i], floor);
    if (*relErr > pixelError) return true;
    // An edge both of whose samples fell on one side shows no variance: compare with the
    // neighbours' means instead.
    float m = pixelMean(film[i]);
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
        int nx = x + dx[k], ny = y + dy[k];
        if (nx < 0 || ny < 0 || nx >= m_width || ny >= m_height) continue;
        const PixelAccum& q = film[size_t(ny) * size_t(m_width) + size_t(nx)];
        if (q.count == 0) continue;
        float mq = pixelMean(q);
        if (std::fabs(m - mq) > m_settings.contrast * std::max(0.1f, 0.5f * (m + mq)))
            return true;
    }
    return false;
}

std::vector<PixelRequest> SamplePlanner::nextPass(const FilmPixels& film,
                                                  float pixelError) {
    std::vector<PixelRequest> out;
    const int b = m_settings.firstPassBlock;
    if (m_pass == 0 && b > 1) {
        // One sample per block, at a pixel chosen by a hash so blocks show no pattern.
        for (uint32_t pixel : m_tileOrder) {
            int x = int(pixel % uint32_t(m_width)), y = int(pixel / uint32_t(m_width));
            int bx = x / b, by = y / b;
            uint32_t h = uint32_t(bx) * 73856093u ^ uint32_t(by) * 19349663u;
            int w = std::min(b, m_width - bx * b), hgt = std::min(b, m_height - by * b);
            int px = bx * b + int(h % uint32_t(w)), py = by * b + int((h / 7) % uint32_t(hgt));
            if (px == x && py == y) out.push_back({pixel, 0, 1});
        }
        // Then every pixel up to the minimum, which needs no film to decide, in the same
        // pass: the ray pool streams on instead of draining between the two.
        const size_t blockSamples = out.size();
        std::vector<uint8_t> sampled(size_t(m_width) * size_t(m_height), 0);
        for (size_t k = 0; k < blockSamples; ++k) sampled[out[k].pixel] = 1;
        for (uint32_t pixel : m_tileOrder) {
            uint32_t have = sampled[pixel];
            if (m_settings.minSamples > have)
                out.push_back({pixel, have, m_settings.minSamples - have});
        }
        ++m_pass;
        return out;
    }
    // A pixel's answer depends on its own samples, its neighbours' means and its relative
    // error against the pass's pixel error. A pixel that answered "no" when last tested (a
    // "yes" would have sampled it) and that neither it nor a neighbour was sampled since
    // answers "no" again while its error then is within this pass's pixel error and has
    // not grown: it grows only when the brightness floor falls below the last one while
    // the pixel's mean is under that (and it is not black).
    const float floor = relativeErrorFloor(film);
    const bool all = !m_settings.incremental || m_relErr.empty();
    if (m_relErr.empty()) m_relErr.assign(size_t(m_width) * size_t(m_height), INFINITY);
    const std::vector<uint8_t> test = pixelsToTest(all);
    const bool floorFell = floor < m_lastFloor;
    m_lastPass.clear();
    for (uint32_t pixel : m_tileOrder) {
        if (!all && !test[pixel] && m_relErr[pixel] <= pixelError) {
            const PixelAccum& p = film[pixel];
            if (!floorFell || pixelMean(p) >= m_lastFloor) continue;
            if (p.sum_sq.x == 0.0f && p.sum_sq.y == 0.0f && p.sum_sq.z == 0.0f) continue;  // black
        }
        int x = int(pixel % uint32_t(m_width)), y = int(pixel / uint32_t(m_width));
        if (!needsMore(film, floor, x, y, pixelError, &m_relErr[pixel])) continue;
        uint32_t n = film[pixel].count;
        // Sequence indices already used include samples dropped as NaN/Inf: never reuse.
        uint32_t used = n + film[pixel].nonfinite;
        uint32_t target = std::max(m_settings.minSamples, std::max(1u, 2 * n));
        target = std::min(target, m_settings.maxSamples);
        if (target > n) out.push_back({pixel, used, target - n}), m_lastPass.push_back(pixel);
    }
    m_lastFloor = floor;
    ++m_pass;
    return out;
}

std::vector<uint8_t> SamplePlanner::pixelsToTest(bool all) const {
    if (all) return {};  // nextPass tests every pixel without looking
    std::vector<uint8_t> test(size_t(m_width) * size_t(m_height), 0);
    for (uint32_t pixel : m_lastPass) {
        int x = int(pixel % uint32_t(m_width)), y = int(pixel / uint32_t(m_width));
        test[pixel] = 1;
        if (x > 0) test[pixel - 1] = 1;
        if (x + 1 < m_width) test[pixel + 1] = 1;
        if (y > 0) test[pixel - uint32_t(m_width)] = 1;
        if (y + 1 < m_height) test[pixel + uint32_t(m_width)] = 1;
    }
    return test;
}

}  // namespace rd
