// teapot_test.cpp: Geometry "teapot" (host/scene/teapot.cpp): Newell's control points
// checked by the teapot's own symmetries, the rendered pot's extents against its patches'
// analytic extremes, and the request drawn as the 32 Bezier patches whatever the Basis.
#include "scene/teapot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

struct Point3 {
    float x, y, z;
};
Point3 point(const std::vector<float>& p, int row, int col) {
    const size_t i = size_t(row * 4 + col) * 3;
    return {p[i], p[i + 1], p[i + 2]};
}
bool near(Point3 a, Point3 b) {
    return std::fabs(a.x - b.x) < 1e-6f && std::fabs(a.y - b.y) < 1e-6f &&
           std::fabs(a.z - b.z) < 1e-6f;
}

}  // namespace

// The rim, the body's two rings, the lid's two and the bottom are surfaces of revolution
// cut in quarters: each patch of a ring is the one before it turned a quarter about z
// (the same way round the ring). The handle and the spout are mirrored in y: the second
// patch of each pair is the first mirrored, its columns reversed. A mistyped coordinate
// breaks one of these.
TEST(Teapot, ControlPointsHaveTheTeapotsSymmetries) {
    for (int first : {0, 4, 8, 20, 24, 28}) {
        int sense = 0;  // +1: (x, y) -> (-y, x); -1: (x, y) -> (y, -x)
        for (int k = first; k < first + 4; ++k) {
            const std::vector<float> p = rd::teapotPatch(k), q = rd::teapotPatch(
                                                                 first + (k - first + 1) % 4);
            for (int s : {1, -1}) {
                bool all = true;
                for (int r = 0; r < 4; ++r)
                    for (int c = 0; c < 4; ++c) {
                        const Point3 a = point(p, r, c);
                        const Point3 turned = s > 0 ? Point3{-a.y, a.x, a.z}
                                                    : Point3{a.y, -a.x, a.z};
                        all = all && near(turned, point(q, r, c));
                    }
                if (all && (sense == 0 || sense == s)) sense = s;
            }
            EXPECT_NE(sense, 0) << "patch " << k << " turned is not patch "
                                << first + (k - first + 1) % 4;
        }
    }
    for (int first : {12, 14, 16, 18}) {
        const std::vector<float> p = rd::teapotPatch(first), q = rd::teapotPatch(first + 1);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                const Point3 a = point(p, r, 3 - c);
                EXPECT_TRUE(near({a.x, -a.y, a.z}, point(q, r, c)))
                    << "patch " << first + 1 << " row " << r << " column " << c;
            }
    }
    // The pieces meet: the rim's last row is the body's first, the body's last the
    // bottom's outer ring.
    EXPECT_TRUE(near(point(rd::teapotPatch(0), 3, 0), point(rd::teapotPatch(4), 0, 0)));
    EXPECT_TRUE(near(point(rd::teapotPatch(8), 3, 0), point(rd::teapotPatch(28), 3, 0)));
}

// Seen from the side (orthographic, along y) at 8 pixels a unit: the pot spans x from the
// handle's outer corner (-3, a control point the patch passes through) to the spout's
// lip, whose outermost Bezier curve (3.3, 3.525, 3.45, 3.2) peaks at 3.4342, and z from
// the bottom's centre (0) to the knob (3.15). Box filter, so a pixel's alpha is its
// covered fraction; the extents are read to a pixel (0.125) plus the edge pixel's share.
TEST(Teapot, SideViewSpansTheHandleToTheSpoutAndTheBottomToTheKnob) {
    Rendered r = renderRib("Format 128 64 1\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\n"
                           "Projection \"orthographic\"\nScreenWindow -8 8 -4 4\n"
                           "Translate 0 -1.6 10\nWorldBegin\nRotate -90 1 0 0\n"
                           "Surface \"constant\"\nGeometry \"teapot\"\nWorldEnd\n");
    int x0 = r.width, x1 = -1, y0 = r.height, y1 = -1;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            if (r.at(x, y).a > 0.02f) {
                x0 = std::min(x0, x), x1 = std::max(x1, x);
                y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
    ASSERT_LE(x0, x1) << "nothing drawn";
    const double unit = 8.0;  // pixels a world unit
    const double left = (x0 - 64) / unit, right = (x1 + 1 - 64) / unit;
    const double top = (32 - y0) / unit + 1.6, bottom = (32 - y1 - 1) / unit + 1.6;
    EXPECT_NEAR(left, -3.0, 0.13);
    EXPECT_NEAR(right, 3.4342, 0.13);
    EXPECT_NEAR(top, 3.15, 0.13);
    EXPECT_NEAR(bottom, 0.0, 0.13);
    // Row 40 (z from 0.475 to 0.6) crosses the body, about 3.9 units wide there: a pot,
    // not an outline.
    EXPECT_GT(r.mean(3, 0, 40, r.width, 41) * r.width / unit, 3.5);
}

// The request is the 32 patches under the Bezier basis whatever Basis is current, and
// leaves the current one as it was: the same image as the patches written out, with a
// b-spline patch drawn after it in both (in front of the pot).
TEST(Teapot, IsTheBezierPatchesWhateverTheBasis) {
    std::string patches = "Basis \"bezier\" 3 \"bezier\" 3\n";
    for (int k = 0; k < rd::kTeapotPatches; ++k) {
        patches += "Patch \"bicubic\" \"P\" [";
        for (float c : rd::teapotPatch(k)) patches += std::to_string(c) + " ";
        patches += "]\n";
    }
    const std::string bspline =
        "Translate 0 0 -3\nPatch \"bicubic\" \"P\" [-4 -4 0 -2 -4 0 2 -4 0 4 -4 0 -4 -2 0 "
        "-2 -2 1 2 -2 1 4 -2 0 -4 2 0 -2 2 1 2 2 1 4 2 0 -4 4 0 -2 4 0 2 4 0 4 4 0]\n";
    const std::string frame = "Format 48 48 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                              "ScreenWindow -4 4 -4 4\nTranslate 0 0 10\nWorldBegin\n"
                              "Surface \"matte\"\nLightSource \"distantlight\" 1 \"from\" "
                              "[1 2 -3] \"to\" [0 0 0]\n";
    Rendered request = renderRib(frame + "Basis \"b-spline\" 1 \"b-spline\" 1\n"
                                         "Geometry \"teapot\"\n" +
                                 bspline + "WorldEnd\n");
    Rendered written = renderRib(frame + patches + "Basis \"b-spline\" 1 \"b-spline\" 1\n" +
                                 bspline + "WorldEnd\n");
    ASSERT_EQ(request.pixels.size(), written.pixels.size());
    double diff = 0, sum = 0;
    for (size_t i = 0; i < request.pixels.size(); ++i) {
        diff = std::max(diff, double(std::fabs(request.pixels[i].r - written.pixels[i].r)));
        sum += request.pixels[i].a;
    }
    EXPECT_LT(diff, 1e-5);
    // Seen from below the pot covers its base's disc (radius 2, 0.196 of the frame) with the
    // handle and spout, and the b-spline patch in front of it (x, y within +-5/3) hides
    // inside that; as a Bezier patch it would cover the whole frame.
    EXPECT_GT(sum / request.pixels.size(), 0.19);
    EXPECT_LT(sum / request.pixels.size(), 0.3);
}
