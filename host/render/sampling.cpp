// sampling.cpp: the sample planner and the error estimates it and --stats use.
#include "sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <thread>

namespace rd {

SamplePlanner::SamplePlanner(int width, int height, int x0, int x1, int y0, int y1,
                             const SamplingSettings& settings)
    : m_width(width), m_height(height), m_settings(settings) {
    m_settings.firstPassBlock = std::max(1, m_settings.firstPassBlock);
    m_settings.maxSamples = std::max(1u, m_settings.maxSamples);
    m_settings.minSamples = std::clamp(m_settings.minSamples, 1u, m_settings.maxSamples);
    const int tile = 16;
    m_tileOrder.reserve(size_t(width) * size_t(height));
    m_tileRank.assign(size_t(width) * size_t(height), kOutside);
    for (int ty = y0; ty < y1; ty += tile)
        for (int tx = x0; tx < x1; tx += tile)
            for (int y = ty; y < std::min(ty + tile, y1); ++y)
                for (int x = tx; x < std::min(tx + tile, x1); ++x) {
                    const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
                    m_tileRank[pixel] = uint32_t(m_tileOrder.size());
                    m_tileOrder.push_back(pixel);
                }
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
    // neighbours' means instead (kept by brightnessFloor, up to date for every pixel).
    // (a neighbour off the image is the pixel itself: no contrast; without samples, < 0)
    const float m = m_meanOf[i];
    const std::array<uint32_t, 5> around = neighbourhood(uint32_t(i));
    for (int k = 1; k < 5; ++k) {
        const float mq = m_meanOf[around[k]];
        if (mq >= 0.0f &&
            std::fabs(m - mq) > m_settings.contrast * std::max(0.1f, 0.5f * (m + mq)))
            return true;
    }
    return false;
}

std::vector<PixelRequest> SamplePlanner::nextPass(const FilmPixels& film, float pixelError,
                                                  const std::vector<uint8_t>& busy) {
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
    const float floor = brightnessFloor(film);
    const bool all = !m_settings.incremental || m_relErr.empty();
    if (m_relErr.empty()) m_relErr.assign(size_t(m_width) * size_t(m_height), INFINITY);
    const bool floorFell = floor < m_lastFloor;
    // When the pixel error did not tighten and the floor did not fall, every pixel off the
    // test set answers "no" again: visit the test set alone (in tile order), not every
    // pixel, so that a pass costs what it samples (a 512x512 frame took 0.7 ms a pass
    // just to walk its pixels).
    const bool testedOnly = !all && !floorFell && pixelError >= m_lastPixelError;
    std::vector<uint32_t> visit;
    if (testedOnly) {  // the test set as bits by tile rank: sorted, each pixel once
        std::vector<uint64_t> bits((m_tileOrder.size() + 63) / 64, 0);
        for (uint32_t pixel : m_lastPass)
            for (uint32_t q : neighbourhood(pixel))
                if (const uint32_t r = m_tileRank[q]; r != kOutside) bits[r >> 6] |= 1ull << (r & 63);
        for (size_t i = 0; i < bits.size(); ++i)
            for (uint64_t w = bits[i]; w; w &= w - 1)
                visit.push_back(m_tileOrder[i * 64 + size_t(__builtin_ctzll(w))]);
    }
    // (visiting the test set alone, every pixel visited is in it)
    const std::vector<uint8_t> test = pixelsToTest(all || testedOnly);
    // The pixels of `order` in [begin, end): their requests, the pixels sampled and those
    // left busy (deferred: tested next pass, with their neighbours).
    struct Part {
        std::vector<PixelRequest> out;
        std::vector<uint32_t> sampled, deferred;
    };
    const std::vector<uint32_t>& order = testedOnly ? visit : m_tileOrder;
    auto plan = [&](size_t begin, size_t end, Part& part) {
        for (size_t k = begin; k < end; ++k) {
            const uint32_t pixel = order[k];
            if (!busy.empty() && busy[pixel]) {
                part.deferred.push_back(pixel);
                continue;
            }
            if (!test.empty() && !test[pixel] && m_relErr[pixel] <= pixelError) {
                const PixelAccum& p = film[pixel];
                if (!floorFell || m_meanOf[pixel] >= m_lastFloor) continue;
                if (p.sum_sq.x == 0.0f && p.sum_sq.y == 0.0f && p.sum_sq.z == 0.0f) continue;  // black
                // Under the fallen floor its error grew by at most the floors' ratio: while
                // that bound stays within the pixel error it answers "no" again, and the
                // bound is kept as its error (an upper bound from here on).
                const float bound = m_relErr[pixel] * (m_lastFloor / floor);
                if (bound <= pixelError) {
                    m_relErr[pixel] = bound;
                    continue;
                }
            }
            int x = int(pixel % uint32_t(m_width)), y = int(pixel / uint32_t(m_width));
            if (!needsMore(film, floor, x, y, pixelError, &m_relErr[pixel])) continue;
            uint32_t n = film[pixel].count;
            // Sequence indices already used include samples dropped as NaN/Inf: never reuse.
            uint32_t used = n + film[pixel].nonfinite;
            uint32_t target = std::max(m_settings.minSamples, std::max(1u, 2 * n));
            target = std::min(target, m_settings.maxSamples);
            if (target > n) part.out.push_back({pixel, used, target - n}), part.sampled.push_back(pixel);
        }
    };
    // A full test (every pixel: 9 ms at 512x512 on this machine's core) is cut into
    // contiguous parts on the host's cores, joined in order: the same pass whatever the
    // number of threads. (While it runs the device waits for the next round's retire.)
    const size_t threads =
        order.size() < m_settings.parallelPixels ? 1
        : m_settings.planThreads > 0 ? m_settings.planThreads
                                     : std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 8);
    std::vector<Part> parts(threads);
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t)
        pool.emplace_back(plan, order.size() * t / threads, order.size() * (t + 1) / threads,
                          std::ref(parts[t]));
    plan(0, order.size() / threads, parts[0]);
    for (std::thread& th : pool) th.join();
    m_lastPass.clear();
    for (Part& part : parts) {
        out.insert(out.end(), part.out.begin(), part.out.end());
        m_lastPass.insert(m_lastPass.end(), part.sampled.begin(), part.sampled.end());
    }
    for (Part& part : parts) m_lastPass.insert(m_lastPass.end(), part.deferred.begin(), part.deferred.end());
    m_lastFloor = floor;
    m_lastPixelError = pixelError;
    ++m_pass;
    return out;
}

std::array<uint32_t, 5> SamplePlanner::neighbourhood(uint32_t pixel) const {
    const uint32_t w = uint32_t(m_width), x = pixel % w, y = pixel / w;
    return {pixel, x > 0 ? pixel - 1 : pixel, x + 1 < w ? pixel + 1 : pixel,
            y > 0 ? pixel - w : pixel, y + 1 < uint32_t(m_height) ? pixel + w : pixel};
}

float SamplePlanner::brightnessFloor(const FilmPixels& film) {
    auto account = [&](uint32_t pixel, float sign) {
        if (m_meanOf[pixel] >= 0.0f) m_meanSum += sign * double(m_meanOf[pixel]), m_meanCount += sign;
    };
    if (m_meanOf.empty()) {  // after the first pass: every pixel
        m_meanOf.assign(film.size(), -1.0f);
        m_meanSum = 0, m_meanCount = 0;
        for (uint32_t pixel = 0; pixel < film.size(); ++pixel)
            if (film[pixel].count) m_meanOf[pixel] = pixelMean(film[pixel]), account(pixel, 1.0f);
    } else {  // only the pixels sampled (or left busy) in the last pass have changed
        for (uint32_t pixel : m_lastPass) {
            account(pixel, -1.0f);
            m_meanOf[pixel] = film[pixel].count ? pixelMean(film[pixel]) : -1.0f;
            account(pixel, 1.0f);
        }
    }
    return relativeErrorFloorOf(m_meanSum, m_meanCount);
}

std::vector<uint8_t> SamplePlanner::pixelsToTest(bool all) const {
    if (all) return {};  // nextPass tests every pixel without looking
    std::vector<uint8_t> test(size_t(m_width) * size_t(m_height), 0);
    for (uint32_t pixel : m_lastPass) {
        for (uint32_t q : neighbourhood(pixel)) test[q] = 1;
    }
    return test;
}

}  // namespace rd
