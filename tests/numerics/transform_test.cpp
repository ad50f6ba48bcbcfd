// transform_test.cpp: case 3, geometry far from the origin (translated by 1e5 and 1e7,
// the camera moved along) and scaled by 1e-6..1e6 (world and camera): the same image as
// at unit scale within a stated tolerance, no acne (lit wall exact), no light leaks
// (shadow exactly black). Triangles only (polygons).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

// A matte wall (z = 5) lit at 45 degrees, a small square occluder (z = 4) casting a
// shadow 1 unit below itself. `cameraXf` goes before WorldBegin; in the world `move`
// comes before the light and `scale` after it (a distant light depends only on its
// direction, and this keeps its compiled constants, so the program, the same).
std::string scene(const std::string& cameraXf, const std::string& move = "",
                  const std::string& scale = "") {
    return camera(24, 40, 2) + cameraXf + "WorldBegin\n" + move +
           "LightSource \"distantlight\" 1 \"from\" [0 0.70710678 -0.70710678] \"to\" [0 0 0]\n" +
           scale + "Color [0.5 0.5 0.5]\nSurface \"matte\"\n"
           "Polygon \"P\" [-3 -3 5  3 -3 5  3 3 5  -3 3 5]\n"
           "Polygon \"P\" [-0.3 -0.3 4  0.3 -0.3 4  0.3 0.3 4  -0.3 0.3 4]\n"
           "WorldEnd\n";
}

std::string vec(const char* request, double x, double y, double z) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s %.9g %.9g %.9g\n", request, x, y, z);
    return buf;
}

struct Diff {
    double maxDiff = 0, meanDiff = 0;
    int pixels = 0;  // pixels differing by more than 1e-3
};

Diff compare(const rd::test::Rendered& a, const rd::test::Rendered& b) {
    Diff d;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        double e = std::fmax(std::fabs(a.pixels[i].r - b.pixels[i].r),
                             std::fabs(a.pixels[i].a - b.pixels[i].a));
        if (!std::isfinite(b.pixels[i].r)) e = INFINITY;
        d.maxDiff = std::fmax(d.maxDiff, e);
        d.meanDiff += e / double(a.pixels.size());
        d.pixels += e > 1e-3;
    }
    return d;
}

}  // namespace

// Tolerance: mean absolute difference from the unit-scale image 1e-3 (a pixel is 4
// samples; one sample flipping at an edge changes it by 0.09, so 1e-3 allows about six
// such flips in 576 pixels), and the lit wall and the shadow are exact in every pixel
// that is not on an edge (checked through the unit image: where it is exactly lit or
// exactly black, the transformed one must be too, within 1e-4).
TEST(Numerics, TranslatedAndScaledScenesRenderTheSame) {
    const rd::test::Rendered unit = renderWithDiagnostics(scene("")).image;
    // The unit image itself: lit 0.5 cos 45 and a shadow.
    int lit = 0, dark = 0;
    for (const rd::Rgba& p : unit.pixels) {
        lit += std::fabs(p.r - 0.35355339) < 1e-5;
        dark += p.r == 0.0f && p.a == 1.0f;
    }
    ASSERT_GT(lit, 200);
    ASSERT_GT(dark, 4);
    struct Case {
        const char* name;
        std::string cam, move, scale;
    };
    const Case cases[] = {
        {"translate_1e5", vec("Translate", -1e5, -1e5, -1e5), vec("Translate", 1e5, 1e5, 1e5), ""},
        {"translate_1e7", vec("Translate", -1e7, -1e7, -1e7), vec("Translate", 1e7, 1e7, 1e7), ""},
        {"scale_1e-6", vec("Scale", 1e6, 1e6, 1e6), "", vec("Scale", 1e-6, 1e-6, 1e-6)},
        {"scale_1e3", vec("Scale", 1e-3, 1e-3, 1e-3), "", vec("Scale", 1e3, 1e3, 1e3)},
        {"scale_1e6", vec("Scale", 1e-6, 1e-6, 1e-6), "", vec("Scale", 1e6, 1e6, 1e6)},
        {"scale_1e-4_translate_1e5",
         vec("Scale", 1e4, 1e4, 1e4) + vec("Translate", -1e5, -1e5, -1e5),
         vec("Translate", 1e5, 1e5, 1e5), vec("Scale", 1e-4, 1e-4, 1e-4)},
    };
    for (const Case& c : cases) {
        Diagnosed d = renderWithDiagnostics(scene(c.cam, c.move, c.scale));
        const rd::test::Rendered& img = d.image;
        ASSERT_EQ(img.pixels.size(), unit.pixels.size()) << c.name;
        Diff diff = compare(unit, img);
        // acne and leaks: interior pixels exactly lit or exactly black stay so
        double interior = 0;
        for (size_t i = 0; i < unit.pixels.size(); ++i) {
            const float u = unit.pixels[i].r;
            if (std::fabs(u - 0.35355339f) < 1e-5f || (u == 0.0f && unit.pixels[i].a == 1.0f))
                interior = std::fmax(interior, std::fabs(double(img.pixels[i].r) - u));
        }
        EXPECT_TRUE(allFinite(img)) << c.name;
        EXPECT_TRUE(report(std::string("far_") + c.name + "_mean_diff", 1e-3, diff.meanDiff))
            << diff.pixels << " pixels differ, largest " << diff.maxDiff;
        EXPECT_TRUE(report(std::string("far_") + c.name + "_acne_leak", 1e-4, interior));
    }
}
