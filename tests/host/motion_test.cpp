// motion_test.cpp: motion blur (Shutter, MotionBegin/End). Orthographic views of
// constant surfaces, whose alpha is the fraction of the shutter time a pixel is covered:
// an exact sphere and a square moved by a transform against the closed-form time
// averages, a deforming mesh's mean area, and no blur without a shutter interval.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

constexpr int kW = 64, kH = 16;  // screen window [-2, 2] x [-0.5, 0.5]

Rendered render(const std::string& shutter, const std::string& world) {
    std::ostringstream rib;
    rib << "Format " << kW << " " << kH << " 1\nPixelSamples 16 16\n" << shutter
        << "Projection \"orthographic\"\nScreenWindow -2 2 -0.5 0.5\nTranslate 0 0 5\n"
        << "WorldBegin\nSurface \"constant\"\n" << world << "\nWorldEnd\n";
    return renderRib(rib.str());
}

// Mean over a pixel and the shutter of `covered(x, y, time)`, by a fine grid.
template <typename F>
double expectedAlpha(int px, int py, F covered) {
    const int n = 24;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                double x = -2 + (px + (i + 0.5) / n) * 4.0 / kW;
                double y = 0.5 - (py + (j + 0.5) / n) * 1.0 / kH;
                sum += covered(x, y, (k + 0.5) / n);
            }
    return sum / (n * n * n);
}

// Compares every pixel's alpha with the time average; returns the mean absolute error.
template <typename F>
double compare(const Rendered& img, F covered, const char* name,
               double columnTolerance = 0.035) {
    double sumErr = 0, worstColumn = 0, signedWorst = 0;
    for (int x = 0; x < kW; ++x) {
        double colErr = 0;
        for (int y = 0; y < kH; ++y) {
            double e = img.at(x, y).a - expectedAlpha(x, y, covered);
            sumErr += std::fabs(e);
            colErr += e;
        }
        if (std::fabs(colErr / kH) > worstColumn) signedWorst = colErr / kH;
        worstColumn = std::max(worstColumn, std::fabs(colErr / kH));
    }
    double mean = sumErr / (kW * kH);
    // 256 samples a pixel: a coverage estimate's standard deviation is at most 0.031, so
    // the mean absolute error is at most 0.025 and a column's mean error (16 pixels) has
    // a standard deviation under 0.008 (measured errors halve from 64 to 256 samples: no
    // bias)
    std::printf(
        "NUMERICS case=motion_%s tolerance=0.02 measured=%g (worst column mean %g)\n",
        name, mean, signedWorst);
    EXPECT_LE(mean, 0.02) << name;
    EXPECT_LE(worstColumn, columnTolerance) << name;
    return mean;
}

}  // namespace

// A sphere of radius 0.45 translated from x = -1 to x = 1 over the shutter.
TEST(Motion, MovingExactSphereBlursAlongItsPath) {
    Rendered img = render("Shutter 0 1\n",
                          "MotionBegin [0 1] Translate -1 0 0 Translate 1 0 0 MotionEnd\n"
                          "Sphere 0.45 -0.45 0.45 360");
    EXPECT_TRUE(std::find(img.stats.features.names().begin(), img.stats.features.names().end(),
                          "motion_blur") != img.stats.features.names().end());
    compare(img, [](double x, double y, double t) {
        double c = -1 + 2 * t;
        return (x - c) * (x - c) + y * y < 0.45 * 0.45 ? 1.0 : 0.0;
    }, "sphere_translate");
}

// A square (two triangles) moved by a transform, and a mesh deforming between two keys.
TEST(Motion, MovingAndDeformingMeshes) {
    Rendered moved = render("Shutter 0 1\n",
                            "MotionBegin [0 1] Translate -1 0 0 Translate 1 0 0 MotionEnd\n"
                            "Polygon \"P\" [-0.25 -0.25 0  0.25 -0.25 0  0.25 0.25 0  -0.25 0.25 0]");
    compare(moved, [](double x, double y, double t) {
        double c = -1 + 2 * t;
        return std::fabs(x - c) < 0.25 && std::fabs(y) < 0.25 ? 1.0 : 0.0;
    }, "square_translate");
    // a rectangle whose right edge runs from x = -1 to x = 1.5 over the shutter
    Rendered deformed = render("Shutter 0 1\n",
                               "MotionBegin [0 1]\n"
                               "Polygon \"P\" [-1.5 -0.3 0  -1 -0.3 0  -1 0.3 0  -1.5 0.3 0]\n"
                               "Polygon \"P\" [-1.5 -0.3 0  1.5 -0.3 0  1.5 0.3 0  -1.5 0.3 0]\n"
                               "MotionEnd");
    compare(deformed, [](double x, double y, double t) {
        double right = -1 + 2.5 * t;
        return x > -1.5 && x < right && std::fabs(y) < 0.3 ? 1.0 : 0.0;
    }, "rectangle_deform");
}

// Without a Shutter interval there is no blur: everything is seen at its first key.
TEST(Motion, NoShutterIntervalMeansNoBlur) {
    Rendered img = render("", "MotionBegin [0 1] Translate -1 0 0 Translate 1 0 0 MotionEnd\n"
                              "Sphere 0.45 -0.45 0.45 360");
    compare(img, [](double x, double y, double) {
        return (x + 1) * (x + 1) + y * y < 0.45 * 0.45 ? 1.0 : 0.0;
    }, "no_shutter");
    EXPECT_FLOAT_EQ(img.at(kW / 4, kH / 2).a, 1.0f);  // x = -1: the sphere's centre
    EXPECT_FLOAT_EQ(img.at(3 * kW / 4, kH / 2).a, 0.0f);
}

// A moving camera (MotionBegin around the camera transform) blurs a still sphere as if
// the sphere moved: the camera's translation runs the sphere's image from x = -1 to 1.
TEST(Motion, MovingCameraBlursTheScene) {
    std::ostringstream rib;
    rib << "Format " << kW << " " << kH << " 1\nPixelSamples 16 16\nShutter 0 1\n"
        << "Projection \"orthographic\"\nScreenWindow -2 2 -0.5 0.5\n"
        << "MotionBegin [0 1] Translate -1 0 5 Translate 1 0 5 MotionEnd\n"
        << "WorldBegin\nSurface \"constant\"\nSphere 0.45 -0.45 0.45 360\nWorldEnd\n";
    Rendered img = renderRib(rib.str());
    compare(img, [](double x, double y, double t) {
        double c = -1 + 2 * t;
        return (x - c) * (x - c) + y * y < 0.45 * 0.45 ? 1.0 : 0.0;
    }, "camera_translate");
}

// An instance under a moving transform moves like the geometry it places.
TEST(Motion, MovingInstance) {
    Rendered img = render("Shutter 0 1\n",
                          "ObjectBegin \"sq\"\n"
                          "Polygon \"P\" [-0.25 -0.25 0  0.25 -0.25 0  0.25 0.25 0  -0.25 0.25 0]\n"
                          "ObjectEnd\n"
                          "MotionBegin [0 1] Translate -1 0 0 Translate 1 0 0 MotionEnd\n"
                          "ObjectInstance \"sq\"");
    EXPECT_EQ(img.stats.instances, 1u);
    compare(img, [](double x, double y, double t) {
        double c = -1 + 2 * t;
        return std::fabs(x - c) < 0.25 && std::fabs(y) < 0.25 ? 1.0 : 0.0;
    }, "instance_translate");
}

// Motion keys between the first and the last (MotionBegin with three times, uneven):
// an exact sphere, a square's triangles and an instance moved by the keys x = -1, 1, 0
// at times 0, 0.25, 1 run out to the right and back, linearly from key to key; a mesh
// deforming through three keys, its right edge at -1, 1.5 and 0, likewise. With the
// first and last keys alone (the keys between skipped on the device) the mean errors
// were 0.10-0.23 and the worst columns 0.23-0.56.
TEST(Motion, KeysBetweenTheFirstAndTheLast) {
    auto along = [](double t, double a, double b, double c) {
        return t < 0.25 ? a + (b - a) * t / 0.25 : b + (c - b) * (t - 0.25) / 0.75;
    };
    const std::string keys =
        "MotionBegin [0 0.25 1] Translate -1 0 0 Translate 1 0 0 Translate 0 0 0 "
        "MotionEnd\n";
    Rendered sphere = render("Shutter 0 1\n", keys + "Sphere 0.45 -0.45 0.45 360");
    compare(
        sphere,
        [&](double x, double y, double t) {
            const double c = along(t, -1, 1, 0);
            return (x - c) * (x - c) + y * y < 0.45 * 0.45 ? 1.0 : 0.0;
        },
        "sphere_three_keys");
    const std::string square =
        "Polygon \"P\" [-0.25 -0.25 0  0.25 -0.25 0  0.25 0.25 0  -0.25 0.25 0]";
    auto squareAt = [&](double x, double y, double t) {
        const double c = along(t, -1, 1, 0);
        return std::fabs(x - c) < 0.25 && std::fabs(y) < 0.25 ? 1.0 : 0.0;
    };
    compare(render("Shutter 0 1\n", keys + square), squareAt, "square_three_keys");
    Rendered instance =
        render("Shutter 0 1\n", "ObjectBegin \"sq\"\n" + square + "\nObjectEnd\n" + keys +
                                    "ObjectInstance \"sq\"");
    EXPECT_EQ(instance.stats.instances, 1u);
    compare(instance, squareAt, "instance_three_keys");
    Rendered deformed =
        render("Shutter 0 1\n",
               "MotionBegin [0 0.25 1]\n"
               "Polygon \"P\" [-1.5 -0.3 0  -1 -0.3 0  -1 0.3 0  -1.5 0.3 0]\n"
               "Polygon \"P\" [-1.5 -0.3 0  1.5 -0.3 0  1.5 0.3 0  -1.5 0.3 0]\n"
               "Polygon \"P\" [-1.5 -0.3 0  0 -0.3 0  0 0.3 0  -1.5 0.3 0]\n"
               "MotionEnd");
    compare(
        deformed,
        [&](double x, double y, double t) {
            return x > -1.5 && x < along(t, -1, 1.5, 0) && std::fabs(y) < 0.3 ? 1.0 : 0.0;
        },
        "rectangle_three_keys");
}

// MotionBegin around a quadric's keys moves its parameters: two keys of a sphere (radius
// 0.3, then 0.45) are diced alike into a deforming mesh, a sphere growing over the
// shutter; the sphere given after the block stays still. Before, the first key alone was
// drawn (with a warning), and the two keys made the transform move from the identity to
// the current one (the small sphere at x = 1 smeared towards x = 2). (A diced sphere's
// outline lies inside its circle, by up to about 0.14 pixel at the larger radius: its
// edge columns read up to 0.04 low, so those are held to 0.05.)
TEST(Motion, QuadricKeysMoveItsParametersAndNothingAfterThem) {
    Rendered img = render("Shutter 0 1\n",
                          "Translate -1 0 0\nMotionBegin [0 1]\nSphere 0.3 -0.3 0.3 360\n"
                          "Sphere 0.45 -0.45 0.45 360\nMotionEnd\nTranslate 2 0 0\n"
                          "Sphere 0.2 -0.2 0.2 360");
    compare(
        img,
        [](double x, double y, double t) {
            const double r = 0.3 + 0.15 * t;
            return (x + 1) * (x + 1) + y * y < r * r || (x - 1) * (x - 1) + y * y < 0.04
                       ? 1.0
                       : 0.0;
        },
        "quadric_keys", 0.05);
}

// A camera moved through three keys (out and back, at uneven times) blurs a still sphere
// along the same path as the sphere moved by those keys in KeysBetweenTheFirstAndTheLast.
TEST(Motion, CameraKeysBetweenTheFirstAndTheLast) {
    std::ostringstream rib;
    rib << "Format " << kW << " " << kH << " 1\nPixelSamples 16 16\nShutter 0 1\n"
        << "Projection \"orthographic\"\nScreenWindow -2 2 -0.5 0.5\n"
        << "MotionBegin [0 0.25 1] Translate -1 0 5 Translate 1 0 5 Translate 0 0 5 "
           "MotionEnd\n"
        << "WorldBegin\nSurface \"constant\"\nSphere 0.45 -0.45 0.45 360\nWorldEnd\n";
    Rendered img = renderRib(rib.str());
    compare(
        img,
        [](double x, double y, double t) {
            const double c = t < 0.25 ? -1 + 2 * t / 0.25 : 1 - (t - 0.25) / 0.75;
            return (x - c) * (x - c) + y * y < 0.45 * 0.45 ? 1.0 : 0.0;
        },
        "camera_three_keys");
}

// A surface that shows its shading normal as a colour, 0.5 + 0.5 N.
static const char* const kShowNormal[][2] = {
    {"shownormal",
     "surface shownormal() {\n    normal n = normalize(N);\n"
     "    Ci = color(0.5 + 0.5 * xcomp(n), 0.5 + 0.5 * ycomp(n), 0.5 + 0.5 * zcomp(n));\n"
     "    Oi = 1;\n}\n"}};

// `world` in a size x size orthographic view of [-1, 1]^2 from z = -5, at one shutter
// time, shaded by kShowNormal from the shader folder `dir`.
static Rendered showNormalsAt(const std::string& dir, int size, const char* time,
                              const std::string& world) {
    const std::string format = std::to_string(size);
    return renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\nFormat " +
                     format + " " + format + " 1\nPixelSamples 2 2\nShutter " + time +
                     " " + time +
                     "\nProjection \"orthographic\"\nScreenWindow -1 1 -1 1\n"
                     "Translate 0 0 5\nWorldBegin\nSurface \"shownormal\"\n" +
                     world + "WorldEnd\n");
}

// A mesh's vertex normals turn with it: a square whose normals lean (0.6, 0, -0.8),
// turned about the view axis from 0 to 90 degrees, is shaded at the shutter's end with
// them turned to (0, 0.6, -0.8), and halfway (its vertices midway between the keys: the
// square turned 45 degrees and shrunk by cos 45, a similarity) with (0.42, 0.42, -0.8).
// The shader shows N as a colour, 0.5 + 0.5 N. Before, the normals stayed the first
// key's: (0.8, 0.5, 0.1) at every time.
TEST(Motion, VertexNormalsTurnWithTheMesh) {
    const std::string dir =
        rd::test::shaderFolder("raydrive_motion_normals", kShowNormal);
    auto at = [&](const char* time) {
        return showNormalsAt(
            dir, 16, time,
            "MotionBegin [0 1]\nRotate 0 0 0 1\nRotate 90 0 0 1\nMotionEnd\n"
            "Polygon \"P\" [-0.6 -0.6 0  0.6 -0.6 0  0.6 0.6 0  -0.6 0.6 0] "
            "\"N\" [0.6 0 -0.8  0.6 0 -0.8  0.6 0 -0.8  0.6 0 -0.8]\n");
    };
    const double h = 0.5 + 0.5 * 0.6 * std::sqrt(0.5);
    const struct {
        const char* time;
        double r, g;
    } cases[] = {{"0", 0.8, 0.5}, {"1", 0.5, 0.8}, {"0.5", h, h}};
    for (const auto& c : cases) {
        const Rendered r = at(c.time);
        // the middle 4 x 4 pixels: inside the square at every turn
        EXPECT_NEAR(r.mean(0, 6, 6, 10, 10), c.r, 1e-4) << "time " << c.time;
        EXPECT_NEAR(r.mean(1, 6, 6, 10, 10), c.g, 1e-4) << "time " << c.time;
        EXPECT_NEAR(r.mean(2, 6, 6, 10, 10), 0.1, 1e-4) << "time " << c.time;
    }
}

// A mesh under a moving transform that is not a similarity takes each key's normals by
// that key's inverse transpose: a square in the plane z = x with vertex normals
// (0, 0.6, -0.8), squashed along z to a quarter (Scale 1 1 1, then 1 1 0.25), is shaded
// at the shutter's end with (0, 0.6, -3.2) normalised, as the same square standing
// still under Scale 1 1 0.25 is. Before, the triangles' own motion carried them, which
// cannot tell how the squash shears a normal: (-0.54, 0.53, -0.65) at the end.
TEST(Motion, NormalsUnderANonSimilarMotionAreEachKeys) {
    const std::string dir =
        rd::test::shaderFolder("raydrive_squash_normals", kShowNormal);
    const std::string square =
        "Polygon \"P\" [-0.6 -0.6 -0.6  0.6 -0.6 0.6  0.6 0.6 0.6  "
        "-0.6 0.6 -0.6] \"N\" [0 0.6 -0.8  0 0.6 -0.8  0 0.6 -0.8  "
        "0 0.6 -0.8]\n";
    const std::string moving =
        "MotionBegin [0 1]\nScale 1 1 1\nScale 1 1 0.25\nMotionEnd\n";
    const double len = std::sqrt(0.36 + 3.2 * 3.2);
    const struct {
        const char* time;
        double g, b;
    } cases[] = {{"0", 0.8, 0.1}, {"1", 0.5 + 0.5 * 0.6 / len, 0.5 - 0.5 * 3.2 / len}};
    for (const auto& c : cases) {
        const Rendered r = showNormalsAt(dir, 16, c.time, moving + square);
        EXPECT_NEAR(r.mean(0, 6, 6, 10, 10), 0.5, 1e-4) << "time " << c.time;
        EXPECT_NEAR(r.mean(1, 6, 6, 10, 10), c.g, 1e-4) << "time " << c.time;
        EXPECT_NEAR(r.mean(2, 6, 6, 10, 10), c.b, 1e-4) << "time " << c.time;
    }
    // the same as the square standing still under each key's transform
    const Rendered still = showNormalsAt(dir, 16, "1", "Scale 1 1 0.25\n" + square);
    const Rendered end = showNormalsAt(dir, 16, "1", moving + square);
    for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(end.mean(ch, 6, 6, 10, 10), still.mean(ch, 6, 6, 10, 10), 1e-5);
}

// A deforming mesh whose keys each give N: its normals at a time are the keys' own,
// between the two keys around it (before, the first key's, carried by the triangles'
// motion: here the keys' points are the same, so always the first key's).
TEST(Motion, DeformingMeshNormalsAreTheKeys) {
    const std::string dir = rd::test::shaderFolder("raydrive_key_normals", kShowNormal);
    const std::string square =
        "Polygon \"P\" [-0.6 -0.6 0  0.6 -0.6 0  0.6 0.6 0  -0.6 0.6 0] ";
    auto key = [&](const char* n) {
        return square + "\"N\" [" + n + " " + n + " " + n + " " + n + "]\n";
    };
    auto at = [&](const std::string& motion, const char* time) {
        return showNormalsAt(dir, 16, time, motion);
    };
    const std::string two =
        "MotionBegin [0 1]\n" + key("0.6 0 -0.8") + key("0 0.6 -0.8") + "MotionEnd\n";
    const std::string three = "MotionBegin [0 0.5 1]\n" + key("0.6 0 -0.8") +
                              key("0 0.6 -0.8") + key("-0.6 0 -0.8") + "MotionEnd\n";
    // halfway between (0.6, 0, -0.8) and (0, 0.6, -0.8): (0.3, 0.3, -0.8), normalised
    const double len = std::sqrt(0.82), mid = 0.5 + 0.5 * 0.3 / len,
                 low = 0.5 - 0.5 * 0.3 / len, blue = 0.5 - 0.5 * 0.8 / len;
    const struct {
        const std::string* motion;
        const char* time;
        double r, g, b;
    } cases[] = {{&two, "0", 0.8, 0.5, 0.1},     {&two, "1", 0.5, 0.8, 0.1},
                 {&two, "0.5", mid, mid, blue},  {&three, "0.25", mid, mid, blue},
                 {&three, "0.5", 0.5, 0.8, 0.1}, {&three, "0.75", low, mid, blue},
                 {&three, "1", 0.2, 0.5, 0.1}};
    for (const auto& c : cases) {
        const Rendered r = at(*c.motion, c.time);
        const std::string what =
            (c.motion == &two ? "two keys, time " : "three keys, time ") +
            std::string(c.time);
        EXPECT_NEAR(r.mean(0, 4, 4, 12, 12), c.r, 1e-4) << what;
        EXPECT_NEAR(r.mean(1, 4, 4, 12, 12), c.g, 1e-4) << what;
        EXPECT_NEAR(r.mean(2, 4, 4, 12, 12), c.b, 1e-4) << what;
    }
}

// A subdivision surface bending through its keys: each key's limit normals come from its
// own shape, so the surface at a key's time shades as that key standing still does
// (before, the first key's normals, carried by each triangle's motion, missed the bend:
// at time 1 the flat key's normals tilted with each facet).
TEST(Motion, BendingSubdivisionSurfaceShadesAsItsKeys) {
    const std::string dir =
        rd::test::shaderFolder("raydrive_bending_normals", kShowNormal);
    auto grid = [](bool bent) {
        std::string faces, points;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                const int a = 4 * j + i;
                faces += std::to_string(a) + " " + std::to_string(a + 1) + " " +
                         std::to_string(a + 5) + " " + std::to_string(a + 4) + " ";
            }
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const double x = -0.9 + 0.6 * i, y = -0.9 + 0.6 * j;
                points += std::to_string(x) + " " + std::to_string(y) + " " +
                          std::to_string(bent ? -0.6 * (1.0 - x * x) : 0.0) + " ";
            }
        return "SubdivisionMesh \"catmull-clark\" [4 4 4 4 4 4 4 4 4] [" + faces +
               "] [] [] [] [] \"P\" [" + points + "]\n";
    };
    auto render = [&](const std::string& geometry, const char* time) {
        return showNormalsAt(dir, 32, time, geometry);
    };
    const std::string bending =
        "MotionBegin [0 1]\n" + grid(false) + grid(true) + "MotionEnd\n";
    for (const auto& [time, bent] :
         {std::pair<const char*, bool>{"0", false}, {"1", true}}) {
        const Rendered moving = render(bending, time), still = render(grid(bent), time);
        double largest = 0;
        for (size_t p = 0; p < moving.pixels.size(); ++p) {
            const rd::Rgba &a = moving.pixels[p], &b = still.pixels[p];
            largest =
                std::max({largest, double(std::fabs(a.r - b.r)),
                          double(std::fabs(a.g - b.g)), double(std::fabs(a.b - b.b))});
        }
        EXPECT_LT(largest, 1e-5) << "time " << time;
        // the bend shows: the red channel (x of N) spans more than 0.3 at time 1
        double lo = 1, hi = 0;
        for (const rd::Rgba& c : moving.pixels)
            if (c.a > 0.5f)
                lo = std::min(lo, double(c.r)), hi = std::max(hi, double(c.r));
        if (bent) {
            EXPECT_GT(hi - lo, 0.3);
        }
    }
}
