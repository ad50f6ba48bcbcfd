// degenerate_test.cpp: case 4, degenerate input: zero-area triangles, NaN/Inf vertices,
// zero-length normals, collinear polygons, coincident faces: no crash, no NaN in the
// film, and each defective request reported once as a warning at its RIB file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

struct Line {
    std::string request;
    bool defective;
};

}  // namespace

// Every surface is matte, Cs 0.5, under a distant light from the eye: wherever a valid
// surface is seen the pixel is 0.5 (the zero-normal square is shaded with its geometric
// normal; behind it, in its shadow, a square given twice covers the whole frame).
TEST(Numerics, DegenerateInputIsReportedOnceAndRendersClean) {
    const std::vector<Line> lines = {
        {"Format 16 16 1", false},
        {"PixelSamples 2 2", false},
        {"Projection \"perspective\" \"fov\" 40", false},
        {"WorldBegin", false},
        {"LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]", false},
        {"Color [0.5 0.5 0.5]", false},
        {"Surface \"matte\"", false},
        // zero-area triangle (a repeated vertex)
        {"Polygon \"P\" [0 0 5  0 0 5  1 0 5]", true},
        // NaN and Inf vertices
        {"Polygon \"P\" [nan 0 5  1 0 5  0 1 5]", true},
        {"Polygon \"P\" [0 0 5  inf 0 5  0 1 5]", true},
        // a vertex sent to infinity by the transform
        {"TransformBegin", false},
        {"Scale 1e30 1e30 1e30", false},
        {"Polygon \"P\" [0 0 1e10  1 0 5  0 1 5]", true},
        {"TransformEnd", false},
        // zero-length normals on a valid square
        {"Polygon \"P\" [-1 -1 5  1 -1 5  1 1 5  -1 1 5] \"N\" [0 0 0  0 0 0  0 0 0  0 0 0]",
         true},
        // a collinear polygon
        {"Polygon \"P\" [0 0 5  1 0 5  2 0 5  3 0 5]", true},
        // a mesh with the same face twice (coincident faces), one warning for the request
        {"PointsPolygons [4 4 3] [0 1 2 3  0 1 2 3  0 0 1] \"P\" "
         "[-3 -3 6  3 -3 6  3 3 6  -3 3 6]", true},
        // the same triangle again with -0 for +0 (equal coordinates): coincident too
        {"PointsPolygons [3 3] [0 1 2  3 4 5] \"P\" [0 0 7  1 0 7  0 1 7  -0 0 7  1 -0 7  -0 1 7]",
         true},
        {"WorldEnd", false},
    };
    std::string rib;
    for (const Line& l : lines) rib += l.request + "\n";
    Diagnosed d = renderWithDiagnostics(rib);
    int defective = 0;
    for (size_t i = 0; i < lines.size(); ++i) {
        const std::string at = "test.rib:" + std::to_string(i + 1) + ": warning: ";
        EXPECT_EQ(countOf(d.messages, at), lines[i].defective ? 1 : 0)
            << "line " << i + 1 << ": " << lines[i].request << "\n" << d.messages;
        defective += lines[i].defective;
    }
    EXPECT_EQ(d.warnings, defective) << d.messages;
    EXPECT_EQ(d.errors, 0) << d.messages;
    const auto& img = d.image;
    EXPECT_TRUE(allFinite(img));
    EXPECT_EQ(img.stats.nonfiniteSamples, 0u);
    EXPECT_EQ(img.stats.shadeNonfinite, 0u);
    // two triangles of the lit square, two of the back square (its copy left out), one
    // behind it (its -0 copy left out)
    EXPECT_EQ(img.stats.triangles, 5u);
    double err = 0;
    for (const rd::Rgba& p : img.pixels)
        err = std::fmax(err, std::fmax(std::fabs(p.r - 0.5), std::fabs(p.a - 1.0)));
    EXPECT_TRUE(report("degenerate_input_image", 1e-5, err)) << d.messages;
}

// Coincident faces given by two requests (z-fighting by construction): the closest-hit
// order (t, then primitive) makes the image independent of the order of the BVH and the
// same from run to run; both colours are finite, the first-given face wins everywhere.
TEST(Numerics, CoincidentFacesAreDeterministic) {
    const std::string rib = camera(16, 40, 2) +
                            "WorldBegin\nSurface \"constant\"\n"
                            "Color [1 0 0]\n" + squareAtZ(5.0) +
                            "Color [0 0 1]\n" + squareAtZ(5.0) + "WorldEnd\n";
    Diagnosed a = renderWithDiagnostics(rib), b = renderWithDiagnostics(rib);
    double err = 0;
    for (size_t i = 0; i < a.image.pixels.size(); ++i) {
        err = std::fmax(err, std::fabs(a.image.pixels[i].r - b.image.pixels[i].r));
        err = std::fmax(err, std::fabs(a.image.pixels[i].r - 1.0f));
        err = std::fmax(err, std::fabs(a.image.pixels[i].b));
    }
    EXPECT_TRUE(report("coincident_faces_first_wins", 0.0, err));
}
