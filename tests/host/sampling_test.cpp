// sampling_test.cpp: adaptive sampling (its incremental planning equal to testing every
// pixel), the samplers, budgets and fail-soft stops. Render tests run on PoCL. The film
// and its error estimate: film_estimate_test.cpp.
#include <chrono>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "film/film_error.h"
#include "film/film_error_batch.h"
#include "ocl/program.h"
#include "render/device_film_sums.h"
#include "render/device_pixel_tests.h"
#include "render/sampling.h"
#include "render/stop.h"
#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// The renderer's pixel order: every pixel of the window once, tile by 16x16 tile, each
// tile in Morton order (eight consecutive pixels a 4x2 block: a packet's eye rays), the
// tiles cut at the window's edges.
TEST(Sampling, TileOrderIsMortonWithinTiles) {
    const int width = 40, x0 = 3, x1 = 37, y0 = 2, y1 = 21;  // tiles cut on every side
    const std::vector<uint32_t> order = rd::tileOrder(width, x0, x1, y0, y1);
    ASSERT_EQ(order.size(), size_t((x1 - x0) * (y1 - y0)));
    std::vector<uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
    for (uint32_t p : order) {
        const int x = int(p % width), y = int(p / width);
        EXPECT_TRUE(x >= x0 && x < x1 && y >= y0 && y < y1) << x << " " << y;
    }
    // the first tile is whole: its first eight pixels are the 4x2 block at its corner,
    // then the next 4x2 below it (z order), and its 256 pixels come before any other's
    for (int k = 0; k < 8; ++k) {
        const int x = x0 + (k & 1) + 2 * (k >> 2), y = y0 + (k >> 1 & 1);
        EXPECT_EQ(order[size_t(k)], uint32_t(y * width + x)) << k;
    }
    for (int k = 8; k < 16; ++k)
        EXPECT_EQ(order[size_t(k)] / width, uint32_t(y0 + 2 + (k >> 1 & 1)));
    for (size_t k = 0; k < 256; ++k) {
        EXPECT_LT(int(order[k] % width), x0 + 16);
        EXPECT_LT(int(order[k] / width), y0 + 16);
    }
}

// Orthographic camera with 1 unit = 1 pixel, origin at the image centre.
std::string orthoCamera(int res, int spp, const std::string& renderOptions = "") {
    std::string half = std::to_string(res / 2);
    return "Format " + std::to_string(res) + " " + std::to_string(res) + " 1\nPixelSamples " +
           std::to_string(spp) + " " + std::to_string(spp) + "\nProjection \"orthographic\"\n" +
           "ScreenWindow -" + half + " " + half + " -" + half + " " + half + "\n" +
           renderOptions + "Translate 0 0 5\n";
}

std::string rect(double x0, double x1, double y0, double y1) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "Polygon \"P\" [%g %g 0  %g %g 0  %g %g 0  %g %g 0]\n", x0,
                  y0, x1, y0, x1, y1, x0, y1);
    return buf;
}

// Thin vertical stripes, 0.3 px wide every 0.713 px: every pixel is partly covered, so
// each sample is a coin toss and the pixel mean is a plain Monte Carlo estimate.
std::string stripes(int res) {
    std::string s = "WorldBegin\nSurface \"constant\"\n";
    for (double x = -res / 2.0; x < res / 2.0; x += 0.713) s += rect(x, x + 0.3, -res, res);
    return s + "WorldEnd\n";
}

// A res x res plane of a shader `name` that returns random() (written to a scratch folder
// of `test`): no contrast between pixels, and each pixel's samples stratified under the
// Sobol sampler, so that the samples' spread overstates their error. spp x spp samples,
// pixel error 0.1: adaptive.
std::string grainPlane(const std::string& test, const std::string& name, int res, int spp) {
    const std::string dir = rd::test::scratchDir(test);
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/" + name + ".sl")
        << "surface " << name << "() {\n    Ci = random();\n    Oi = 1;\n}\n";
    const double h = res / 2.0;
    return orthoCamera(res, spp,
                       "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n"
                       "Option \"render\" \"float pixelerror\" [0.1]\n") +
           "WorldBegin\nSurface \"" + name + "\"\n" + rect(-h, h, -h, h) + "WorldEnd\n";
}

// Pixels whose sample count or red channel differ between two renders of one frame.
size_t pixelsDiffering(const Rendered& a, const Rendered& b) {
    size_t differ = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            differ += a.count(x, y) != b.count(x, y) || a.at(x, y).r != b.at(x, y).r;
    return differ;
}

}  // namespace

// Each pass re-tests only the pixels whose answer can have changed; the passes must be
// exactly those of testing every pixel. Both planners plan from one synthetic film (a
// crop window of it) where each requested sample adds a value drawn per pixel and sample
// index. Also with a pixel error that tightens pass by pass (a time
// budget's), where every pixel is re-tested.
// The planners that test every pixel on the device (device_pixel_tests.h: the first
// adaptive pass of one incremental, every pass of one that is not) must plan the same
// passes, bit for bit.
// With `overlap`, a third of each pass's pixels are still in flight when the next pass is
// planned (the renderer plans while a pass's tail drains): both planners get them as
// busy, must not sample them, and see their samples only after that plan; a quarter of
// those stay in flight through three plans (a busy pixel's mean does not move: its
// neighbours need no new test until it does). One case each of (small passes quadrupled,
// overlapped, tightening), so that a run can take a few of them (the Oclgrind subset
// takes two: the interpreter needs 8 s a case).
class IncrementalPlan : public ::testing::TestWithParam<std::tuple<bool, bool, bool>> {};

TEST_P(IncrementalPlan, IsExact) {
    {
        const uint32_t smallPass = std::get<0>(GetParam()) ? 1000u : 0u;
        const bool overlap = std::get<1>(GetParam()),
                   tightening = std::get<2>(GetParam());
        const int w = 97, h = 61;
        rd::SamplingSettings s;
        s.maxSamples = 64;
        s.pixelError = 0.02f;
        s.smallPass = smallPass;
        rd::SamplingSettings full = s;
        full.incremental = false;
        full.parallelPixels = 1;  // every pass's visit split across three threads
        full.planThreads = 3;
        rd::SamplePlanner inc(w, h, 3, 90, 2, 58, s), ref(w, h, 3, 90, 2, 58, full);
        rd::FilmPixels film(size_t(w) * size_t(h));
        const rd::ClContext& ctx = rd::test::testContext();
        ASSERT_TRUE(ctx.info().fp64);
        rd::Program program(ctx, rd::assembleClSource({"pixel_tests.cl"}), "-cl-std=CL1.2");
        rd::Profiler prof(ctx);
        rd::DeviceBuffer<PixelAccum> filmBuf(ctx, film.size(), CL_MEM_READ_ONLY);
        rd::SamplePlanner dev(w, h, 3, 90, 2, 58, s), devAll(w, h, 3, 90, 2, 58, full);
        rd::DevicePixelTests devTests(ctx, program.get(), prof, filmBuf, w, h, dev,
                                      rd::PixelTestMemory(dev, w, h)),
            devAllTests(ctx, program.get(), prof, filmBuf, w, h, devAll,
                        rd::PixelTestMemory(devAll, w, h));
        dev.setTester(&devTests);
        devAll.setTester(&devAllTests);
        auto sample = [&](uint32_t pixel, uint32_t index) {
            const int x = int(pixel) % w, y = int(pixel) / w;
            std::mt19937 rng(pixel * 7919u + index);
            std::uniform_real_distribution<float> u(0.0f, 1.0f);
            const float dx = float(x - 30), dy = float(y - 30);
            // a dark disc; a bright band whose first samples are brighter still, so that
            // the brightness floor (0.1 of the image's mean) falls as samples come in;
            // elsewhere mild noise on a level that ramps across the floor, so that pixels
            // near it change answers as it moves
            float v = dx * dx + dy * dy < 300.0f ? 0.002f * u(rng)
                      : x > 80 ? (index < 2 ? 6.0f : 2.0f)
                               : (0.015f + 0.0004f * float(x)) * (0.9f + 0.2f * u(rng));
            // and below, a flat region left of one whose mean drifts as it is sampled:
            // the flat pixels at the border turn into edges only by their neighbour's
            // samples
            if (y >= 45) v = x < 40 ? 1.1f : (index < 2 ? 1.2f : 1.0f);
            PixelAccum& p = film[pixel];
            p.sum.x += v, p.sum.y += v, p.sum.z += v, p.sum.w += 1.0f;
            p.sum_sq.x += v * v, p.sum_sq.y += v * v, p.sum_sq.z += v * v;
            ++p.count;
        };
        size_t passes = 0, samples = 0, deferred = 0;
        // overlap: requests not retired yet, and how many more plans each stays through
        std::vector<std::pair<rd::PixelRequest, int>> inFlight;
        auto retire = [&](const rd::PixelRequest& r) {
            for (uint32_t k = 0; k < r.count; ++k) sample(r.pixel, r.first + k), ++samples;
        };
        for (float err = s.pixelError;; err *= tightening ? 0.7f : 1.0f) {
            std::vector<uint8_t> busy(overlap ? film.size() : 0, 0);
            for (const auto& [r, plans] : inFlight) busy[r.pixel] = 1;
            std::vector<rd::PixelRequest> a = inc.nextPass(film, err, busy),
                                          b = ref.nextPass(film, err, busy);
            filmBuf.uploadRange(0, film.data(), film.size());
            for (rd::SamplePlanner* onDevice : {&dev, &devAll}) {
                const std::vector<rd::PixelRequest> c = onDevice->nextPass(film, err, busy);
                ASSERT_EQ(c.size(), a.size()) << "pass " << passes;
                for (size_t i = 0; i < c.size(); ++i)
                    ASSERT_TRUE(c[i].pixel == a[i].pixel && c[i].first == a[i].first &&
                                c[i].count == a[i].count)
                        << "pass " << passes << ", request " << i;
                ASSERT_EQ(onDevice->lastFloor(), inc.lastFloor());
            }
            ASSERT_EQ(a.size(), b.size()) << "pass " << passes;
            if (passes > 0) {  // the floor and the means kept up to date pass by pass
                const float floor = rd::relativeErrorFloor(film);
                ASSERT_NEAR(inc.lastFloor(), floor, 1e-6f * floor) << "pass " << passes;
                for (uint32_t p = 0; p < film.size(); ++p)
                    ASSERT_EQ(inc.meanUsed(p), film[p].count ? rd::pixelMean(film[p]) : -1.0f)
                        << "pass " << passes << ", pixel " << p;
            }
            for (size_t i = 0; i < a.size(); ++i) {
                ASSERT_EQ(a[i].pixel, b[i].pixel) << "pass " << passes << ", request " << i;
                ASSERT_EQ(a[i].first, b[i].first);
                ASSERT_EQ(a[i].count, b[i].count);
                if (overlap) {
                    ASSERT_FALSE(busy[a[i].pixel]) << "a busy pixel sampled";
                }
            }
            const bool anyBusy = !inFlight.empty();
            std::vector<std::pair<rd::PixelRequest, int>> still;
            for (auto& [r, plans] : inFlight)
                if (plans > 1) still.push_back({r, plans - 1});
                else retire(r);
            inFlight.swap(still);
            if (a.empty() && !anyBusy) break;
            for (const rd::PixelRequest& r : a) {
                if (overlap && (r.pixel * 2654435761u + uint32_t(passes)) % 3u == 0u)
                    inFlight.push_back({r, 1 + int(r.pixel % 4 == 0) * 2}), ++deferred;
                else
                    retire(r);
            }
            ++passes;
            ASSERT_LT(passes, 60u);
        }
        std::printf("%s%s%s: %zu passes, %zu samples, %zu requests planned beside busy pixels\n",
                    tightening ? "tightening" : "fixed", overlap ? ", overlapped" : "",
                    smallPass ? ", small passes quadrupled" : "", passes, samples, deferred);
        EXPECT_GE(passes, 5u);  // several adaptive passes, not just the first two
        if (overlap) {
            EXPECT_GT(deferred, 100u);
        }
    }
}
INSTANTIATE_TEST_SUITE_P(
    Sampling, IncrementalPlan,
    ::testing::Combine(::testing::Bool(), ::testing::Bool(), ::testing::Bool()),
    [](const ::testing::TestParamInfo<std::tuple<bool, bool, bool>>& info) {
        return std::string(std::get<0>(info.param) ? "SmallPasses" : "Passes") +
               (std::get<1>(info.param) ? "Overlapped" : "") +
               (std::get<2>(info.param) ? "Tightening" : "Fixed");
    });

// An edge gets more samples than a flat region: left half covered, right half empty, the
// edge at x = 0.37 inside a pixel column. PixelSamples 8x8 caps pixels at 64.
TEST(Sampling, EdgePixelsGetMoreSamplesThanFlatOnes) {
    Rendered img = renderRib(orthoCamera(32, 8) +
                             "WorldBegin\nSurface \"constant\"\n" + rect(-40, 0.37, -40, 40) +
                             "WorldEnd\n");
    int edgeColumn = 16;  // pixel [16, 17) holds x = 0.37
    double edge = 0, flat = 0;
    for (int y = 0; y < 32; ++y) {
        edge += img.count(edgeColumn, y);
        flat += img.count(4, y) + img.count(28, y);
    }
    edge /= 32;
    flat /= 64;
    std::printf("samples per pixel: edge %.1f, flat %.1f\n", edge, flat);
    EXPECT_GE(edge, 32.0);
    EXPECT_LE(flat, 2.0);
    // Coverage of the edge column: 64 iid samples per pixel, 32 pixels: sigma ~ 0.011.
    EXPECT_NEAR(img.mean(3, edgeColumn, 0, edgeColumn + 1, 32), 0.37, 0.045);
}

// A frame of 256x256 pixels (the device's size for it: RenderSettings::devicePixelTestsFrom)
// has its first adaptive pass's tests and its error estimate on the device: the image,
// every pixel's samples, the passes and the estimate are those of the host's tests, bit
// for bit. Also with a crop window (pixels off it never sampled, nor counted unsampled).
TEST(Sampling, DeviceTestsRenderTheHostsImage) {
    for (const std::string crop : {"", "CropWindow 0.1 0.8 0.25 1\n"}) {
        // stripes on the left (every pixel noisy), a flat half on the right (pixels done at
        // the least samples), and an edge between
        std::string world = "WorldBegin\nSurface \"constant\"\n" + rect(0.37, 200, -200, 200);
        for (double x = -128; x < 0; x += 0.713) world += rect(x, x + 0.3, -200, 200);
        const std::string rib = orthoCamera(256, 3, crop) + world + "WorldEnd\n";
        rd::RenderSettings onDevice, onHost;
        onHost.devicePixelTests = false;
        Rendered a = renderRib(rib, onDevice), b = renderRib(rib, onHost);
        auto launches = [](const Rendered& r, const char* kernel) {
            const auto it = r.stats.kernels.find(kernel);
            return it == r.stats.kernels.end() ? uint64_t(0) : it->second.launches;
        };
        EXPECT_EQ(launches(a, "film_tests"), 1u);
        EXPECT_EQ(launches(a, "film_sums"), 1u);
        EXPECT_EQ(launches(b, "film_tests") + launches(b, "film_sums"), 0u);
        EXPECT_GE(a.stats.passes, 3);
        EXPECT_EQ(a.stats.passes, b.stats.passes);
        EXPECT_EQ(a.stats.filmSamples, b.stats.filmSamples);
        EXPECT_EQ(a.stats.unsampledPixels, b.stats.unsampledPixels);
        EXPECT_EQ(a.stats.estimatedError, b.stats.estimatedError);
        EXPECT_EQ(pixelsDiffering(a, b), 0u);
        std::printf("%s: %d passes, %llu samples, error %.4f\n", crop.empty() ? "frame" : "crop",
                    a.stats.passes, (unsigned long long)a.stats.filmSamples,
                    a.stats.estimatedError);
    }
}

// A small pool (many rounds a pass): each pass after the first is planned while the last
// one's tail is in flight, around its pixels. A pixel planned while its samples were in
// flight would reuse their sample indices and end with a count off the planner's doubling
// (6, 10, ...); two of its jobs in flight at once would race in the film. The image is
// the same Monte Carlo estimate either way.
TEST(Sampling, OverlappedPassesPlanAroundTheTail) {
    const std::string opts = "Option \"render\" \"int firstpassblock\" [1]\n";
    const std::string rib = orthoCamera(32, 4, opts) + stripes(32);
    rd::RenderSettings overlapped, drained;
    overlapped.poolCapacity = drained.poolCapacity = 256;
    drained.overlapPasses = false;
    double covered = 0;
    for (double x = -16; x < 16; x += 0.713) covered += std::min(0.3, 16 - x);
    for (const rd::RenderSettings& settings : {overlapped, drained}) {
        Rendered img = renderRib(rib, settings);
        const bool on = settings.overlapPasses;
        std::printf("%s: %d passes, %d overlapped, %d rounds\n", on ? "overlapped" : "drained",
                    img.stats.passes, img.stats.overlappedPasses, img.stats.iterations);
        if (on) {
            EXPECT_GE(img.stats.overlappedPasses, 2);
        } else {
            EXPECT_EQ(img.stats.overlappedPasses, 0);
        }
        EXPECT_EQ(img.stats.filmSamples, img.stats.retiredSamples);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const uint32_t n = img.count(x, y);
                EXPECT_TRUE(n == 2 || n == 4 || n == 8 || n == 16) << x << "," << y << ": " << n;
            }
        // 0.3 px of every 0.713 covered: the mean coverage, 2-16 coin tosses a pixel
        EXPECT_NEAR(img.mean(3, 0, 0, 32, 32), covered / 32, 0.01);
    }
}

// An adaptive render's image does not depend on when --stats' error series samples the
// film: under the Sobol sampler the planner loosens its pixel error by how far the
// samples' spread overstates the error, a ratio it must take at points the render's own
// progress sets (not the clock), or a render's image would hang on its timing. The
// series sampled every round and never give the same image bit for bit.
TEST(Sampling, AdaptiveImageDoesNotDependOnTheErrorSeries) {
    const std::string rib = grainPlane("raydrive_series", "grain", 32, 8);
    rd::RenderSettings everyRound, never;
    everyRound.poolCapacity = never.poolCapacity = 512;
    everyRound.sobol = never.sobol = 1;
    everyRound.errorSeriesSec = 0;
    never.errorSeriesSec = 1e9;
    // the pixel error, then an error target (its estimate each pass)
    for (double target : {0.0, 0.004}) {
        everyRound.errorTarget = never.errorTarget = target;
        Rendered a = renderRib(rib, everyRound), b = renderRib(rib, never);
        std::printf("error target %g: series every round: %d passes, %llu samples, %zu "
                    "points; never: %d passes, %llu samples\n",
                    target, a.stats.passes, (unsigned long long)a.stats.filmSamples,
                    a.stats.errorVsTime.size(), b.stats.passes,
                    (unsigned long long)b.stats.filmSamples);
        EXPECT_GE(a.stats.passes, 4);  // adaptive: passes after the first two
        EXPECT_GT(a.stats.errorVsTime.size(), size_t(a.stats.passes));
        EXPECT_EQ(a.stats.filmSamples, b.stats.filmSamples);
        EXPECT_EQ(pixelsDiffering(a, b), 0u);
    }
}

// A render's first round waits on the kernels' JIT (a scene's first render): its rays
// per second read a thousand times low. Rounds follow the device's rate only under a time
// budget, so a first render and the next give the same image bit for bit (a cold first
// round had capped the rounds after it at 1024 rays, and SPD gears and balls at 9
// samples a pixel came out another image). The shader's name is new each run: its
// program is built and its kernels compiled by this test.
TEST(Sampling, FirstRenderIsTheImageOfTheNext) {
    const std::string rib = grainPlane(
        "raydrive_cold",
        "grain" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()),
        64, 8);
    rd::RenderSettings settings;
    settings.poolCapacity = 16384;
    Rendered cold = renderRib(rib, settings), warm = renderRib(rib, settings);
    std::printf("cold: %d rounds, %llu samples, program built in %.0f ms; warm: %d rounds, "
                "%llu samples\n",
                cold.stats.iterations, (unsigned long long)cold.stats.filmSamples,
                cold.stats.program.buildMs, warm.stats.iterations,
                (unsigned long long)warm.stats.filmSamples);
    EXPECT_FALSE(cold.stats.program.cacheHit);
    EXPECT_EQ(cold.stats.iterations, warm.stats.iterations);
    EXPECT_EQ(cold.stats.filmSamples, warm.stats.filmSamples);
    EXPECT_EQ(pixelsDiffering(cold, warm), 0u);
}

// A pass asking for fewer samples than a 64th of the frame's pixels (256 of 16384 here)
// gives its pixels two doublings at once: a frame's last passes are small and each costs
// the rounds of its rays however few they are. A 2x2 square off the pixel grid at 8x8
// samples: its edge pixels and their neighbours climb to 64 samples in fewer passes and
// rounds, every pixel's count still on the ladder, the square's coverage the same
// estimate.
TEST(Sampling, SmallPassesQuadrupleTheirPixels) {
    const std::string rib = orthoCamera(128, 8) + "WorldBegin\nSurface \"constant\"\n" +
                            rect(0.37, 2.37, 0.37, 2.37) + "WorldEnd\n";
    rd::RenderSettings jump, doubling;
    doubling.jumpSmallPasses = false;
    Rendered a = renderRib(rib, jump), b = renderRib(rib, doubling);
    std::printf("quadrupled: %d passes, %d rounds, %llu samples; doubled: %d passes, %d "
                "rounds, %llu samples\n",
                a.stats.passes, a.stats.iterations, (unsigned long long)a.stats.filmSamples,
                b.stats.passes, b.stats.iterations, (unsigned long long)b.stats.filmSamples);
    EXPECT_LT(a.stats.passes, b.stats.passes);
    EXPECT_LT(a.stats.iterations, b.stats.iterations);
    EXPECT_LE(a.stats.filmSamples, b.stats.filmSamples + b.stats.filmSamples / 20);
    for (const Rendered* img : {&a, &b})
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                const uint32_t n = img->count(x, y);
                EXPECT_TRUE(n && n <= 64 && (n & (n - 1)) == 0) << x << "," << y << ": " << n;
            }
    // the square covers 4 of the 9 pixels [64, 67) x [61, 64) (rows run down): 64 samples
    // in each edge pixel
    for (const Rendered* img : {&a, &b})
        EXPECT_NEAR(img->mean(3, 64, 61, 67, 64) * 9.0, 4.0, 0.25);
}

// The estimate falls as 1/sqrt(samples) on a noisy scene with independent samples: 16 ->
// 256 samples per pixel must shrink it 4x (within 15%).
TEST(Sampling, ErrorEstimateShrinksAsInverseSqrtOfSamples) {
    const std::string opts =
        "Option \"render\" \"int firstpassblock\" [1] \"float pixelerror\" [1e-9]\n"
        "Option \"render\" \"string sampler\" \"independent\"\n";
    Rendered a = renderRib(orthoCamera(16, 4, opts) + stripes(16));
    Rendered b = renderRib(orthoCamera(16, 16, opts) + stripes(16));
    ASSERT_EQ(a.count(5, 5), 16u);
    ASSERT_EQ(b.count(5, 5), 256u);
    double ea = a.stats.estimatedError, eb = b.stats.estimatedError;
    std::printf("estimated error: 16 spp %.4f, 256 spp %.4f, ratio %.2f (expect 4)\n", ea, eb,
                ea / eb);
    EXPECT_NEAR(ea / eb, 4.0, 0.6);
    // The mean itself is right: the stripes' total width over the image width.
    double covered = 0;
    for (double x = -8; x < 8; x += 0.713) covered += std::min(0.3, 8 - x);
    EXPECT_NEAR(b.mean(3, 0, 0, 16, 16), covered / 16, 0.005);
}

// A seed picks another set of random numbers: seed 0 is the default set bit for bit, the
// RIB's Option and the command line's setting give the same image, and another seed's
// image shares no samples with the first (its pixels differ as two independent estimates
// do: rms sqrt(2) x 0.12 for 16 coin tosses of p = 0.42, with independent samples) while
// its mean is the same.
TEST(Sampling, SeedGivesIndependentImagesOfTheSameMean) {
    const std::string opts =
        "Option \"render\" \"int firstpassblock\" [1] \"float pixelerror\" [1e-9]\n"
        "Option \"render\" \"string sampler\" \"independent\"\n";
    const std::string seeded = opts + "Option \"render\" \"int seed\" [7]\n";
    Rendered a = renderRib(orthoCamera(16, 4, opts) + stripes(16));
    rd::RenderSettings zero, seven;
    zero.seed = 0;
    seven.seed = 7;
    Rendered a0 = renderRib(orthoCamera(16, 4, opts) + stripes(16), zero);
    Rendered b = renderRib(orthoCamera(16, 4, seeded) + stripes(16));
    Rendered b2 = renderRib(orthoCamera(16, 4, opts) + stripes(16), seven);
    double sq = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        EXPECT_EQ(a.pixels[i].a, a0.pixels[i].a) << i;
        EXPECT_EQ(b.pixels[i].a, b2.pixels[i].a) << i;
        sq += double(a.pixels[i].a - b.pixels[i].a) * (a.pixels[i].a - b.pixels[i].a);
    }
    const double rms = std::sqrt(sq / double(a.pixels.size()));
    EXPECT_GT(rms, 0.1) << "the seeds' samples are not independent";
    EXPECT_LT(rms, 0.3);
    EXPECT_NEAR(a.mean(3, 0, 0, 16, 16), b.mean(3, 0, 0, 16, 16), 0.03);
    const std::string& opts7 = b.stats.program.options;
    EXPECT_NE(opts7.find("-DRT_SEED=7u"), std::string::npos) << opts7;
}
// The Sobol sampler (Option "render" "string sampler" "sobol", or the setting) stratifies
// each pixel's samples: on the stripes, whose exact pixel coverage is known, 16 samples a
// pixel land within half the independent sampler's RMS error (about a quarter measured:
// one-dimensional edges), with no bias in the image's mean, and the option and the
// setting give the same image and build the sampler in (RT_SAMPLER_SOBOL); it is the
// default, and Option "render" "string sampler" "independent" turns it off.
TEST(Sampling, SobolSamplerHalvesTheErrorOfTheSameSamples) {
    const int res = 16;
    const std::string opts =
        "Option \"render\" \"int firstpassblock\" [1] \"float pixelerror\" [1e-9]\n";
    rd::RenderSettings sobol, independent;
    sobol.sobol = 1;
    independent.sobol = 0;
    Rendered indep = renderRib(orthoCamera(res, 4, opts) + stripes(res), independent);
    Rendered qmc = renderRib(orthoCamera(res, 4, opts) + stripes(res), sobol);
    Rendered byOption = renderRib(
        orthoCamera(res, 4, opts + "Option \"render\" \"string sampler\" \"sobol\"\n") +
        stripes(res));
    Rendered byDefault = renderRib(orthoCamera(res, 4, opts) + stripes(res));
    Rendered indepByOption = renderRib(
        orthoCamera(res, 4,
                    opts + "Option \"render\" \"string sampler\" \"independent\"\n") +
        stripes(res));
    // pixel px covers x in [px - res / 2, px - res / 2 + 1): the stripes' overlap with it
    std::vector<double> exact(res, 0.0);
    for (double x = -res / 2.0; x < res / 2.0; x += 0.713)
        for (int px = 0; px < res; ++px) {
            const double lo = px - res / 2.0, hi = lo + 1.0;
            exact[px] += std::max(0.0, std::min(hi, x + 0.3) - std::max(lo, x));
        }
    auto rms = [&](const Rendered& img) {
        double sq = 0;
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                EXPECT_EQ(img.count(x, y), 16u);
                const double d = img.at(x, y).a - exact[x];
                sq += d * d;
            }
        return std::sqrt(sq / double(res * res));
    };
    const double ei = rms(indep), eq = rms(qmc);
    std::printf("RMS error at 16 samples: independent %.4f, sobol %.4f (%.2f)\n", ei, eq, eq / ei);
    EXPECT_LT(eq, 0.5 * ei);
    EXPECT_GT(ei, 0.05);  // (the independent samples' own: 16 coin tosses, about 0.1)
    double mean = 0;
    for (double c : exact) mean += c / res;
    EXPECT_NEAR(qmc.mean(3, 0, 0, res, res), mean, 0.01);
    // The error estimates against the true relative error (white stripes: rgb =
    // coverage). Under Sobol the one from the two replicates (even and odd samples)
    // tracks it, and it is the one the render reports; the samples' spread overstates it
    // (3x measured), while under independent samples the spread is right.
    const rd::FilmError fi = rd::estimateFilmErrors(indep.film.pixels);
    const rd::FilmError fq = rd::estimateFilmErrors(qmc.film.pixels);
    const double trueI = ei / mean, trueQ = eq / mean;
    std::printf(
        "relative error: independent %.4f, estimated %.4f; sobol %.4f, estimated %.4f "
        "from replicates, %.4f from the spread\n",
        trueI, fi.spread, trueQ, fq.replicates, fq.spread);
    EXPECT_GT(fi.spread, 0.7 * trueI);
    EXPECT_LT(fi.spread, 1.4 * trueI);
    EXPECT_GT(fq.replicates, 0.6 * trueQ);
    EXPECT_LT(fq.replicates, 1.6 * trueQ);
    EXPECT_GT(fq.spread, 2.0 * trueQ);
    EXPECT_NEAR(qmc.stats.estimatedError, fq.replicates, 1e-9);
    EXPECT_NEAR(indep.stats.estimatedError, fi.spread, 1e-9);
    // The "error" AOV likewise: each pixel's spread-based error, times the film's
    // replicate-over-spread ratio under Sobol.
    const std::vector<float> spreadErr = rd::pixelRelativeErrors(qmc.film.pixels);
    const std::vector<rd::Channel> aov = qmc.film.aovChannels("error");
    ASSERT_EQ(aov.size(), 1u);
    for (size_t i = 0; i < spreadErr.size(); ++i)
        EXPECT_NEAR(aov[0].values[i], spreadErr[i] * fq.replicates / fq.spread, 1e-6)
            << i;
    EXPECT_EQ(indep.film.aovChannels("error")[0].values,
              rd::pixelRelativeErrors(indep.film.pixels));
    // Every pixel's odd samples are in its second replicate's sums, whichever job took
    // them: with the first pass's blocks (a pixel's sample 0 alone, then its sample 1 in
    // a job of its own), uneven counts (PixelSamples 3 3: samples 0-8) and a pool of 12
    // rays (jobs of at most 3 samples: samples 4-7 as 4-6 and 7), floor(n / 2) of a
    // pixel's n samples.
    rd::RenderSettings small = sobol;
    small.poolCapacity = 12;
    Rendered blocks =
        renderRib(orthoCamera(res, 3, "Option \"render\" \"float pixelerror\" [1e-9]\n") +
                      stripes(res),
                  small);
    for (const PixelAccum& p : blocks.film.pixels) {
        ASSERT_EQ(p.count, 9u);
        EXPECT_EQ(p.sum_odd.w, 4.0f);
        EXPECT_LE(p.sum_odd.x, p.sum.x);
    }
    for (size_t i = 0; i < qmc.pixels.size(); ++i) {
        EXPECT_EQ(qmc.pixels[i].a, byOption.pixels[i].a) << i;
        EXPECT_EQ(qmc.pixels[i].a, byDefault.pixels[i].a) << i;
        EXPECT_EQ(indep.pixels[i].a, indepByOption.pixels[i].a) << i;
    }
    for (const Rendered* img : {&qmc, &byOption, &byDefault}) {
        const std::string& o = img->stats.program.options;
        EXPECT_NE(o.find("-DRT_SAMPLER_SOBOL"), std::string::npos) << o;
    }
    for (const Rendered* img : {&indep, &indepByOption})
        EXPECT_EQ(img->stats.program.options.find("SOBOL"), std::string::npos);
}

// Under the Sobol sampler a shader's random() calls come from the sample's own stream, two
// in a row a stratified pair (rsl_abi.h RANDOM): 16 samples of a pixel put exactly 4 of
// their (random(), random()) points in each quarter of the unit square, so a surface lit
// where both are under 1/2 shows exactly 1/4 in every pixel (independent samples: binomial
// noise). An area light's points, the lens (depth of field) and the shutter time (motion
// blur) come from such pairs too: the same means as independent samples within noise.
TEST(Sampling, SobolSamplerStratifiesShaderRandomAreaLightsLensAndTime) {
    const std::string dir = rd::test::scratchDir("raydrive_sobol");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/quadrant.sl")
        << "surface quadrant() {\n    float a = random(), b = random();\n"
           "    Ci = (a < 0.5 && b < 0.5) ? 1 : 0;\n    Oi = 1;\n}\n";
    const std::string opts = "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                             "Option \"render\" \"int firstpassblock\" [1] \"float pixelerror\" [1e-9]\n";
    const std::string quad = "WorldBegin\nSurface \"quadrant\"\n" + rect(-4, 4, -4, 4) + "WorldEnd\n";
    rd::RenderSettings sobol, independent;
    sobol.sobol = 1;
    independent.sobol = 0;
    Rendered q = renderRib(orthoCamera(8, 4, opts) + quad, sobol);
    Rendered i = renderRib(orthoCamera(8, 4, opts) + quad, independent);
    int exact = 0, off = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            ASSERT_EQ(q.count(x, y), 16u);
            exact += q.at(x, y).r == 0.25f;
            off += i.at(x, y).r != 0.25f;
        }
    EXPECT_EQ(exact, 64) << "every pixel 1/4 under the Sobol sampler";
    EXPECT_GT(off, 32) << "independent samples are not stratified";
    const std::string area =
        "Format 24 24 1\nPixelSamples 4 4\nProjection \"perspective\" \"fov\" [40]\n" + opts +
        "Translate 0 -1 6\nWorldBegin\nAttributeBegin\nTranslate 0 3 0\nRotate 90 1 0 0\n"
        "AreaLightSource \"arealight\" 1 \"intensity\" [6]\nSurface \"constant\"\n" +
        rect(-1, 1, -1, 1) +
        "AttributeEnd\nIlluminate 1 1\nSurface \"matte\"\n"
        "Polygon \"P\" [-9 0 -9  -9 0 9  9 0 9  9 0 -9]\nTranslate 0 1 0\nSphere 1 -1 1 360\nWorldEnd\n";
    Rendered aq = renderRib(area, sobol), ai = renderRib(area, independent);
    const double mq = aq.mean(0, 0, 0, 24, 24), mi = ai.mean(0, 0, 0, 24, 24);
    std::printf("area light mean: sobol %.4f, independent %.4f\n", mq, mi);
    EXPECT_GT(mi, 0.02);
    EXPECT_NEAR(mq / mi, 1.0, 0.05);
    const std::string blurred =
        "Format 32 24 1\nPixelSamples 4 4\nProjection \"perspective\" \"fov\" [40]\n" + opts +
        "DepthOfField 2.8 0.5 6\nShutter 0 1\nTranslate 0 -1 6\nWorldBegin\n"
        "LightSource \"distantlight\" 1 \"from\" [-1 4 -2] \"to\" [0 0 0]\nSurface \"matte\"\n"
        "Polygon \"P\" [-9 0 -9  -9 0 9  9 0 9  9 0 -9]\n"
        "MotionBegin [0 1]\nTranslate 0 1 0\nTranslate 0.5 1 0\nMotionEnd\nSphere 1 -1 1 360\nWorldEnd\n";
    Rendered bq = renderRib(blurred, sobol), bi = renderRib(blurred, independent);
    const auto& features = bq.stats.features.names();
    for (const char* f : {"depth_of_field", "motion_blur", "sobol_sampler"})
        EXPECT_NE(std::find(features.begin(), features.end(), f), features.end()) << f;
    EXPECT_NEAR(bq.mean(0, 0, 0, 32, 24) / bi.mean(0, 0, 0, 32, 24), 1.0, 0.03);
}

// A time budget ends the render promptly and leaves whole samples only.
TEST(Sampling, TimeBudgetStopsTheRender) {
    rd::RenderSettings s;
    s.timeBudget = 0.3;
    Rendered img = renderRib(orthoCamera(64, 64) + stripes(64), s);
    EXPECT_EQ(img.stats.stopReason, "time budget");
    // The budget counts set-up (a cold OpenCL build included) and the first batch always
    // completes (on a cold PoCL cache it holds the JIT of every kernel at its first
    // launch: PoCL compiles each kernel for its local size then). The first point of the
    // error-against-time series is taken at the end of a batch, the first or a later one
    // past half a second (as cli.stop_time); past the latest of those, one short batch.
    ASSERT_FALSE(img.stats.errorVsTime.empty());
    EXPECT_LT(img.stats.elapsedSec, std::max({0.3, img.stats.sceneSetupMs / 1000.0,
                                              img.stats.errorVsTime.front().seconds}) +
                                        1.0);
    EXPECT_GT(img.film.tally().samples, 0u);
    for (const auto& p : img.film.pixels) EXPECT_LE(p.count, 1u << 16);
}

// A stop request (what SIGINT does) before the first round returns at once with an empty
// film (tests/cli: a SIGINT mid-render writes what is done).
TEST(Sampling, StopSignalEndsTheRenderFailSoft) {
    rd::requestStop(2);
    Rendered img = renderRib(orthoCamera(32, 8) + stripes(32));
    rd::clearStop();
    EXPECT_EQ(img.stats.stopReason, "SIGINT");
    EXPECT_EQ(img.film.tally().samples, 0u);
    EXPECT_EQ(img.stats.retiredSamples, 0u);
    EXPECT_EQ(img.stats.iterations, 0);
    EXPECT_EQ(img.stats.unsampledPixels, 32u * 32u);
}

// PixelVariance is the pixel error adaptive sampling refines to (PRMan's meaning under
// RIS): the same image as Option "render" "pixelerror"; Hider "raytrace" "int minsamples"
// and "int maxsamples" bound each pixel's samples in place of PixelSamples. Before, both
// requests were ignored.
TEST(Sampling, PixelVarianceAndHiderSamplesSteerTheAdaptiveSampling) {
    std::string rib = grainPlane("pixel_variance", "grain_pv", 16, 8);
    const std::string option = "Option \"render\" \"float pixelerror\" [0.1]\n";
    const size_t at = rib.find(option);
    ASSERT_NE(at, std::string::npos);
    Rendered byOption = renderRib(rib);
    std::string variance = rib;
    variance.replace(at, option.size(), "PixelVariance 0.1\n");
    Rendered byVariance = renderRib(variance);
    EXPECT_EQ(pixelsDiffering(byOption, byVariance), 0u);
    std::string tight = rib;
    tight.replace(at, option.size(), "PixelVariance 0.001\n");
    uint64_t loose = 0, many = 0;
    Rendered tighter = renderRib(tight);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            loose += byVariance.count(x, y), many += tighter.count(x, y);
    EXPECT_GT(many, loose);  // (up to PixelSamples' 64 each)
    // every pixel exactly 12 samples, whatever PixelSamples and the error say
    std::string bounded = variance;
    bounded.replace(
        bounded.find("PixelVariance 0.1\n"), 18,
        "Hider \"raytrace\" \"int minsamples\" [12] \"int maxsamples\" [12]\n");
    Rendered twelve = renderRib(bounded);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) ASSERT_EQ(twelve.count(x, y), 12u) << x << ", " << y;
}
