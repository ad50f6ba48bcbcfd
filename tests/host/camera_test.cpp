// camera_test.cpp: depth of field, crop windows and matte (holdout) objects, rendered on
// PoCL and checked against what the RI spec says they do.
#include <gtest/gtest.h>

#include <algorithm>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// A constant white half-plane (x < 0) at depth 5 seen by a 60-degree camera with the
// given DepthOfField line; returns the number of pixels of row 16 whose alpha is
// strictly between 0.05 and 0.95 (the width of the blurred edge).
int edgeWidth(const std::string& dof) {
    Rendered img = renderRib("Format 32 32 1\nPixelSamples 8 8\n"
                             "Option \"render\" \"float pixelerror\" [1e-9]\n"
                             "Projection \"perspective\" \"fov\" 60\n" + dof +
                             "WorldBegin\nSurface \"constant\"\n"
                             "Polygon \"P\" [-50 -50 5  0 -50 5  0 50 5  -50 50 5]\n"
                             "WorldEnd\n");
    int n = 0;
    for (int x = 0; x < 32; ++x) n += img.at(x, 16).a > 0.05f && img.at(x, 16).a < 0.95f;
    return n;
}

}  // namespace

// In focus, the edge stays as sharp as a pinhole's (one pixel of partial coverage); with
// the focus at 1 instead of 5 and a lens of radius 0.25 the blur circle on the plane is
// 0.25 * (5 - 1) / 1 = 1 unit across ... about 9 pixels at this scale: the edge spreads.
TEST(Camera, DepthOfFieldBlursOnlyWhatIsOutOfFocus) {
    int pinhole = edgeWidth("");
    int inFocus = edgeWidth("DepthOfField 2 1 5\n");   // lens radius 1 / (2*2) = 0.25
    int outOfFocus = edgeWidth("DepthOfField 2 1 1\n");
    std::printf("edge width in pixels: pinhole %d, in focus %d, out of focus %d\n", pinhole,
                inFocus, outOfFocus);
    EXPECT_LE(pinhole, 1);
    EXPECT_LE(inFocus, 1);
    EXPECT_GE(outOfFocus, 5);
}

// CropWindow renders only the pixels whose centres fall inside it.
TEST(Camera, CropWindowRendersOnlyItsPixels) {
    Rendered img = renderRib("Format 40 40 1\nPixelSamples 1 1\nCropWindow 0.25 0.75 0 0.5\n"
                             "Projection \"orthographic\"\nWorldBegin\nSurface \"constant\"\n"
                             "Polygon \"P\" [-5 -5 1  5 -5 1  5 5 1  -5 5 1]\nWorldEnd\n");
    EXPECT_EQ(img.film.cropX0, 10);
    EXPECT_EQ(img.film.cropX1, 30);
    EXPECT_EQ(img.film.cropY0, 0);
    EXPECT_EQ(img.film.cropY1, 20);
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x) {
            bool inside = x >= 10 && x < 30 && y < 20;
            EXPECT_EQ(img.count(x, y) > 0, inside) << x << "," << y;
        }
    EXPECT_EQ(img.stats.unsampledPixels, 0u);
}

// Matte 1: a holdout hides the plane behind it and adds neither colour nor alpha.
TEST(Camera, MatteObjectIsAHoldout) {
    Rendered img = renderRib("Format 20 20 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                             "WorldBegin\nSurface \"constant\"\nColor [1 1 1]\n"
                             "Polygon \"P\" [-5 -5 2  5 -5 2  5 5 2  -5 5 2]\n"
                             "AttributeBegin\nMatte 1\n"
                             "Polygon \"P\" [-0.5 -0.5 1  0.5 -0.5 1  0.5 0.5 1  -0.5 0.5 1]\n"
                             "AttributeEnd\nWorldEnd\n");
    EXPECT_EQ(img.at(10, 10).a, 0.0f);
    EXPECT_EQ(img.at(10, 10).r, 0.0f);
    EXPECT_EQ(img.at(1, 1).a, 1.0f);
    EXPECT_EQ(img.at(1, 1).r, 1.0f);
}

// RI's other way to a perspective camera: Projection "null" then Perspective fov (or a
// Perspective first among the camera's transforms) renders what Projection
// "perspective" "fov" does.
TEST(Camera, PerspectiveRequestIsTheProjection) {
    const std::string world = "Translate 0 0 5\nWorldBegin\nSurface \"matte\"\n"
                              "LightSource \"distantlight\" 1\nSphere 1 -1 1 360\nWorldEnd\n";
    const std::string head = "Format 24 24 1\nPixelSamples 1 1\n";
    Rendered projection = renderRib(head + "Projection \"perspective\" \"fov\" 40\n" + world);
    Rendered null = renderRib(head + "Projection \"null\"\nPerspective 40\n" + world);
    Rendered bare = renderRib(head + "Perspective 40\n" + world);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            EXPECT_EQ(projection.at(x, y).r, null.at(x, y).r) << x << " " << y;
            EXPECT_EQ(projection.at(x, y).a, bare.at(x, y).a) << x << " " << y;
        }
    EXPECT_GT(projection.at(12, 12).a, 0.5f);
    EXPECT_EQ(projection.at(0, 0).a, 0.0f) << "fov 40 at distance 5 leaves the corners empty";
}

// ClippingPlane (RI 3.2): camera rays do not see what lies on the side its normal points
// to. A unit sphere over a blue plane, head on: clipped at x = 0 (normal +x, given in the
// world) the right halves of both are gone. A plane given before the world
// is in camera space: at camera z = 4.5, normal -z, it clips the sphere's nearer cap (a
// disc of radius sqrt(0.75) seen head on), through which, the sphere one-sided, the plane
// shows: a white ring of area pi / 4 is left. Camera "main" names the camera space as a
// coordinate system: a disk placed in it at z = 3 is seen head on.
TEST(Camera, ClippingPlanesHideWhatLiesBeyondThem) {
    auto render = [](const std::string& options, const std::string& world,
                     const std::string& sphere = "") {
        return renderRib(
            "Format 32 32 1\nPixelSamples 4 4\n"
            "Option \"render\" \"float pixelerror\" [1e-9]\n"
            "Projection \"orthographic\"\nScreenWindow -2 2 -2 2\n" +
            options + "Translate 0 0 5\nWorldBegin\n" + world +
            "AttributeBegin\nColor [0 0 1]\nSurface \"constant\"\n"
            "Polygon \"P\" [-3 -3 3  3 -3 3  3 3 3  -3 3 3]\nAttributeEnd\n"
            "Surface \"constant\"\n" +
            sphere + "Sphere 1 -1 1 360\nWorldEnd\n");
    };
    const double kPi = 3.14159265358979;
    const Rendered whole = render("", "");
    EXPECT_NEAR(whole.mean(0, 0, 0, 32, 32) * 16, kPi, 0.1);
    const Rendered half = render("", "ClippingPlane 0 0 0 1 0 0\n");
    EXPECT_NEAR(half.mean(0, 0, 0, 32, 32) * 16, kPi / 2, 0.1)
        << "the right half clipped";
    EXPECT_NEAR(half.mean(3, 17, 0, 32, 32), 0.0, 1e-6) << "nothing right of the plane";
    EXPECT_NEAR(half.mean(2, 0, 0, 15, 32), 1.0, 1e-6) << "the blue plane left of it";
    EXPECT_NEAR(half.mean(0, 10, 14, 14, 18), 1.0, 1e-6) << "the sphere's left half";
    const auto& names = half.stats.features.names();
    EXPECT_TRUE(std::find(names.begin(), names.end(), "clipping_planes") != names.end());
    // camera space, before the world: the cap nearer than camera z = 4.5 is clipped, and
    // through it (the sphere one-sided: its inside is not there) the blue plane shows
    const Rendered cap = render("ClippingPlane 0 0 4.5 0 0 -1\n", "", "Sides 1\n");
    EXPECT_NEAR(cap.mean(0, 0, 0, 32, 32) * 16, kPi * 0.25, 0.1) << "a ring left";
    EXPECT_NEAR(cap.mean(2, 14, 14, 18, 18), 1.0, 1e-6) << "the plane through the cap";
    // the camera named, and a disk placed in its space
    const Rendered named = renderRib(
        "Format 32 32 1\nPixelSamples 4 4\nOption \"render\" \"float pixelerror\" "
        "[1e-9]\n"
        "Projection \"orthographic\"\nScreenWindow -2 2 -2 2\nRotate 30 0 1 0\n"
        "Translate 0 0 5\nCamera \"main\"\nWorldBegin\nSurface \"constant\"\n"
        "CoordSysTransform \"main\"\nTranslate 0 0 3\nDisk 0 1 360\nWorldEnd\n");
    EXPECT_NEAR(named.mean(3, 0, 0, 32, 32) * 16, kPi, 0.1) << "a disc seen head on";
}
