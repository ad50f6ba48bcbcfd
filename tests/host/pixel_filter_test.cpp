// pixel_filter_test.cpp: PixelFilter by filter importance sampling (host/scene/
// pixel_filter.h): the sampling tables against the filters, and the image of a straight
// edge against the edge's filtered step, for a box, RI's default gaussian and a
// catmull-rom with its negative lobes.
#include "scene/pixel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// Integral of g over [a, b] (midpoint rule, fine enough for 1e-6).
double integral(const std::string& name, double width, double a, double b) {
    const int n = 20000;
    double s = 0;
    for (int i = 0; i < n; ++i)
        s += rd::pixelFilter1D(name, a + (b - a) * (i + 0.5) / n, width);
    return s * (b - a) / n;
}

// Integral of a filter `width` wide in x and y over the part of its support right of x =
// from (midpoint rule on a 600 x 600 grid).
double integral2D(const std::string& name, double width, double from) {
    const int n = 600;
    const double h = width / n;
    double s = 0;
    for (int i = 0; i < n; ++i) {
        const double x = -width / 2 + (i + 0.5) * h;
        if (x < from) continue;
        for (int j = 0; j < n; ++j)
            s += rd::pixelFilter2D(name, x, -width / 2 + (j + 0.5) * h, width, width);
    }
    return s * h * h;
}

}  // namespace

// Each axis's table is the inverse of the cumulative |g|: it starts and ends at the
// support's ends, rises, is symmetric, and the share of |g| below icdf(u) is u; samples
// weigh the integral of |g| over that of g (1 for filters that are never negative).
TEST(PixelFilter, TablesAreTheInverseCumulativeFilter) {
    struct Case {
        const char* name;
        float width;               // in x; y is half as wide
        bool negative, negativeY;  // (catmull-rom is positive within a pixel)
    };
    for (const Case c :
         {Case{"gaussian", 2, false, false}, Case{"triangle", 3, false, false},
          Case{"catmull-rom", 4, true, false}, Case{"sinc", 6, true, true},
          Case{"mitchell", 4, true, true}, Case{"blackman-harris", 3, false, false},
          Case{"lanczos", 6, true, true}}) {
        SCOPED_TRACE(c.name);
        Camera cam{};
        ASSERT_TRUE(rd::setCameraFilter(cam, c.name, c.width, c.width * 0.5f));
        EXPECT_EQ(cam.filter_table, 1u);
        for (int axis = 0; axis < 2; ++axis) {
            const double w = axis == 0 ? c.width : c.width * 0.5;
            const float* icdf = cam.filter_icdf[axis];
            EXPECT_FLOAT_EQ(icdf[0], float(-w / 2));
            EXPECT_FLOAT_EQ(icdf[RT_FILTER_TABLE], float(w / 2));
            double absTotal = 0;
            for (int i = 0; i < 2000; ++i) {
                const double x = -w / 2 + w * (i + 0.5) / 2000;
                absTotal += std::fabs(rd::pixelFilter1D(c.name, x, w)) * w / 2000;
            }
            for (int k = 0; k < RT_FILTER_TABLE; ++k) {
                EXPECT_LE(icdf[k], icdf[k + 1]);
                EXPECT_NEAR(icdf[k], -icdf[RT_FILTER_TABLE - k], 2e-3 * w);
            }
            for (int k : {16, 40, 64, 100}) {  // the share of |g| below icdf(k / TABLE)
                double below = 0;
                for (int i = 0; i < 2000; ++i) {
                    const double x = -w / 2 + (icdf[k] + w / 2) * (i + 0.5) / 2000;
                    below += std::fabs(rd::pixelFilter1D(c.name, x, w)) *
                             (icdf[k] + w / 2) / 2000;
                }
                EXPECT_NEAR(below / absTotal, double(k) / RT_FILTER_TABLE, 2e-3) << k;
            }
            // g's sign changes where the cumulative |g| is at the flips
            const bool anyNegative =
                cam.filter_negative_start[axis] || cam.filter_flips[axis][0] <= 1.0f;
            EXPECT_EQ(anyNegative, axis == 0 ? c.negative : c.negativeY)
                << "axis " << axis;
            for (int f = 0; f < RT_FILTER_FLIPS && cam.filter_flips[axis][f] <= 1.0f;
                 ++f) {
                // the x whose share of |g| below it is the flip's u (by bisection)
                const double u = cam.filter_flips[axis][f];
                double lo = -w / 2, hi = w / 2;
                for (int it = 0; it < 40; ++it) {
                    const double mid = 0.5 * (lo + hi);
                    double below = 0;
                    for (int i = 0; i < 2000; ++i)
                        below +=
                            std::fabs(rd::pixelFilter1D(
                                c.name, -w / 2 + (mid + w / 2) * (i + 0.5) / 2000, w)) *
                            (mid + w / 2) / 2000;
                    (below / absTotal < u ? lo : hi) = mid;
                }
                EXPECT_NEAR(rd::pixelFilter1D(c.name, lo, w), 0.0, 3e-3) << "flip " << f;
            }
        }
        if (c.negative)
            EXPECT_GT(cam.filter_weight, 1.0f);
        else
            EXPECT_NEAR(cam.filter_weight, 1.0f, 1e-5f);
    }
    // Radial filters (disk, bessel): one table of the distance from the centre, over
    // [0, xwidth / 2], the share of |f(r)| r below icdf(u) being u; bessel's negative
    // lobe (jinc's first zero at r = 1.2197) is a flip and weighs samples above 1.
    for (const char* name : {"disk", "bessel"}) {
        SCOPED_TRACE(name);
        Camera cam{};
        ASSERT_TRUE(rd::setCameraFilter(cam, name, 4, 2));
        EXPECT_EQ(cam.filter_table, 2u);
        const float* icdf = cam.filter_icdf[0];
        EXPECT_FLOAT_EQ(icdf[0], 0.0f);
        EXPECT_FLOAT_EQ(icdf[RT_FILTER_TABLE], 2.0f);
        auto share = [&](double r) {  // of |f(r)| r below r
            double s = 0;
            for (int i = 0; i < 4000; ++i) {
                const double x = r * (i + 0.5) / 4000;
                s += std::fabs(rd::pixelFilter2D(name, x, 0, 4, 2)) * x * r / 4000;
            }
            return s;
        };
        const double total = share(2.0);
        for (int k = 0; k < RT_FILTER_TABLE; ++k) EXPECT_LE(icdf[k], icdf[k + 1]);
        for (int k : {16, 40, 64, 100})
            EXPECT_NEAR(share(icdf[k]) / total, double(k) / RT_FILTER_TABLE, 2e-3) << k;
        const bool bessel = std::string(name) == "bessel";
        EXPECT_EQ(cam.filter_flips[0][0] <= 1.0f, bessel);
        if (bessel) {
            EXPECT_NEAR(share(1.2197) / total, cam.filter_flips[0][0], 2e-3);
            EXPECT_GT(cam.filter_weight, 1.0f);
        } else {
            EXPECT_NEAR(icdf[RT_FILTER_TABLE / 4], 1.0, 0.02) << "a quarter of the disc";
            EXPECT_NEAR(cam.filter_weight, 1.0f, 1e-5f);
        }
        // stretched along y when the widths differ: half as tall here
        EXPECT_EQ(rd::pixelFilter2D(name, 0, 0.99, 4, 2) != 0.0, true);
        EXPECT_EQ(rd::pixelFilter2D(name, 0, 1.01, 4, 2), 0.0);
    }
    // A box needs no table: its place is uniform over its widths.
    Camera box{};
    ASSERT_TRUE(rd::setCameraFilter(box, "box", 1, 2));
    EXPECT_EQ(box.filter_table, 0u);
    EXPECT_EQ(box.filter_width[1], 2.0f);
}

// A white half-plane whose edge is at raster x = 8.3 of a 16-pixel-wide orthographic
// image: pixel column px is the filter's share of the step, the integral of g over the
// offsets x with px + 0.5 + x > 8.3 over the integral of g; exact for the box (the
// covered fraction), smooth for the gaussian, overshooting on both sides for catmull-rom.
TEST(PixelFilter, EdgeProfileIsTheFilteredStep) {
    struct Case {
        const char* filter;
        double width;
        double tolerance;
    };
    for (const Case c : {Case{"box", 1, 1.0 / 1024}, Case{"gaussian", 2, 0.01},
                         Case{"catmull-rom", 4, 0.03}, Case{"disk", 3, 0.005},
                         Case{"bessel", 4, 0.01}}) {
        SCOPED_TRACE(c.filter);
        std::ostringstream rib;
        rib << "Format 16 4 1\nPixelSamples 32 32\nPixelFilter \"" << c.filter << "\" "
            << c.width << " " << c.width
            << "\nOption \"render\" \"float pixelerror\" [0.0001]\n"
               "Hider \"raytrace\" \"int minsamples\" [1024]\n"
               "Projection \"orthographic\"\nScreenWindow -8 8 -2 2\nTranslate 0 0 5\n"
               "WorldBegin\nSurface \"constant\"\n"
               "Polygon \"P\" [0.3 -50 0  50 -50 0  50 50 0  0.3 50 0]\nWorldEnd\n";
        Rendered r = renderRib(rib.str());
        const bool radial = rd::pixelFilterRadial(c.filter);
        const double all = radial
                               ? integral2D(c.filter, c.width, -c.width / 2)
                               : integral(c.filter, c.width, -c.width / 2, c.width / 2);
        for (int px = 4; px < 13; ++px) {
            const double from = std::max(-c.width / 2, 8.3 - (px + 0.5));
            const double expected =
                from >= c.width / 2 ? 0.0
                : radial            ? integral2D(c.filter, c.width, from) / all
                         : integral(c.filter, c.width, from, c.width / 2) / all;
            EXPECT_NEAR(r.mean(0, px, 0, px + 1, 4), expected, c.tolerance)
                << "column " << px << " samples " << r.count(px, 0) << " "
                << r.count(px, 1);
            EXPECT_NEAR(r.mean(3, px, 0, px + 1, 4), expected, c.tolerance)
                << "alpha " << px;
        }
        EXPECT_EQ(r.stats.features.signedFilter, std::string(c.filter) == "catmull-rom" ||
                                                     std::string(c.filter) == "bessel");
        if (std::string(c.filter) == "catmull-rom") {  // its negative lobes: ringing
            EXPECT_LT(r.mean(0, 7, 0, 8, 4), -0.01);
            EXPECT_GT(r.mean(0, 9, 0, 10, 4), 1.01);
        }
    }
}
