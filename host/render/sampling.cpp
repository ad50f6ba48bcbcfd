// sampling.cpp: the sample planner and the error estimates it and --stats use.
#include "sampling.h"

#include "film/film_error_batch.h"
#include "film/run_in_parts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace rd {

std::vector<uint32_t> tileOrder(int width, int x0, int x1, int y0, int y1) {
    constexpr int tile = 16;
    // a tile's (x, y) in Morton order: x the even bits of the code, y the odd ones
    std::array<uint8_t, tile * tile> mx{}, my{};
    for (int z = 0; z < tile * tile; ++z)
        for (int b = 0; b < 4; ++b) {
            mx[size_t(z)] |= uint8_t(((z >> (2 * b)) & 1) << b);
            my[size_t(z)] |= uint8_t(((z >> (2 * b + 1)) & 1) << b);
        }
    std::vector<uint32_t> order;
    order.reserve(size_t(std::max(0, x1 - x0)) * size_t(std::max(0, y1 - y0)));
    for (int ty = y0; ty < y1; ty += tile)
        for (int tx = x0; tx < x1; tx += tile) {
            const bool whole = tx + tile <= x1 && ty + tile <= y1;
            for (size_t z = 0; z < size_t(tile * tile); ++z) {
                const int x = tx + mx[z], y = ty + my[z];
                if (whole || (x < x1 && y < y1))
                    order.push_back(uint32_t(y) * uint32_t(width) + uint32_t(x));
            }
        }
    return order;
}

SamplePlanner::SamplePlanner(int width, int height, int x0, int x1, int y0, int y1,
                             const SamplingSettings& settings)
    : m_width(width), m_height(height), m_settings(settings) {
    m_settings.firstPassBlock = std::max(1, m_settings.firstPassBlock);
    m_settings.maxSamples = std::max(1u, m_settings.maxSamples);
    m_settings.minSamples = std::clamp(m_settings.minSamples, 1u, m_settings.maxSamples);
    m_tileOrder = tileOrder(width, x0, x1, y0, y1);
    m_tileRank.assign(size_t(width) * size_t(height), kOutside);
    for (size_t r = 0; r < m_tileOrder.size(); ++r) m_tileRank[m_tileOrder[r]] = uint32_t(r);
    // (allocated and touched here, on the thread that plans the first pass while the
    // program builds: the first adaptive pass, with the device idle, took 1-1.5 ms more)
    m_relErr.assign(size_t(width) * size_t(height), INFINITY);
    m_meanOf.assign(size_t(width) * size_t(height), -1.0f);
    m_lastPass.assign(m_tileOrder.size(), 0);  // (its memory touched; the first pass sets none)
    m_lastPass.clear();
}

inline std::array<uint32_t, 5> SamplePlanner::neighbourhood(uint32_t pixel) const {
    const uint32_t w = uint32_t(m_width), x = pixel % w, y = pixel / w;
    return {pixel, x > 0 ? pixel - 1 : pixel, x + 1 < w ? pixel + 1 : pixel,
            y > 0 ? pixel - w : pixel, y + 1 < uint32_t(m_height) ? pixel + w : pixel};
}

void SamplePlanner::measure(const FilmPixels& film, const uint32_t* pixels, size_t count,
                            float floor, float* relErr, uint8_t* edge) const {
    PixelSumsBatch b;
    for (size_t j = 0; j < kPixelBatch; ++j) {
        if (j >= count) {  // (a short batch: padded, its answers unused)
            b.n[j] = 2, b.mean[j] = 1.0f;
            for (int c = 0; c < 3; ++c) b.s[c][j] = 0.0f, b.q[c][j] = 0.0f;
            continue;
        }
        const uint32_t pixel = pixels[j];
        const PixelAccum& p = film[pixel];
        // (m_meanOf holds pixelMean of every pixel with samples: brightnessFloor)
        const float m = m_meanOf[pixel];
        b.n[j] = p.count, b.mean[j] = m;
        b.s[0][j] = p.sum.x, b.s[1][j] = p.sum.y, b.s[2][j] = p.sum.z;
        b.q[0][j] = p.sum_sq.x, b.q[1][j] = p.sum_sq.y, b.q[2][j] = p.sum_sq.z;
        // An edge both of whose samples fell on one side shows no variance: compare with
        // the neighbours' means instead (a neighbour off the image is the pixel itself:
        // no contrast; without samples, < 0).
        const std::array<uint32_t, 5> around = neighbourhood(pixel);
        unsigned contrast = 0;  // (bitwise: no branch per neighbour)
        for (int k = 1; k < 5; ++k) contrast |= unsigned(contrasts(m, m_meanOf[around[k]]));
        edge[j] = uint8_t(contrast);
    }
    float all[kPixelBatch];
    relativeErrors(b, floor, all);
    std::copy(all, all + count, relErr);
}

bool SamplePlanner::needsMore(uint32_t n, float relErr, bool edge, float pixelError,
                              float* keptErr) const {
    if (n >= m_settings.maxSamples) {
        *keptErr = -INFINITY;  // never again
        return false;
    }
    if (n < m_settings.minSamples) return true;
    *keptErr = relErr;
    return relErr > pixelError || edge;
}

// The first pass with blocks: one sample a block of firstPassBlock pixels, then every
// pixel up to the minimum.
const std::vector<PixelRequest>& SamplePlanner::firstBlockPass() {
    std::vector<PixelRequest>& out = m_out;
    const int b = m_settings.firstPassBlock;
    // One sample per block, at a pixel chosen by a hash so blocks show no pattern.
    for (uint32_t pixel : m_tileOrder) {
        int x = int(pixel % uint32_t(m_width)), y = int(pixel / uint32_t(m_width));
        int bx = x / b, by = y / b;
        uint32_t h = uint32_t(bx) * 73856093u ^ uint32_t(by) * 19349663u;
        int w = std::min(b, m_width - bx * b), hgt = std::min(b, m_height - by * b);
        int px = bx * b + int(h % uint32_t(w)),
            py = by * b + int((h / 7) % uint32_t(hgt));
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

// The test set (forEachToTest) in tile order, each pixel once: as bits by tile rank.
std::vector<uint32_t> SamplePlanner::testSetInTileOrder() const {
    std::vector<uint64_t> bits((m_tileOrder.size() + 63) / 64, 0);
    forEachToTest([&](uint32_t q) {
        if (const uint32_t r = m_tileRank[q]; r != kOutside)
            bits[r >> 6] |= 1ull << (r & 63);
    });
    std::vector<uint32_t> visit;
    for (size_t i = 0; i < bits.size(); ++i)
        for (uint64_t w = bits[i]; w; w &= w - 1)
            visit.push_back(m_tileOrder[i * 64 + size_t(__builtin_ctzll(w))]);
    return visit;
}

const std::vector<PixelRequest>& SamplePlanner::nextPass(
    const FilmPixels& film, float pixelError, const std::vector<uint8_t>& busy) {
    if (m_pass == 0 && m_settings.firstPassBlock > 1) return firstBlockPass();
    // A pixel's answer depends on its own samples, its neighbours' means and its relative
    // error against the pass's pixel error. A pixel that answered "no" when last tested (a
    // "yes" would have sampled it), whose samples have not changed since and whose
    // neighbours' means have not moved, answers "no" again while its error then is within
    // this pass's pixel error and has not grown: it grows only when the brightness floor
    // falls below the last one while the pixel's mean is under that (and it is not black).
    const float floor = brightnessFloor(film);
    const bool all = !m_settings.incremental || !m_tested;
    const bool floorFell = floor < m_lastFloor;
    // When the pixel error did not tighten and the floor did not fall, every pixel off the
    // test set answers "no" again: visit the test set alone (in tile order), not every
    // pixel, so that a pass costs what it samples (a 512x512 frame took 0.7 ms a pass
    // just to walk its pixels).
    const bool testedOnly = !all && !floorFell && pixelError >= m_lastPixelError;
    const std::vector<uint32_t> visit =
        testedOnly ? testSetInTileOrder() : std::vector<uint32_t>{};
    // (visiting the test set alone, every pixel visited is in it)
    const std::vector<uint8_t> test = pixelsToTest(all || testedOnly);
    if (all && m_tester) return passFromTester(film, floor, pixelError, busy);
    const PassVisit v{film, busy, test, floor, pixelError, floorFell};
    const std::vector<uint32_t>& order = testedOnly ? visit : m_tileOrder;
    // A large visit is cut into contiguous parts on the host's cores (threadsFor), joined
    // in order: the same pass whatever the number of threads.
    std::vector<PassPart> parts(threadsFor(order.size()));
    runInParts(order.size(), parts.size(), [&](size_t begin, size_t end, size_t t) {
        planPart(v, order.data() + begin, order.data() + end, parts[t]);
    });
    joinParts(parts);
    return endPass(film, floor, pixelError);
}

// A batch of pixels is measured before any is decided: with no branch between them the
// core overlaps their loads and divisions (a 512x512 full test on one thread took 8-9 ms
// measured and decided pixel by pixel).
void SamplePlanner::planPart(const PassVisit& v, const uint32_t* begin,
                             const uint32_t* end, PassPart& part) {
    uint32_t batch[kPixelBatch];
    float relErr[kPixelBatch];
    uint8_t edge[kPixelBatch];
    const uint32_t* next = begin;
    while (next < end) {
        // The next batch of pixels to measure. Busy ones are set aside (SPD teapot at 9
        // samples a pixel: 20-28k of the 30k pixels a pass visits), and so are those that
        // answer "no" as before without a test.
        size_t count = 0;
        for (; next < end && count < kPixelBatch; ++next) {
            const uint32_t pixel = *next;
            if (!v.busy.empty() && v.busy[pixel]) {
                part.deferred.push_back(pixel);
                continue;
            }
            if (answersNoAgain(v, pixel)) continue;
            __builtin_prefetch(&v.film[pixel]);  // (measured once the batch is full)
            batch[count++] = pixel;
        }
        measure(v.film, batch, count, v.floor, relErr, edge);
        for (size_t j = 0; j < count; ++j) {
            const uint32_t pixel = batch[j];
            if (needsMore(v.film[pixel].count, relErr[j], edge[j], v.pixelError,
                          &m_relErr[pixel]))
                requestMore(v.film[pixel], pixel, part);
        }
    }
}

bool SamplePlanner::answersNoAgain(const PassVisit& v, uint32_t pixel) {
    if (v.test.empty() || v.test[pixel] || !(m_relErr[pixel] <= v.pixelError))
        return false;
    if (!v.floorFell || m_meanOf[pixel] >= m_lastFloor) return true;
    const PixelAccum& p = v.film[pixel];
    if (p.sum_sq.x == 0.0f && p.sum_sq.y == 0.0f && p.sum_sq.z == 0.0f)
        return true;  // black
    // Under the fallen floor its error grew by at most the floors' ratio: while that
    // bound stays within the pixel error it answers "no" again, and the bound is kept as
    // its error (an upper bound from here on).
    const float bound = m_relErr[pixel] * (m_lastFloor / v.floor);
    if (!(bound <= v.pixelError)) return false;
    m_relErr[pixel] = bound;
    return true;
}

void SamplePlanner::requestMore(const PixelAccum& p, uint32_t pixel,
                                PassPart& part) const {
    const uint32_t n = p.count;
    // Sequence indices already used include samples dropped as NaN/Inf: never reuse.
    const uint32_t used = n + p.nonfinite;
    const uint32_t target = std::min(std::max(m_settings.minSamples, std::max(1u, 2 * n)),
                                     m_settings.maxSamples);
    if (target > n)
        part.out.push_back({pixel, used, target - n}), part.sampled.push_back(pixel);
}

void SamplePlanner::joinParts(const std::vector<PassPart>& parts) {
    m_lastPass.clear();
    size_t requests = 0, lastPass = 0;
    for (const PassPart& part : parts)
        requests += part.out.size(), lastPass += part.sampled.size() + part.deferred.size();
    m_out.clear();  // (its memory kept from pass to pass)
    m_out.reserve(requests);
    m_lastPass.reserve(lastPass);
    for (const PassPart& part : parts) {
        m_out.insert(m_out.end(), part.out.begin(), part.out.end());
        m_lastPass.insert(m_lastPass.end(), part.sampled.begin(), part.sampled.end());
    }
    for (const PassPart& part : parts)
        m_lastPass.insert(m_lastPass.end(), part.deferred.begin(), part.deferred.end());
}

const std::vector<PixelRequest>& SamplePlanner::endPass(const FilmPixels& film, float floor,
                                                        float pixelError) {
    jumpSmallPass(film, m_out);
    m_lastFloor = floor;
    m_lastPixelError = pixelError;
    m_tested = true;
    ++m_pass;
    return m_out;
}

const std::vector<PixelRequest>& SamplePlanner::passFromTester(
    const FilmPixels& film, float floor, float pixelError, const std::vector<uint8_t>& busy) {
    const PixelTester::Answers a = m_tester->test(m_meansByTester, floor, pixelError, busy);
    m_meansByTester = false;
    // The requests in tile order, most of them empty: each written where the next one
    // goes and kept by its count, without a branch a pixel (one that mispredicted took
    // 0.7 ms over 262k pixels), into m_out at its size from the first pass (one or two
    // requests a pixel): neither cleared nor faulted in here.
    const size_t n = m_tileOrder.size();
    std::vector<PixelRequest>& out = m_out;
    if (out.size() < n) out.resize(n);
    std::vector<uint32_t> deferred;
    size_t at = 0;
    for (size_t k = 0; k < n; ++k) {
        const uint32_t samples = a.request[2 * k];
        if (samples == PixelTester::kBusy) {  // (rare)
            deferred.push_back(m_tileOrder[k]);
            continue;
        }
        out[at] = {m_tileOrder[k], a.request[2 * k + 1], samples};
        at += samples != 0;
    }
    out.resize(at);
    m_lastPass.resize(at + deferred.size());
    for (size_t i = 0; i < at; ++i) m_lastPass[i] = out[i].pixel;
    std::copy(deferred.begin(), deferred.end(), m_lastPass.begin() + ptrdiff_t(at));
    for (size_t pixel = 0; pixel < m_relErr.size(); ++pixel)  // (NaN: its own kept)
        m_relErr[pixel] = std::isnan(a.relErr[pixel]) ? m_relErr[pixel] : a.relErr[pixel];
    return endPass(film, floor, pixelError);
}

void SamplePlanner::jumpSmallPass(const FilmPixels& film, std::vector<PixelRequest>& out) const {
    if (m_settings.smallPass == 0) return;
    // (the request's target is n + count: its pixel's samples after the pass)
    auto jumpedTarget = [&](const PixelRequest& r) {
        const uint64_t n = film[r.pixel].count;
        return std::min<uint64_t>(m_settings.maxSamples, 4 * (n + r.count));
    };
    uint64_t asked = 0, jumped = 0;
    for (const PixelRequest& r : out) asked += r.count;
    if (asked >= m_settings.smallPass) return;  // (most passes: no film read)
    for (const PixelRequest& r : out) jumped += jumpedTarget(r) - film[r.pixel].count;
    if (jumped > 4ull * m_settings.smallPass) return;
    for (PixelRequest& r : out) r.count = uint32_t(jumpedTarget(r) - film[r.pixel].count);
}

// A visit of `pixels` (6-7 ms for every pixel of a 512x512 frame on one core of this
// machine) runs on the host's cores when it is large. (While a full test runs the device
// waits for the next round's retire.)
size_t SamplePlanner::threadsFor(size_t pixels) const {
    if (pixels < m_settings.parallelPixels) return 1;
    return m_settings.planThreads > 0 ? m_settings.planThreads : hostThreads();
}

float SamplePlanner::brightnessFloor(const FilmPixels& film) {
    auto account = [&](uint32_t pixel, float sign) {
        if (m_meanOf[pixel] >= 0.0f) m_meanSum += sign * double(m_meanOf[pixel]), m_meanCount += sign;
    };
    if (!m_tested) {  // after the first pass: every pixel, a group of kPixelBatch at a time
        const size_t groups = (film.size() + kPixelBatch - 1) / kPixelBatch;
        std::vector<double> sums(groups), counts(groups);
        if (m_tester) {
            m_tester->means(m_meanOf.data(), sums.data(), counts.data());
            m_meansByTester = true;
        } else {
            runInParts(groups, threadsFor(film.size()), [&](size_t begin, size_t end, size_t) {
                for (size_t g = begin; g < end; ++g) {
                    double sum = 0, count = 0;
                    for (size_t pixel = g * kPixelBatch;
                         pixel < std::min(film.size(), (g + 1) * kPixelBatch); ++pixel) {
                        const float m = film[pixel].count ? pixelMean(film[pixel]) : -1.0f;
                        m_meanOf[pixel] = m;
                        if (m >= 0.0f) sum += double(m), count += 1.0;
                    }
                    sums[g] = sum, counts[g] = count;
                }
            });
        }
        m_meanSum = 0, m_meanCount = 0;  // the groups added in order, on one thread
        for (size_t g = 0; g < groups; ++g) m_meanSum += sums[g], m_meanCount += counts[g];
    } else {  // only the pixels sampled (or left busy) in the last pass have changed
        m_meanMoved.clear();
        for (uint32_t pixel : m_lastPass) {
            account(pixel, -1.0f);
            const float was = m_meanOf[pixel];
            m_meanOf[pixel] = film[pixel].count ? pixelMean(film[pixel]) : -1.0f;
            if (std::memcmp(&was, &m_meanOf[pixel], sizeof was) != 0) m_meanMoved.push_back(pixel);
            account(pixel, 1.0f);
        }
    }
    return relativeErrorFloorOf(m_meanSum, m_meanCount);
}

std::vector<uint8_t> SamplePlanner::pixelsToTest(bool all) const {
    if (all) return {};  // nextPass tests every pixel without looking
    std::vector<uint8_t> test(size_t(m_width) * size_t(m_height), 0);
    forEachToTest([&](uint32_t q) { test[q] = 1; });
    return test;
}

}  // namespace rd
