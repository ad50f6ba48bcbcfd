// gather_test.cpp: the gather() loop (rsl2cl gather.cpp): its passes' rays, the hit
// branch with what a ray met ("surface:Ci"), the else branch when it escaped, against the
// same analytic hemisphere fractions as occlusion() (shading_test.cpp). The loops the
// affine model cannot take are refused: tests/rsl2cl/affine_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// `hits` counts the passes whose ray met something within maxd (0: no limit): 1 - hits /
// 16 is the fraction that escaped. `gathered` adds what the rays meet, or blue (0, 0,
// 0.5) for those that escape, over `samples` passes (a parameter: the directions a
// shading sample traces are chosen when it runs).
const char* kShaders[][2] = {{"gatherhitp", R"(
surface gatherhitp() {
    point hp = 0;
    float sum = 0;
    gather("illuminance", P, normal(0, 0, 1), PI / 2, 16, "primitive:P", hp) {
        sum += zcomp(hp);
    }
    Ci = sum / 16;
    Oi = 1;
}
)"},
                             {"gao", R"(
surface gao(float maxd = 0;) {
    float hits = 0;
    gather("illuminance", P, normal(0, 0, 1), PI / 2, 16, "maxdist", maxd) {
        hits += 1;
    }
    Ci = 1 - hits / 16;
    Oi = 1;
}
)"},
                             {"gathered", R"(
surface gathered(float samples = 16;) {
    color hitc = 0, sum = 0;
    vector dir = 0;
    gather("illuminance", P, normal(0, 0, 1), PI / 2, samples, "surface:Ci", hitc,
           "ray:direction", dir) {
        sum += hitc;
    } else {
        sum += color(0, 0, 0.5) * (zcomp(dir) > 0 ? 1 : 0);
    }
    Ci = sum / samples;
    Oi = 1;
}
)"},
                             {"gatherlen", R"(
surface gatherlen() {
    float len = 0, sum = 0;
    gather("illuminance", P, normal(0, 0, 1), PI / 2, 16, "ray:length", len) {
        sum += len;
    }
    Ci = sum / 16;
    Oi = 1;
}
)"}};

std::string shaderDir(const std::string& name) {
    return rd::test::shaderFolder(name, kShaders);
}

const std::string kDisk =
    "Translate 0 0 7\nDisk 0 1 360\n";  // covers 0.2 of the hemisphere

}  // namespace

// A patch under a disk that covers 0.2 of its cosine-weighted hemisphere (see
// Shading.OcclusionAndIndirectDiffuseAreTheirHemisphereFractions): 0.8 of the passes
// escape, as occlusion() finds; under half a sky sphere 0.5; none are stopped with the
// disk beyond "maxdist". Four by four samples a pixel, 16 passes each (four traced
// directions, cycled); image means.
TEST(Gather, PassesAreTheHemisphereFractions) {
    const std::string dir = shaderDir("gather_ao");
    auto render = [&](const std::string& call, const std::string& above) {
        return renderRib(rd::test::patchUnder(dir, 4, call, above));
    };
    Rendered under = render("\"gao\"", kDisk),
             half = render("\"gao\"", "Sphere 100 -100 100 180\n"),
             reach = render("\"gao\" \"maxd\" 1.5", kDisk);
    EXPECT_NEAR(under.mean(0, 0, 0, 16, 16), 0.8, 0.02);
    EXPECT_NEAR(half.mean(0, 0, 0, 16, 16), 0.5, 0.02);
    EXPECT_NEAR(reach.mean(0, 0, 0, 16, 16), 1.0, 1e-6);
    EXPECT_TRUE(under.stats.features.visibilityRays);
    EXPECT_TRUE(under.stats.features.sampledTrace);
    std::printf("NUMERICS case=gather_disk tolerance=0.02 measured=%.4f\n",
                under.mean(0, 0, 0, 16, 16) - 0.8);
}

// What the rays meet: the disk's constant colour (1, 0.5, 0.25) over 0.2 of the passes,
// the else branch's blue (0, 0, 0.5) over the 0.8 that escape (their direction, given by
// "ray:direction", points up): Ci = (0.2, 0.1, 0.05 + 0.4), with 16 passes over the four
// directions a shading sample traces, and with 3 (three directions).
TEST(Gather, TheHitBranchGetsWhatTheRayMetTheElseBranchTheRest) {
    const std::string dir = shaderDir("gather_ci");
    for (const char* call : {"\"gathered\"", "\"gathered\" \"samples\" 3"}) {
        Rendered r = renderRib(rd::test::patchUnder(dir, 4, call, kDisk));
        EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), 0.2, 0.02) << call;
        EXPECT_NEAR(r.mean(1, 0, 0, 16, 16), 0.1, 0.01) << call;
        EXPECT_NEAR(r.mean(2, 0, 0, 16, 16), 0.45, 0.02) << call;
    }
}

// "ray:length": the distance to what a pass's ray met (a distance ray, not shaded). Under
// the disk (radius 1, 2 units up) a ray at angle theta from the normal meets it at 2 /
// cos theta while tan theta < 1/2; over the cosine-weighted hemisphere the mean of (hit ?
// length : 0) is the integral of (2 / cos theta) 2 cos theta sin theta to that angle,
// 4 (1 - 2 / sqrt 5) = 0.4223.
TEST(Gather, RayLengthIsTheDistanceToWhatTheRayMet) {
    Rendered r = renderRib(
        rd::test::patchUnder(shaderDir("gather_length"), 4, "\"gatherlen\"", kDisk));
    const double expected = 4 * (1 - 2 / std::sqrt(5.0));
    EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), expected, 0.02);
    std::printf("NUMERICS case=gather_ray_length tolerance=0.02 measured=%.4f\n",
                r.mean(0, 0, 0, 16, 16) - expected);
}

// The same under a wider disk halfway up that traced rays do not see: the rays go through
// it and measure from where they started, to the same mean (before, they stopped at it).
TEST(Gather, RayLengthGoesThroughWhatTracedRaysDoNotSee) {
    const double expected = 4 * (1 - 2 / std::sqrt(5.0));
    Rendered through = renderRib(rd::test::patchUnder(
        shaderDir("gather_length"), 4, "\"gatherlen\"",
        "AttributeBegin\nAttribute \"visibility\" \"int trace\" [0]\nTranslate 0 0 6\n"
        "Disk 0 1.5 360\nAttributeEnd\n" +
            kDisk));
    EXPECT_NEAR(through.mean(0, 0, 0, 16, 16), expected, 0.02);
    EXPECT_TRUE(through.stats.features.invisible);
}

// "primitive:P": where a pass's ray met the surface (its origin plus its direction times
// its length). Under the disk at z = 7, which 0.2 of the cosine-weighted passes meet, the
// mean of (hit ? zcomp(P) : 0) is 0.2 x 7 = 1.4.
TEST(Gather, PrimitivePIsWhereTheRayMetTheSurface) {
    Rendered r = renderRib(
        rd::test::patchUnder(shaderDir("gather_hitp"), 4, "\"gatherhitp\"", kDisk));
    EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), 1.4, 0.05);
    std::printf("NUMERICS case=gather_primitive_p tolerance=0.05 measured=%.4f\n",
                r.mean(0, 0, 0, 16, 16) - 1.4);
}
