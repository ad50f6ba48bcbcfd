// render_test.cpp: small RIB scenes rendered through the whole pipeline on PoCL, checked
// against closed-form values. Tolerances are stated per test; shading here is noise-free
// (no Monte Carlo estimator yet), so the only error is pixel-coverage aliasing at edges
// and sphere tessellation, which the coverage test bounds.
#include <gtest/gtest.h>

#include <cmath>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// A camera at the origin looking down +z (RenderMan camera space = world space here).
std::string camera(int res, float fov, int spp) {
    return "Format " + std::to_string(res) + " " + std::to_string(res) +
           " 1\nPixelSamples " + std::to_string(spp) + " " + std::to_string(spp) +
           "\nProjection \"perspective\" \"fov\" " + std::to_string(fov) + "\n";
}

const char* kPlaneAt5 = "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n";

}  // namespace

// A constant sphere of radius 1 at distance 5, fov 30: its silhouette is a disc of screen
// radius tan(asin(1/5)) / tan(15 deg) in a 2x2 screen window. Mean alpha = covered
// fraction, expected within 0.5% (tessellation loses < 0.2%, 4x4 samples alias < 0.1%).
TEST(Render, ConstantSphereCoversTheAnalyticFraction) {
    Rendered img = renderRib(camera(128, 30, 4) +
                             "WorldBegin\nColor [0.25 0.5 0.75]\nSurface \"constant\"\n"
                             "Translate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n");
    double radius = std::tan(std::asin(0.2)) / std::tan(15.0 * M_PI / 180.0);
    double expected = M_PI * radius * radius / 4.0;
    double coverage = img.mean(3, 0, 0, img.width, img.height);
    std::printf("coverage %.5f expected %.5f relative error %.2e\n", coverage, expected,
                std::fabs(coverage / expected - 1));
    EXPECT_NEAR(coverage / expected, 1.0, 0.005);
    const rd::Rgba& c = img.at(64, 64);
    EXPECT_FLOAT_EQ(c.r, 0.25f);
    EXPECT_FLOAT_EQ(c.g, 0.5f);
    EXPECT_FLOAT_EQ(c.b, 0.75f);
    EXPECT_FLOAT_EQ(c.a, 1.0f);
    EXPECT_FLOAT_EQ(img.at(1, 1).a, 0.0f);
}

// Lambert: matte, Kd = 1, Cs = 0.5, distant light of intensity 1 at 60 degrees from the
// plane's normal: Ci = 0.5 * cos(60) = 0.25 everywhere, within 1%.
TEST(Render, MattePlaneUnderDistantLightIsLambert) {
    Rendered img = renderRib(camera(32, 60, 1) +
                             "WorldBegin\n"
                             "LightSource \"distantlight\" 1 \"from\" [0 0.8660254 -0.5] "
                             "\"to\" [0 0 0]\n"
                             "Color [0.5 0.5 0.5]\nSurface \"matte\"\n" +
                             kPlaneAt5 + "WorldEnd\n");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.mean(c, 0, 0, 32, 32), 0.25, 0.0025);
    EXPECT_NEAR(img.mean(3, 0, 0, 32, 32), 1.0, 1e-6);
}

// Inverse square law: a point light of intensity 25 at the eye, 5 units from the plane:
// Cl = 25 / 25 = 1 on the axis, Ci = Cs = 0.5 at the centre pixel; off axis
// Ci = 0.5 * 25 cos(theta) / d^2 with d = 5 / cos(theta). 8x8 samples make the pixel
// mean the value at its centre to well under 1% (the radiance is smooth).
TEST(Render, PointLightFallsOffWithTheSquareOfDistance) {
    Rendered img = renderRib(camera(33, 60, 8) +
                             "WorldBegin\nLightSource \"pointlight\" 1 \"intensity\" 25\n"
                             "Color [0.5 0.5 0.5]\nSurface \"matte\"\n" +
                             kPlaneAt5 + "WorldEnd\n");
    EXPECT_NEAR(img.at(16, 16).r, 0.5, 0.005);
    // Pixel centre (32.5 of 33) at screen x = (32.5/33*2 - 1) * tan(30 deg)
    double x = (32.5 / 33.0 * 2.0 - 1.0) * std::tan(M_PI / 6), y = 0.0;
    double cosTheta = 1.0 / std::sqrt(1 + x * x + y * y);
    double expected = 0.5 * 25.0 * cosTheta * cosTheta * cosTheta / 25.0;
    EXPECT_NEAR(img.at(32, 16).r, expected, 0.01 * expected);
}

// Plastic with light, eye and normal aligned: N.H = 1, so
// Ci = Cs*Kd*1 + Ks*specularcolor*1 = 0.5*0.5 + 0.5 = 0.75, Ka*ambient adds 0.1*0.5.
TEST(Render, PlasticPeakHighlight) {
    Rendered img = renderRib(camera(9, 10, 1) +
                             "WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" 0.1\n"
                             "LightSource \"distantlight\" 2 \"from\" [0 0 0] \"to\" [0 0 1]\n"
                             "Color [0.5 0.5 0.5]\nSurface \"plastic\"\n" +
                             kPlaneAt5 + "WorldEnd\n");
    EXPECT_NEAR(img.at(4, 4).g, 0.75 + 0.05, 0.008);
}

// Ray-traced shadow: a sphere of radius 0.5 at z = 4 between the plane at z = 5 and a
// distant light at 60 degrees casts its shadow centred on (0, -1.732, 5): that pixel gets
// nothing (no ambient), an unshadowed one gets the Lambert 0.25.
TEST(Render, DistantLightCastsRayTracedShadow) {
    Rendered img = renderRib(camera(100, 60, 1) +
                             "WorldBegin\n"
                             "LightSource \"distantlight\" 1 \"from\" [0 0.8660254 -0.5] "
                             "\"to\" [0 0 0]\n"
                             "Color [0.5 0.5 0.5]\nSurface \"matte\"\n" + kPlaneAt5 +
                             "AttributeBegin\nTranslate 0 0 4\nSphere 0.5 -0.5 0.5 360\n"
                             "AttributeEnd\nWorldEnd\n");
    // screen y of the shadow centre: -1.732/5 / tan(30 deg) = -0.6 -> raster row 80
    EXPECT_NEAR(img.at(50, 80).r, 0.0, 1e-6) << "shadow centre must be dark";
    EXPECT_NEAR(img.at(10, 10).r, 0.25, 0.0025) << "open plane must be lit";
    EXPECT_GT(img.stats.shadowRays, 0u);
}

// Opacity 0.5 red over opaque blue: 0.5 red + 0.5 blue, alpha 1; where the back plane is
// absent the pixel is half red with alpha 0.5.
TEST(Render, TransparentSurfaceContinuesTheRay) {
    Rendered img = renderRib(camera(40, 60, 1) +
                             "WorldBegin\nSurface \"constant\"\n"
                             "AttributeBegin\nColor [1 0 0]\nOpacity [0.5 0.5 0.5]\n"
                             "Polygon \"P\" [-50 -50 4  50 -50 4  50 50 4  -50 50 4]\n"
                             "AttributeEnd\n"
                             "AttributeBegin\nColor [0 0 1]\n"
                             "Polygon \"P\" [-50 -50 5  0 -50 5  0 50 5  -50 50 5]\n"
                             "AttributeEnd\nWorldEnd\n");
    const rd::Rgba& both = img.at(5, 20);
    EXPECT_NEAR(both.r, 0.5, 1e-5);
    EXPECT_NEAR(both.b, 0.5, 1e-5);
    EXPECT_NEAR(both.a, 1.0, 1e-5);
    const rd::Rgba& front = img.at(35, 20);
    EXPECT_NEAR(front.r, 0.5, 1e-5);
    EXPECT_NEAR(front.b, 0.0, 1e-5);
    EXPECT_NEAR(front.a, 0.5, 1e-5);
    EXPECT_GT(img.stats.continuationRays, 0u);
}

// The image does not depend on the pool capacity (and so the tiling): random numbers are
// indexed by pixel and sample, never by pool slot. Bit for bit when each adaptive pass
// drains before the next is planned; with overlapped passes (the default) which pixels
// are still in flight at a plan, and so wait a pass, depends on the pool: the same
// image within sampling noise.
TEST(Render, ImageIndependentOfPoolCapacity) {
    std::string rib = camera(37, 45, 3) +
                      "WorldBegin\nLightSource \"pointlight\" 1 \"from\" [1 2 0] "
                      "\"intensity\" 20\nSurface \"plastic\"\n" + kPlaneAt5 +
                      "Translate 0 0 4\nSphere 1 -1 1 360\nWorldEnd\n";
    rd::RenderSettings large, small;
    small.poolCapacity = 9 * 50;  // forces many small tiles
    for (bool overlap : {false, true}) {
        large.overlapPasses = small.overlapPasses = overlap;
        Rendered a = renderRib(rib, large), b = renderRib(rib, small);
        EXPECT_GT(b.stats.iterations, a.stats.iterations);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        double diff = 0, sum = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) {
            if (!overlap) {
                ASSERT_EQ(a.pixels[i].r, b.pixels[i].r) << "pixel " << i;
                ASSERT_EQ(a.pixels[i].a, b.pixels[i].a) << "pixel " << i;
            }
            diff += std::fabs(a.pixels[i].r - b.pixels[i].r);
            sum += a.pixels[i].r;
        }
        std::printf("overlap %d: mean |difference| %.2e of the mean\n", int(overlap), diff / sum);
        EXPECT_LT(diff / sum, 2e-3);  // 9 samples a pixel where they differ
    }
}

// Per-kernel counters: every kernel launched, active never above launched.
TEST(Render, KernelStatsAreConsistent) {
    Rendered img = renderRib(camera(16, 45, 2) +
                             "WorldBegin\nLightSource \"distantlight\" 1\n"
                             "Surface \"matte\"\n" + std::string(kPlaneAt5) + "WorldEnd\n");
    const auto& k = img.stats.kernels;
    for (const char* name : {"generate_eye", "intersect_closest", "classify_hits",
                             "shade_matte", "intersect_shadow", "close_round",
                             "retire_samples"}) {
        ASSERT_TRUE(k.count(name)) << name;
        EXPECT_GT(k.at(name).launches, 0u) << name;
        EXPECT_LE(k.at(name).activeItems, k.at(name).launchedItems) << name;
    }
    // One shader: no sort (its run is the whole pool), so no scatter and no wait for it.
    EXPECT_TRUE(!k.count("scatter_by_shader") || k.at("scatter_by_shader").launches == 0);
    // A flat, evenly lit plane: 1/4 ray per pixel first, then every pixel to the minimum
    // of 2 samples and no further (no variance, no contrast): 64 + 64*1 + 192*2 = 512.
    EXPECT_EQ(img.stats.eyeRays, 512u);
    EXPECT_EQ(k.at("intersect_closest").activeItems, img.stats.eyeRays);
    EXPECT_EQ(img.stats.shadowRays, img.stats.eyeRays);  // every hit sees the light
    // the group counts (counters.clh): every index below the count, or every ray shaded
    for (const char* name : {"generate_eye", "classify_hits", "shade_matte", "close_round"})
        EXPECT_EQ(k.at(name).activeItems, img.stats.eyeRays) << name;
    // retire's: the jobs in flight at each launch. Every sample here ends in the round it
    // starts, so each job counts once: 64 one-sample jobs, then 64 + 192 to the minimum
    // (its count reads job states that the launch itself rewrites: RT_JOB_TAG)
    EXPECT_EQ(k.at("retire_samples").activeItems, 64u + 64u + 192u);
    // the loop's idle time: the host's part never more than the whole
    EXPECT_GE(img.stats.launchGapsMs, 0.0);
    EXPECT_GE(img.stats.hostSyncOverhead, 0.0);
    EXPECT_LE(img.stats.hostSyncOverhead, img.stats.hostOverhead);
}

// A window of jobs in flight larger than one retire launch takes (on PoCL 65472: it
// compiles a kernel again for larger launches) is retired by several launches, each from
// its base: the same image bit for bit and the same count of jobs in flight as one launch
// each, with launches of 64 jobs. Mirrors facing each other keep samples in flight over
// rounds (their rays bounce to the specular depth), so the launches' progress meets too.
TEST(Render, RetireWindowInSeveralLaunchesIsTheSame) {
    const std::string rib = camera(24, 45, 3) +
                            "Attribute \"trace\" \"int maxspeculardepth\" [4]\n"
                            "WorldBegin\nLightSource \"distantlight\" 1\n"
                            "AttributeBegin\nSurface \"mirror\" \"Kr\" 0.8\n" +
                            std::string(kPlaneAt5) +
                            "Polygon \"P\" [-50 -50 -5  50 -50 -5  50 50 -5  -50 50 -5]\n"
                            "AttributeEnd\nTranslate 0 0 3\nSurface \"matte\"\n"
                            "Sphere 1 -1 1 360\nWorldEnd\n";
    rd::RenderSettings small;
    small.retireLaunchItems = 64;
    Rendered one = renderRib(rib), several = renderRib(rib, small);
    const auto& a = one.stats.kernels.at("retire_samples");
    const auto& b = several.stats.kernels.at("retire_samples");
    std::printf("retire: %llu launches, %llu jobs in flight; in launches of 64: %llu, %llu\n",
                (unsigned long long)a.launches, (unsigned long long)a.activeItems,
                (unsigned long long)b.launches, (unsigned long long)b.activeItems);
    EXPECT_GT(b.launches, 2 * a.launches);
    EXPECT_EQ(a.activeItems, b.activeItems);
    EXPECT_GT(one.stats.continuationRays, 0u);
    EXPECT_EQ(one.stats.iterations, several.stats.iterations);
    size_t differ = 0;
    for (size_t i = 0; i < one.pixels.size(); ++i)
        differ += one.pixels[i].r != several.pixels[i].r || one.pixels[i].g != several.pixels[i].g;
    EXPECT_EQ(differ, 0u);
}

// Two shaders: the sort runs, each shade kernel takes its own run, and the misses and the
// surfaces of the other shader are left out of a shader's work-items. Left half constant
// 0.25, right half constant 0.75 (exact: constant is Cs), top rows empty sky.
TEST(Render, TwoShadersAreSortedIntoTheirRuns) {
    Rendered img = renderRib(
        camera(16, 45, 2) +
        "WorldBegin\nColor [0.25 0.25 0.25]\nSurface \"constant\"\n"
        "Polygon \"P\" [-50 -50 5  0 -50 5  0 0 5  -50 0 5]\n"
        "AttributeBegin\nColor [0.75 0.75 0.75]\nSurface \"matte\"\n"
        "LightSource \"ambientlight\" 1 \"intensity\" 1\n"
        "Polygon \"P\" [0 -50 5  50 -50 5  50 0 5  0 0 5]\nAttributeEnd\nWorldEnd\n");
    const auto& k = img.stats.kernels;
    ASSERT_TRUE(k.count("scatter_by_shader"));
    EXPECT_GT(k.at("scatter_by_shader").launches, 0u);
    // 16x16, at least 2 samples a pixel, the lower half hit: 64 pixels per shader; the
    // sampler adds samples at the seam and the horizon, every one shaded once
    const uint64_t constant = k.at("shade_constant").activeItems;
    const uint64_t matte = k.at("shade_matte").activeItems;
    EXPECT_GE(constant, 64u * 2);
    EXPECT_GE(matte, 64u * 2);
    EXPECT_LE(constant + matte, k.at("intersect_closest").activeItems);
    EXPECT_EQ(k.at("scatter_by_shader").activeItems, constant + matte);  // the hits sorted
    // RI: y up, so the planes (y < 0) fill the lower rows 8-15 of the image
    EXPECT_NEAR(img.mean(0, 0, 9, 7, 16), 0.25, 1e-6);
    EXPECT_NEAR(img.mean(0, 9, 9, 16, 16), 0.75, 1e-5);  // matte: Ka ambient Cs
    EXPECT_NEAR(img.mean(3, 0, 0, 16, 7), 0.0, 1e-6);
}

// An empty world renders a transparent black image, no hang, no crash.
TEST(Render, EmptyWorld) {
    Rendered img = renderRib(camera(8, 45, 1) + "WorldBegin\nWorldEnd\n");
    EXPECT_EQ(img.mean(3, 0, 0, 8, 8), 0.0);
}

// Pipelined rounds (the default) queue the next round's eye rays at the pool's front and
// the spawned rays' compaction behind them before the round's wait, fit_refill finding
// on the device how many jobs fit beside the rays spawned. The same rays are traced in
// the same rounds as with both queued after the wait: the same image, up to the order
// in which a sample's rays add to its total, and the same number of rounds and rays,
// through a pool small enough that glass spawns past it onto the spill stack.
TEST(Render, PipelinedRoundsTraceTheSameRays) {
    const std::string rib = camera(32, 45, 3) +
                            "WorldBegin\nLightSource \"pointlight\" 1 \"from\" [1 2 0] "
                            "\"intensity\" 20\nSurface \"plastic\"\n" + kPlaneAt5 +
                            "AttributeBegin\nSurface \"glass\"\nTranslate -0.6 0 3.5\n"
                            "Sphere 0.8 -0.8 0.8 360\nAttributeEnd\n"
                            "AttributeBegin\nSurface \"mirror\"\nTranslate 0.7 0 4\n"
                            "Sphere 0.7 -0.7 0.7 360\nAttributeEnd\nWorldEnd\n";
    rd::RenderSettings after, before;
    after.pipelineRounds = false;
    after.overlapPasses = before.overlapPasses = false;  // passes by pixel error alone
    after.poolCapacity = before.poolCapacity = 256;
    Rendered a = renderRib(rib, after), b = renderRib(rib, before);
    EXPECT_EQ(a.stats.kernels.count("fit_refill") ? a.stats.kernels.at("fit_refill").launches : 0u,
              0u);
    ASSERT_TRUE(b.stats.kernels.count("fit_refill"));
    EXPECT_GT(b.stats.kernels.at("fit_refill").launches, 0u);
    EXPECT_GT(b.stats.spilledRays, 0u);
    EXPECT_EQ(a.stats.iterations, b.stats.iterations);
    EXPECT_EQ(a.stats.eyeRays, b.stats.eyeRays);
    EXPECT_EQ(a.stats.totalRays(), b.stats.totalRays());
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    float worst = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        worst = std::max({worst, std::fabs(a.pixels[i].r - b.pixels[i].r),
                          std::fabs(a.pixels[i].g - b.pixels[i].g),
                          std::fabs(a.pixels[i].a - b.pixels[i].a)});
    std::printf("%u rounds, %llu rays spilled; largest pixel difference %.2e\n",
                unsigned(b.stats.iterations), (unsigned long long)b.stats.spilledRays, worst);
    EXPECT_LT(worst, 1e-5f);
}
