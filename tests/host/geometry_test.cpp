// geometry_test.cpp: one small RIB per geometry family, rendered through the whole
// pipeline on PoCL with a constant white surface and an orthographic camera looking down
// +z over [-2, 2] x [-2, 2]: the mean alpha is the covered fraction, compared with the
// shape's analytic projected area / 16. Also texture coordinates and colours given per
// point on every family. Tolerances cover 4x4-sample antialiasing at
// 64x64 and the tessellation's chord error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "render_harness.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

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

// The other schemes from RIB: "bilinear" keeps the cube's cage (a 2 x 2 square face on),
// "loop" rounds the octahedron on the unit axes inside its square silhouette (area 2),
// around the square its vertices' limits (0.436 out on the axes,
// Subdiv.LoopOctahedronMeetsTheAxesAtItsLimitMask) span (area 0.38). Loop on
// quads is an error at its line, and the mesh is left out.
TEST(Geometry, SubdivisionBilinearAndLoopSchemes) {
    const std::string cubeCage =
        "[4 4 4 4 4 4] [0 1 3 2  2 3 7 6  6 7 5 4  4 5 1 0  1 5 7 3  4 0 2 6] [] [] [] "
        "[] "
        "\"P\" [-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1  -1 -1 1  1 -1 1  -1 1 1  1 1 1]\n";
    EXPECT_NEAR(coverage("SubdivisionMesh \"bilinear\" " + cubeCage), 4.0, 0.05);
    const double loop = coverage(
        "SubdivisionMesh \"loop\" [3 3 3 3 3 3 3 3] "
        "[0 2 4  0 5 2  0 4 3  0 3 5  1 4 2  1 2 5  1 3 4  1 5 3] [] [] [] [] "
        "\"P\" [1 0 0  -1 0 0  0 1 0  0 -1 0  0 0 1  0 0 -1]\n");
    EXPECT_GT(loop, 2 * 0.436 * 0.436);
    EXPECT_LT(loop, 2.0);
    std::ostringstream messages;
    rib::Diagnostics diag(&messages);
    rd::RibBuilder builder(diag, "test.rib");
    rib::readString("WorldBegin\nSubdivisionMesh \"loop\" " + cubeCage + "WorldEnd\n",
                    "test.rib", builder, diag);
    EXPECT_NE(
        messages.str().find("test.rib:2: error: SubdivisionMesh \"loop\": face 0 has 4 "
                            "vertices"),
        std::string::npos)
        << messages.str();
}

// A SubdivisionMesh's texture coordinates as given, per face-vertex: a flat 2x2 grid over
// the frame whose left faces map s to [0, 0.4] and right faces to [0.6, 1] (a seam down
// the middle, as an asset's UV layout cuts it), t = (y + 1) / 2, shown by a shader as
// colour (s, t, 0). Each half keeps its own range up to the seam, the halves' means are
// 0.2 and 0.8 (the layout is symmetric about each half's middle), and t climbs up the
// frame. (Before, a SubdivisionMesh's st was (0, 0) everywhere.)
TEST(Geometry, SubdivisionTextureCoordinatesAsGiven) {
    const std::string dir = rd::test::scratchDir("raydrive_subdiv_st");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/showst.sl") << "surface showst() { Ci = color(s, t, 0); Oi = 1; }\n";
    std::string st;
    const int corners[4][4] = {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}};
    for (const auto& face : corners)
        for (int v : face) {
            const double x = v % 3 - 1.0, y = v / 3 - 1.0;
            const bool left = face[0] % 3 == 0;
            st += std::to_string(left ? 0.4 * (x + 1) : 0.6 + 0.4 * x) + " " +
                  std::to_string((y + 1) / 2) + "  ";
        }
    Rendered img = renderRib(
        "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n"
        "Format 32 32 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
        "ScreenWindow -1 1 -1 1\nTranslate 0 0 5\nWorldBegin\nSurface \"showst\"\n"
        "SubdivisionMesh \"catmull-clark\" [4 4 4 4] [0 1 4 3  1 2 5 4  3 4 7 6  4 5 8 7] "
        "[\"interpolateboundary\"] [0 0] [] [] \"P\" [-1 -1 0  0 -1 0  1 -1 0  -1 0 0  0 0 0  "
        "1 0 0  -1 1 0  0 1 0  1 1 0] \"facevarying float[2] st\" [" + st + "]\nWorldEnd\n");
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const float s = img.at(x, y).r;
            if (x < 15) {
                EXPECT_LE(s, 0.4f + 1e-4f) << x << "," << y;
            }
            if (x > 16) {
                EXPECT_GE(s, 0.6f - 1e-4f) << x << "," << y;
            }
            if (y > 0) {
                EXPECT_LT(img.at(x, y).g, img.at(x, y - 1).g) << x << "," << y;
            }
        }
    EXPECT_NEAR(img.mean(0, 0, 0, 16, 32), 0.2, 0.01);
    EXPECT_NEAR(img.mean(0, 16, 0, 32, 32), 0.8, 0.01);
    EXPECT_NEAR(img.mean(1, 0, 0, 32, 32), 0.5, 0.01);
}

// The nine kinds of geometry that take values per point, each over [-1, 1] x [-1, 1] in
// a 32x32 frame (one sample a pixel) under `surface`, with variables (a declaration, and
// the value at a control point at x); `check` is called on each pixel a geometry covers
// whole, and the sums of red over the frame's left and right halves are returned with
// the count of such pixels.
using PointVariable = std::pair<std::string, std::function<std::string(double)>>;
struct HalfSums {
    std::string what;
    int covered = 0;
    double left = 0, right = 0;
};
std::vector<HalfSums> perPointOnEveryGeometry(
    const std::string& options, const std::string& surface,
    const std::vector<PointVariable>& variables,
    const std::function<void(const std::string&, int, int, const rd::Rgba&)>& check) {
    auto values = [&](std::initializer_list<double> xs) {
        std::string out;
        for (const auto& [decl, valueAt] : variables) {
            out += "\"" + decl + "\" [";
            for (double x : xs) out += valueAt(x) + "  ";
            out += "] ";
        }
        return out + "\n";
    };
    const std::string quad = "\"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] ";
    const std::string grid = "\"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] ";
    const std::vector<std::pair<std::string, std::string>> geometry = {
        {"Polygon", "Polygon " + quad + values({-1, 1, 1, -1})},
        {"GeneralPolygon", "GeneralPolygon [4] " + quad + values({-1, 1, 1, -1})},
        {"PointsPolygons", "PointsPolygons [4] [0 1 2 3] " + quad + values({-1, 1, 1, -1})},
        {"Patch", "Patch \"bilinear\" " + grid + values({-1, 1, -1, 1})},
        {"PatchMesh", "PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" \"P\" "
                      "[-1 -1 0  0 -1 0  1 -1 0  -1 1 0  0 1 0  1 1 0] " +
                          values({-1, 0, 1, -1, 0, 1})},
        {"NuPatch",
         "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + grid + values({-1, 1, -1, 1})},
        {"SubdivisionMesh", "SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] "
                            "[\"interpolateboundary\"] [0 0] [] [] " +
                                quad + values({-1, 1, 1, -1})},
        {"Curves", "Curves \"linear\" [2] \"nonperiodic\" \"P\" [-1 0 0  1 0 0] "
                   "\"constantwidth\" [0.5] " + values({-1, 1})},
        {"Points",
         "Points \"P\" [-0.5 0 0  0.5 0 0] \"constantwidth\" [0.8] " + values({-0.5, 0.5})}};
    std::vector<HalfSums> out;
    for (const auto& [what, g] : geometry) {
        Rendered img = renderRib(options + "Format 32 32 1\nPixelSamples 1 1\n"
                                           "Projection \"orthographic\"\n"
                                           "ScreenWindow -1 1 -1 1\nTranslate 0 0 5\n"
                                           "WorldBegin\nSurface \"" +
                                 surface + "\"\n" + g + "WorldEnd\n");
        HalfSums sums{what};
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const rd::Rgba& c = img.at(x, y);
                if (c.a < 1.0f) continue;
                ++sums.covered;
                check(what, x, y, c);
                (x < 16 ? sums.left : sums.right) += c.r;
            }
        out.push_back(sums);
    }
    return out;
}

// Cs given per point reaches the surface's colour on every kind of geometry (before, only
// polygons and exact quadrics carried it: the others came out white). The colour at a
// control point at x is ((x + 1) / 2, 0.25, (1 - x) / 2): any interpolation's weights sum
// to one, so every covered pixel has green 0.25 and red + blue 1, and red climbs from left
// to right (points: one colour a disc); also in six colour channels, each RGB channel
// twice (ColorSamples: RGB -> (r g b r g b), back by halves).
TEST(Geometry, PerPointColourOnEveryGeometry) {
    const std::string sixChannels =
        "ColorSamples [0.5 0 0  0 0.5 0  0 0 0.5  0.5 0 0  0 0.5 0  0 0 0.5] "
        "[1 0 0 1 0 0  0 1 0 0 1 0  0 0 1 0 0 1]\n";
    for (bool six : {false, true}) {
        auto colour = [&](double x) {
            const std::string rgb =
                std::to_string((x + 1) / 2) + " 0.25 " + std::to_string((1 - x) / 2) + " ";
            return six ? rgb + rgb : rgb;
        };
        auto check = [&](const std::string& what, int x, int y, const rd::Rgba& c) {
            EXPECT_NEAR(c.g, 0.25f, 1e-5f) << what << " " << x << "," << y << " " << six;
            EXPECT_NEAR(c.r + c.b, 1.0f, 1e-5f) << what << " " << x << "," << y << " " << six;
        };
        for (const HalfSums& h : perPointOnEveryGeometry(six ? sixChannels : std::string(),
                                                         "constant",
                                                         {{"varying color Cs", colour}}, check)) {
            EXPECT_GT(h.covered, 100) << h.what;
            EXPECT_LT(h.left, h.right) << h.what;
        }
    }
}

// Texture coordinates given per point, likewise: st = (0.2 + 0.3 (x + 1), 0.25) at a
// control point at x, shown by a shader as colour (s, t, 0), so t is 0.25 at every
// covered pixel and s within [0.2, 0.8], climbing left to right (before: patches, NuPatch,
// subdivision meshes, curves and points showed their own (u, v) or nothing). Also as
// "s" and "t" apart.
TEST(Geometry, PerPointTextureCoordinatesOnEveryGeometry) {
    const std::string dir = rd::test::scratchDir("raydrive_point_st");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/showst.sl") << "surface showst() { Ci = color(s, t, 0); Oi = 1; }\n";
    const std::string path = "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n";
    auto check = [&](const std::string& what, int x, int y, const rd::Rgba& c) {
        EXPECT_NEAR(c.g, 0.25f, 1e-5f) << what << " " << x << "," << y;
        EXPECT_GE(c.r, 0.2f - 1e-5f) << what << " " << x << "," << y;
        EXPECT_LE(c.r, 0.8f + 1e-5f) << what << " " << x << "," << y;
    };
    auto sOf = [](double x) { return std::to_string(0.2 + 0.3 * (x + 1)); };
    auto quarter = [](double) { return std::string("0.25"); };
    for (const std::vector<PointVariable>& given :
         {std::vector<PointVariable>{
              {"varying float[2] st", [&](double x) { return sOf(x) + " 0.25"; }}},
          std::vector<PointVariable>{{"varying float s", sOf}, {"varying float t", quarter}}})
        for (const HalfSums& h : perPointOnEveryGeometry(path, "showst", given, check)) {
            EXPECT_GT(h.covered, 100) << h.what << " " << given[0].first;
            EXPECT_LT(h.left, h.right) << h.what << " " << given[0].first;
        }
}

// Blobby (RI 3.2 5.6): a lone blob is a sphere of radius 0.5 under its matrix (here
// scaled by 2: a disc of radius 1 seen head on); two such blobs 2.4 apart add into one
// shape bridged between them, whose covered area is more than two discs'. Before,
// Blobby was ignored (nothing drawn).
TEST(Geometry, BlobbyImplicitSurfaces) {
    const std::string scale2 = "2 0 0 0 0 2 0 0 0 0 2 0 ";
    EXPECT_NEAR(coverage("Blobby 1 [1001 0] [" + scale2 + "0 0 0 1] []\n"), kPi, 0.1);
    const double two = coverage("Blobby 2 [1001 0 1001 16 0 2 0 1] [" + scale2 +
                                "-1.2 0 0 1 " + scale2 + "1.2 0 0 1] []\n");
    EXPECT_GT(two, 2 * kPi + 0.1);
    EXPECT_LT(two, 16.0);
}

// Per-blob colours (RI: "varying color Cs", one a leaf) blend over a Blobby as its blobs
// do: two blobs under a scale of 1.5 at x = -0.9 and 0.9, red and blue, under the
// constant shader. Every fully covered pixel has red + blue = 1 and no green (the
// weights sum to one); where only the left blob reaches (x < -0.6) it is red alone; the
// two middle columns' fully covered pixels are half and half (symmetric, within 0.01).
// Before, per-blob values were a warning and the surface white.
TEST(Geometry, BlobbyPerBlobColoursBlend) {
    const std::string scale = "1.5 0 0 0 0 1.5 0 0 0 0 1.5 0 ";
    Rendered img = renderRib(
        "Format 64 64 1\nPixelSamples 4 4\n"
        "Option \"render\" \"float pixelerror\" [1e-9]\n"
        "Projection \"orthographic\"\nScreenWindow -2 2 -2 2\n"
        "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n"
        "Blobby 2 [1001 0 1001 16 0 2 0 1] [" +
        scale + "-0.9 0 0 1 " + scale +
        "0.9 0 0 1] [] \"varying color Cs\" [1 0 0  0 0 1]\n"
        "WorldEnd\n");
    int full = 0, redAlone = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const auto& p = img.at(x, y);
            if (p.a < 1.0f) continue;
            ++full;
            EXPECT_NEAR(p.r + p.b, 1.0, 1e-4) << x << " " << y;
            EXPECT_NEAR(p.g, 0.0, 1e-6);
            if (-2.0 + (x + 1) / 16.0 < -0.6) {  // the pixel's right edge
                EXPECT_NEAR(p.r, 1.0, 1e-6) << x << " " << y;
                ++redAlone;
            }
        }
    EXPECT_GT(full, 600);
    EXPECT_GT(redAlone, 100);
    double red = 0, blue = 0;  // the two middle columns' fully covered pixels
    for (int y = 0; y < img.height; ++y)
        for (int x = 31; x <= 32; ++x)
            if (img.at(x, y).a >= 1.0f) red += img.at(x, y).r, blue += img.at(x, y).b;
    ASSERT_GT(red + blue, 4.0);
    EXPECT_NEAR(red / (red + blue), 0.5, 0.01);
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
