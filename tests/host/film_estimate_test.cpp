// film_estimate_test.cpp: the film (unreached pixels filled and flagged, the device's
// sums equal to the host's) and its error estimate (from whole samples, in batches, from
// two replicates), and the geometric AOVs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "film/film_error.h"
#include "film/film_error_batch.h"
#include "ocl/program.h"
#include "render/device_film_sums.h"
#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// Adds n samples to a pixel's sums: two channels level + noise * U(0, 1), the third
// level.
void addSamples(PixelAccum& p, uint32_t n, float level, float noise, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t k = 0; k < n; ++k) {
        const float v[3] = {level + noise * u(rng), level + noise * u(rng), level};
        p.sum.x += v[0], p.sum.y += v[1], p.sum.z += v[2];
        p.sum_sq.x += v[0] * v[0], p.sum_sq.y += v[1] * v[1], p.sum_sq.z += v[2] * v[2];
    }
    p.count += n;
}

}  // namespace

// Pixels with no sample take their nearest sampled neighbour's value and are flagged.
TEST(Film, UnreachedPixelsAreFilledAndFlagged) {
    rd::Film film;
    film.width = 4;
    film.height = 1;
    film.pixels.assign(4, PixelAccum{});
    film.pixels[0].sum = {2, 4, 6, 2};
    film.pixels[0].count = 2;
    film.pixels[3].sum = {9, 9, 9, 1};
    film.pixels[3].count = 1;
    auto rgba = film.resolve();
    EXPECT_EQ(rgba[1].r, 1.0f);  // from pixel 0
    EXPECT_EQ(rgba[2].r, 9.0f);  // from pixel 3
    auto mask = film.filledMask();
    EXPECT_EQ(mask, (std::vector<float>{0, 1, 1, 0}));
    EXPECT_EQ(film.tally().unsampled, 2u);
}

// The estimate follows the definition: sqrt(mean variance of the mean) / mean.
TEST(Film, ErrorEstimateFromWholeSamples) {
    rd::FilmPixels f(1);
    // samples 0 and 2 in every channel: mean 1, sample variance 2, variance of mean 1.
    f[0].sum = {2, 2, 2, 2};
    f[0].sum_sq = {4, 4, 4, 4};
    f[0].count = 2;
    EXPECT_NEAR(rd::estimateFilmErrors(f).spread, 1.0, 1e-6);
    f[0].count = 1;
    EXPECT_LT(rd::estimateFilmErrors(f).spread, 0.0) << "one sample has no variance";
}

// The film's estimate is summed by batches of pixels on the host's cores: within 1e-12 of
// the definition summed pixel by pixel, over a film of 90300 pixels (a short last batch)
// with empty, one-sample, black and stiff pixels (a level of 1e6, noise of 1e-3); also
// over one batch in eight (the renderer's Sobol ratio).
TEST(Film, ErrorEstimateInBatchesIsThePixelByPixelOne) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    rd::FilmPixels f(300 * 301);
    for (size_t i = 0; i < f.size(); ++i) {
        PixelAccum& p = f[i];
        const uint32_t n = i % 11 == 0 ? 0 : i % 11 == 1 ? 1 : 2 + uint32_t(i % 9);
        const float level = i % 7 == 0 ? 1e6f : i % 7 == 1 ? 0.0f : 0.2f + u(rng);
        addSamples(p, n, level, i % 7 == 0 ? 1e-3f : 0.3f * level, rng);
    }
    // over every pixel, or over the first batch of 64 pixels in every `stride` batches
    auto definition = [&](size_t stride) {
        double var = 0, mean = 0, withVar = 0, withMean = 0;
        for (size_t i = 0; i < f.size(); ++i) {
            const PixelAccum& p = f[i];
            if (p.count == 0 || (i / 64) % stride != 0) continue;
            const rd::PixelEstimate e = rd::estimatePixel(p);
            mean += e.mean, ++withMean;
            if (p.count >= 2) var += double(e.stdError) * e.stdError, ++withVar;
        }
        return std::sqrt(var / withVar) / (mean / withMean);
    };
    for (size_t stride : {1, 8}) {
        const double want = definition(stride);
        EXPECT_NEAR(rd::estimateFilmErrors(f, stride).spread, want, 1e-12 * want)
            << stride;
    }
    EXPECT_NE(definition(1), definition(8));
    f.resize(1000);  // one thread
    EXPECT_GT(rd::estimateFilmErrors(f).spread, 0.0);
}

// At the end of a frame the device sums the film's estimate and tally
// (device_film_sums.h): the host's values bit for bit, over a 300x301 film (a short last
// batch) of empty, one-sample, black and stiff pixels, samples in both replicates or one,
// samples dropped as NaN, and a crop window.
TEST(Film, DeviceSumsAreTheHostsBitForBit) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    rd::Film film;
    film.width = 300, film.height = 301;
    film.cropX0 = 7, film.cropX1 = 290, film.cropY0 = 3, film.cropY1 = 300;
    film.pixels.assign(size_t(film.width) * size_t(film.height), PixelAccum{});
    for (size_t i = 0; i < film.pixels.size(); ++i) {
        PixelAccum& p = film.pixels[i];
        const uint32_t n = i % 11 == 0 ? 0 : i % 11 == 1 ? 1 : 2 + uint32_t(i % 9);
        const float level = i % 7 == 0 ? 1e6f : i % 7 == 1 ? 0.0f : 0.2f + u(rng);
        for (uint32_t k = 0; k < n; ++k) {
            PixelAccum one{};
            addSamples(one, 1, level, i % 7 == 0 ? 1e-3f : 0.3f * level, rng);
            p.sum.x += one.sum.x, p.sum.y += one.sum.y, p.sum.z += one.sum.z;
            p.sum_sq.x += one.sum_sq.x, p.sum_sq.y += one.sum_sq.y,
                p.sum_sq.z += one.sum_sq.z;
            if (k % 2 == 1 && i % 5 != 0) {  // (every fifth pixel: one replicate only)
                p.sum_odd.x += one.sum.x, p.sum_odd.y += one.sum.y,
                    p.sum_odd.z += one.sum.z;
                p.sum_odd.w += 1.0f;
            }
        }
        p.count = n;
        p.nonfinite = i % 13 == 0 ? 2 : 0;
    }
    const rd::ClContext& ctx = rd::test::testContext();
    ASSERT_TRUE(ctx.info().fp64);
    rd::Program program(ctx, rd::assembleClSource({"film_sums.cl"}), "-cl-std=CL1.2");
    rd::Profiler prof(ctx);
    rd::DeviceBuffer<PixelAccum> filmBuf(ctx, film.pixels);
    rd::DeviceFilmSums sums(ctx, program.get(), prof, filmBuf, film);
    sums.launch();
    ctx.finish();
    const rd::FilmSummary s = sums.summary();
    const rd::FilmError want = rd::estimateFilmErrors(film.pixels);
    const rd::Film::Tally tally = film.tally();
    ASSERT_GT(want.spread, 0.0);
    ASSERT_GT(want.replicates, 0.0);
    EXPECT_EQ(s.error.spread, want.spread);
    EXPECT_EQ(s.error.replicates, want.replicates);
    EXPECT_EQ(s.tally.samples, tally.samples);
    EXPECT_EQ(s.tally.nonfinite, tally.nonfinite);
    EXPECT_EQ(s.tally.unsampled, tally.unsampled);
    EXPECT_GT(tally.unsampled, 0u);
    EXPECT_LT(tally.unsampled,
              film.pixels.size() / 11);  // (those off the window not counted)
}

// The Sobol sampler's estimate from two replicates (film.h sum_odd): a pixel's squared
// error is (mA - mB)^2 nA nB / n^2 per channel, averaged over the channels; none without
// samples of both. For independent samples split the same way it is an unbiased estimate
// of what the spread gives: over 40000 noisy pixels the two film estimates agree within
// 2%, also with uneven replicates (5 and 4 samples: PixelSamples 3 3).
TEST(Film, ReplicateEstimateIsTheErrorOfTheMeanOfTwoIndependentHalves) {
    PixelAccum p{};
    const float even[2][3] = {{1, 2, 0}, {3, 2, 0}}, odd[2][3] = {{0, 1, 0}, {0, 3, 0}};
    for (int k = 0; k < 2; ++k)
        for (int c = 0; c < 3; ++c) {
            (&p.sum.x)[c] += even[k][c] + odd[k][c];
            (&p.sum_odd.x)[c] += odd[k][c];
        }
    p.count = 4, p.sum_odd.w = 2;
    // means: even (2, 2, 0), odd (0, 2, 0): differences 2, 0, 0; nA nB / n^2 = 1/4
    EXPECT_DOUBLE_EQ(rd::replicateVariance(p), (4.0 * 0.25) / 3.0);
    PixelAccum none = p;
    none.sum_odd = {0, 0, 0, 0};
    EXPECT_LT(rd::replicateVariance(none), 0.0);
    none.sum_odd.w = 4;
    EXPECT_LT(rd::replicateVariance(none), 0.0);

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    rd::FilmPixels f(200 * 200);
    for (size_t i = 0; i < f.size(); ++i) {
        PixelAccum& q = f[i];
        const uint32_t n = i % 2 ? 8 : 9;
        const float level = 0.2f + u(rng);
        for (uint32_t k = 0; k < n; ++k) {
            const float v[3] = {level + 0.3f * u(rng), level + 0.3f * u(rng), level};
            for (int c = 0; c < 3; ++c) {
                (&q.sum.x)[c] += v[c], (&q.sum_sq.x)[c] += v[c] * v[c];
                if (k & 1) (&q.sum_odd.x)[c] += v[c];
            }
            q.sum_odd.w += float(k & 1);
        }
        q.count = n;
    }
    const rd::FilmError e = rd::estimateFilmErrors(f);
    EXPECT_NEAR(e.replicates / e.spread, 1.0, 0.02) << e.replicates << " " << e.spread;
    EXPECT_EQ(e.of(true), e.replicates);
    EXPECT_EQ(e.of(false), e.spread);
    EXPECT_EQ(e.spreadOverstates(false), 1.0);
    EXPECT_GE(e.spreadOverstates(true), 1.0);
}

// The planner measures pixels in batches (vector divisions and square roots on the
// widest vectors the host has): the same bits as pixelRelativeError, pixel by pixel, also
// on stiff pixels (a level of 1e6 with noise of 1e-3, where the sums of squares cancel),
// black ones, one-sample ones and ones above and below the brightness floor.
TEST(Film, BatchOfRelativeErrorsIsThePixelByPixelOne) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    rd::PixelSumsBatch b;
    std::vector<PixelAccum> pixels(rd::kPixelBatch);
    const float floor = 0.05f;
    for (size_t j = 0; j < rd::kPixelBatch; ++j) {
        PixelAccum& p = pixels[j];
        p = PixelAccum{};
        const uint32_t n = j % 7 == 0 ? 1 : 2 + uint32_t(j % 13);
        const float level = j % 5 == 0   ? 1e6f
                            : j % 5 == 1 ? 0.0f
                            : j % 5 == 2 ? 0.01f
                                         : 1.0f;
        addSamples(p, n, level, j % 5 == 0 ? 1e-3f : 0.3f * level, rng);
        b.n[j] = n, b.mean[j] = rd::pixelMean(p);
        b.s[0][j] = p.sum.x, b.s[1][j] = p.sum.y, b.s[2][j] = p.sum.z;
        b.q[0][j] = p.sum_sq.x, b.q[1][j] = p.sum_sq.y, b.q[2][j] = p.sum_sq.z;
    }
    float relErr[rd::kPixelBatch];
    rd::relativeErrors(b, floor, relErr);
    size_t stiff = 0, noisy = 0;
    for (size_t j = 0; j < rd::kPixelBatch; ++j) {
        const float want = rd::pixelRelativeError(pixels[j], floor);
        EXPECT_EQ(std::memcmp(&relErr[j], &want, sizeof want), 0)
            << "pixel " << j << ": " << relErr[j] << " against " << want;
        EXPECT_TRUE(std::isfinite(relErr[j])) << "pixel " << j;
        stiff += j % 5 == 0 && pixels[j].count > 1;
        noisy += want > 0.01f;
    }
    EXPECT_GT(stiff, 5u);
    EXPECT_GT(noisy, 10u);  // not all zero
}

// z and N AOVs of a plane facing the camera at distance 5.
TEST(Aov, DepthAndNormalOfAPlane) {
    rd::RenderSettings s;
    s.geometricAovs = true;
    Rendered img = renderRib(
        "Format 16 16 1\nPixelSamples 2 2\n"
        "Projection \"perspective\" \"fov\" 60\nWorldBegin\n"
        "Surface \"constant\"\n"
        "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
        "WorldEnd\n",
        s);
    auto z = img.film.aovChannels("z");
    auto n = img.film.aovChannels("N");
    ASSERT_EQ(z.size(), 1u);
    ASSERT_EQ(n.size(), 3u);
    for (float v : z[0].values) EXPECT_NEAR(v, 5.0f, 1e-3f);
    for (size_t i = 0; i < n[2].values.size(); ++i)
        EXPECT_NEAR(n[2].values[i], -1.0f, 1e-5f);
    auto samples = img.film.aovChannels("samples");
    EXPECT_EQ(samples[0].values[0], float(img.count(0, 0)));
}
