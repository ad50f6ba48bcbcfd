// geometry_test.cpp: one small RIB per geometry family, rendered through the whole
// pipeline on PoCL with a constant white surface and an orthographic camera looking down
// +z over [-2, 2] x [-2, 2]: the mean alpha is the covered fraction, compared with the
// shape's analytic projected area / 16. Tolerances cover 4x4-sample antialiasing at
// 64x64 and the tessellation's chord error.
#include <gtest/gtest.h>

#include <cmath>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

double coverage(const std::string& geometry) {
    Rendered img = renderRib("Format 64 64 1\nPixelSamples 4 4\n"
                             "Option \"render\" \"float pixelerror\" [1e-9]\n"
                             "Projection \"orthographic\"\nScreenWindow -2 2 -2 2\n"
                             "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n" +
                             geometry + "WorldEnd\n");
    return img.mean(3, 0, 0, img.width, img.height) * 16.0;  // covered area, world units
}

const double kPi = 3.14159265358979;

}  // namespace

TEST(Geometry, Quadrics) {
    EXPECT_NEAR(coverage("Disk 0 1.5 360\n"), kPi * 2.25, 0.1);
    EXPECT_NEAR(coverage("Disk 0 1.5 180\n"), kPi * 2.25 / 2, 0.1);
    EXPECT_NEAR(coverage("Cone 1 1.5 360\n"), kPi * 2.25, 0.1);
    EXPECT_NEAR(coverage("Paraboloid 1.5 0 1 360\n"), kPi * 2.25, 0.1);
    EXPECT_NEAR(coverage("Torus 1 0.4 0 360 360\n"), 4 * kPi * 1 * 0.4, 0.1);
    // Side views: a cylinder and a hyperboloid that is a cylinder are 2r x h rectangles.
    EXPECT_NEAR(coverage("Rotate 90 1 0 0\nCylinder 1 -1 0.5 360\n"), 2 * 1.5, 0.08);
    EXPECT_NEAR(coverage("Rotate 90 1 0 0\nHyperboloid 1 0 -1 1 0 1 360\n"), 4, 0.1);
    EXPECT_NEAR(coverage("Sphere 1 -1 1 360\n"), kPi, 0.08);
}

TEST(Geometry, PolygonsWithHoles) {
    // A 3x3 square with a 1x1 hole.
    EXPECT_NEAR(coverage("GeneralPolygon [4 4] \"P\" [-1.5 -1.5 0  1.5 -1.5 0  1.5 1.5 0  "
                         "-1.5 1.5 0  -0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0  0.5 -0.5 0]\n"),
                8.0, 0.1);
    // A concave L (area 0.75) and a 1 x 1.5 rectangle sharing vertices.
    EXPECT_NEAR(coverage("PointsGeneralPolygons [1 1] [6 6] [0 1 2 3 4 5  0 5 6 7 8 9] "
                         "\"P\" [0 0 0  1 0 0  1 1 0  0.5 1 0  0.5 0.5 0  0 0.5 0 "
                         "-1 0.5 0  -1 -1 0  0 -1 0  0 0 0]\n"),
                0.75 + 1.5, 0.1);
}

TEST(Geometry, Patches) {
    EXPECT_NEAR(coverage("Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\n"), 4.0,
                0.08);
    // A bicubic Bezier patch whose control points lie on a plane square.
    std::string p = "Patch \"bicubic\" \"P\" [";
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            p += std::to_string(-1.5 + i) + " " + std::to_string(-1.5 + j) + " 0 ";
    EXPECT_NEAR(coverage(p + "]\n"), 9.0, 0.12);
    EXPECT_NEAR(coverage("PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" \"P\" "
                         "[-1.5 -1 0  0 -1 0  1.5 -1 0  -1.5 1 0  0 1 0  1.5 1 0]\n"),
                6.0, 0.1);
    // An order-2 (linear) NURBS square, and the same with a circular hole trimmed away.
    std::string nu = "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" "
                     "[-1.5 -1.5 0  1.5 -1.5 0  -1.5 1.5 0  1.5 1.5 0]\n";
    EXPECT_NEAR(coverage(nu), 9.0, 0.12);
}

TEST(Geometry, SubdivisionCubeShrinksInsideItsCage) {
    // A 2x2x2 cage seen face on: its Catmull-Clark limit surface is inside the cage.
    double area = coverage(
        "SubdivisionMesh \"catmull-clark\" [4 4 4 4 4 4] "
        "[0 1 3 2  2 3 7 6  6 7 5 4  4 5 1 0  1 5 7 3  4 0 2 6] [\"interpolateboundary\"] "
        "[0 0] [] [] \"P\" [-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  "
        "1 1 1]\n");
    EXPECT_GT(area, 2.0);
    EXPECT_LT(area, 4.0);
}

TEST(Geometry, CurvesAndPoints) {
    // A straight linear curve of length 3 and width 0.5.
    EXPECT_NEAR(coverage("Curves \"linear\" [2] \"nonperiodic\" \"P\" [-1.5 0 0  1.5 0 0] "
                         "\"constantwidth\" [0.5]\n"),
                1.5, 0.1);
    // Four discs of diameter 0.8.
    EXPECT_NEAR(coverage("Points \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] "
                         "\"constantwidth\" [0.8]\n"),
                4 * kPi * 0.16, 0.1);
}

// ObjectBegin/End defines geometry that is not drawn itself; each ObjectInstance draws it
// under the transform current at the instance.
TEST(Geometry, ObjectInstances) {
    EXPECT_NEAR(coverage("ObjectBegin \"square\"\n"
                         "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n"
                         "ObjectEnd\n"
                         "AttributeBegin\nTranslate -1 0 0\nObjectInstance \"square\"\n"
                         "AttributeEnd\n"
                         "AttributeBegin\nTranslate 1 0 0\nScale 2 1 1\n"
                         "ObjectInstance \"square\"\nAttributeEnd\n"),
                1.0 + 2.0, 0.06);
}
