// graphics_state_test.cpp: RI graphics state rendered: Illuminate turning a light off
// and on within attribute blocks, CoordinateSystem/CoordSysTransform placing geometry in
// a named space, AreaLightSource lighting like its shader, and the same scene read as
// ASCII, binary-encoded and gzip-compressed RIB giving the same image.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render_harness.h"
#include "rib/reader.h"
#include "rib/writer.h"
#include "scene/rib_builder.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const char* kCamera =
    "Format 48 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\nScreenWindow -3 3 -1 1\n"
    "Translate 0 0 5\n";

// Three unit squares at x = -2, 0, 2 facing the camera, under a distant light "key" of
// intensity 1 straight on and a matte surface: lit squares are Cs * Kd = 1.
std::string squares(const std::string& first, const std::string& second,
                    const std::string& third) {
    auto square = [](double x) {
        std::ostringstream s;
        s << "Polygon \"P\" [" << x - 0.5 << " -0.5 0  " << x + 0.5 << " -0.5 0  " << x + 0.5
          << " 0.5 0  " << x - 0.5 << " 0.5 0]\n";
        return s.str();
    };
    return std::string(kCamera) +
           "WorldBegin\nLightSource \"distantlight\" \"key\" \"from\" [0 0 0] \"to\" [0 0 1]\n"
           "Surface \"matte\"\n" + first + square(-2) + "AttributeBegin\n" + second + square(0) +
           "AttributeEnd\n" + third + square(2) + "WorldEnd\n";
}

double brightness(const Rendered& img, int column) { return img.mean(0, column - 2, 6, column + 2, 10); }

}  // namespace

// Illuminate "key" 0 turns the light off for the geometry after it, in its attribute
// block only; Illuminate 1 turns it back on.
TEST(GraphicsState, IlluminateTurnsALightOffAndOn) {
    Rendered img = renderRib(squares("", "Illuminate \"key\" 0\n", ""));
    EXPECT_NEAR(brightness(img, 8), 1.0, 1e-3);   // x = -2: lit
    EXPECT_NEAR(brightness(img, 24), 0.0, 1e-6);  // x = 0: the light off inside the block
    EXPECT_NEAR(brightness(img, 40), 1.0, 1e-3);  // x = 2: the block ended, lit again
    Rendered back = renderRib(squares("Illuminate \"key\" 0\n", "Illuminate \"key\" 1\n", ""));
    EXPECT_NEAR(brightness(back, 8), 0.0, 1e-6);
    EXPECT_NEAR(brightness(back, 24), 1.0, 1e-3);
    EXPECT_NEAR(brightness(back, 40), 0.0, 1e-6);
}

// A name given to the transform at one place puts later geometry there again.
TEST(GraphicsState, CoordSysTransformRestoresANamedSpace) {
    Rendered img = renderRib(std::string(kCamera) +
                             "WorldBegin\nSurface \"constant\"\nAttributeBegin\nTranslate 2 0 0\n"
                             "CoordinateSystem \"right\"\nAttributeEnd\nAttributeBegin\n"
                             "CoordSysTransform \"right\"\n"
                             "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n"
                             "AttributeEnd\nWorldEnd\n");
    EXPECT_NEAR(img.mean(3, 38, 6, 42, 10), 1.0, 1e-6);  // at x = 2
    EXPECT_NEAR(img.mean(3, 22, 6, 26, 10), 0.0, 1e-6);  // not at the origin
}

// ScopedCoordinateSystem names the transform until its attribute block ends: inside the
// block (and blocks within it) CoordSysTransform finds it, after the block it is an
// error (the name is not found), and it hides a CoordinateSystem of the same name.
TEST(GraphicsState, ScopedCoordinateSystemEndsWithItsBlock) {
    const std::string square =
        "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n";
    Rendered img =
        renderRib(std::string(kCamera) +
                  "WorldBegin\nSurface \"constant\"\nTranslate -2 0 0\n"
                  "CoordinateSystem \"spot\"\nTranslate 2 0 0\nAttributeBegin\n"
                  "Translate 2 0 0\nScopedCoordinateSystem \"spot\"\nIdentity\n"
                  "AttributeBegin\nCoordSysTransform \"spot\"\n" +
                  square + "AttributeEnd\nAttributeEnd\nCoordSysTransform \"spot\"\n" +
                  square + "WorldEnd\n");
    EXPECT_NEAR(img.mean(3, 38, 6, 42, 10), 1.0, 1e-6);  // x = 2: the scoped one
    EXPECT_NEAR(img.mean(3, 6, 6, 10, 10), 1.0, 1e-6);   // x = -2: the global one after
    EXPECT_NEAR(img.mean(3, 22, 6, 26, 10), 0.0, 1e-6);  // nothing at the origin
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    rd::RibBuilder b(diag, "scoped.rib");
    rib::readString(
        "WorldBegin\nAttributeBegin\nScopedCoordinateSystem \"inner\"\n"
        "AttributeEnd\nCoordSysTransform \"inner\"\nWorldEnd\n",
        "scoped.rib", b, diag);
    EXPECT_EQ(diag.errorCount(), 1);
    EXPECT_NE(
        err.str().find("scoped.rib:5: error: CoordSysTransform: no coordinate system "
                       "named \"inner\""),
        std::string::npos)
        << err.str();
}

// Resource "attributes" (PRMan): a saved colour and place restored in part. Saved red at
// x = -2; then blue at x = 0, where the shading is restored (red); green at x = 2; the
// transform alone restored (back at x = -2, still green). A name saved inside
// ResourceBegin/ResourceEnd ends with the block; restoring it after is an error at its
// file:line.
TEST(GraphicsState, ResourceSavesAndRestoresAttributes) {
    const std::string square =
        "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n";
    const std::string restore =
        "Resource \"look\" \"attributes\" \"string operation\" "
        "[\"restore\"] \"string subset\" ";
    Rendered img = renderRib(
        std::string(kCamera) +
        "WorldBegin\nSurface \"constant\"\nAttributeBegin\n"
        "Color [1 0 0]\nTranslate -2 0 0\nResource \"look\" \"attributes\" "
        "\"string operation\" [\"save\"]\nColor [0 0 1]\nTranslate 2 0 0\n" +
        restore + "[\"shading\"]\n" + square + "Color [0 1 0]\nTranslate 2 0 0\n" +
        square + restore + "[\"transform\"]\n" + square + "AttributeEnd\nWorldEnd\n");
    EXPECT_NEAR(img.mean(0, 22, 6, 26, 10), 1.0, 1e-6);  // x = 0: red
    EXPECT_NEAR(img.mean(2, 22, 6, 26, 10), 0.0, 1e-6);
    EXPECT_NEAR(img.mean(1, 38, 6, 42, 10), 1.0, 1e-6);  // x = 2: green
    EXPECT_NEAR(img.mean(1, 6, 6, 10, 10), 1.0, 1e-6);   // x = -2: green, moved back
    EXPECT_NEAR(img.mean(0, 6, 6, 10, 10), 0.0, 1e-6);
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    rd::RibBuilder b(diag, "res.rib");
    rib::readString(
        "WorldBegin\nResourceBegin\nResource \"inner\" \"attributes\" \"string "
        "operation\" [\"save\"]\nResourceEnd\nResource \"inner\" \"attributes\" "
        "\"string operation\" [\"restore\"]\nResource \"x\" \"attributes\" "
        "\"string operation\" [\"load\"]\nWorldEnd\n",
        "res.rib", b, diag);
    EXPECT_EQ(diag.errorCount(), 2);
    EXPECT_NE(
        err.str().find("res.rib:5: error: Resource \"inner\" restored but never saved"),
        std::string::npos)
        << err.str();
    EXPECT_NE(
        err.str().find("res.rib:6: error: Resource \"x\": \"string operation\" must be"),
        std::string::npos)
        << err.str();
}

// Attribute "visibility" (PRMan, session 30). Seen by the camera (orthographic, x in
// [-1, 1]): a red square over the left half invisible to the camera shows the green
// plane behind it; a blue one over the right half invisible only to traced rays is seen.
// In a mirror facing the camera: a red square behind the camera invisible to traced rays
// leaves the green plane behind it in the reflection's left half; the blue one, visible
// to them, is reflected in the right half.
TEST(GraphicsState, VisibilityToCameraAndTracedRays) {
    const std::string cam =
        "Format 16 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\nWorldBegin\n"
        "Surface \"constant\"\n";
    const std::string green =
        "AttributeBegin\nColor [0 1 0]\nPolygon \"P\" [-5 -5 Z  5 -5 Z  "
        "5 5 Z  -5 5 Z]\nAttributeEnd\n";
    auto plane = [&](const char* z) {
        std::string g = green;
        for (size_t at; (at = g.find('Z')) != std::string::npos;) g.replace(at, 1, z);
        return g;
    };
    auto half = [](const char* colour, const char* vis, float x0, float x1,
                   const char* z) {
        return std::string("AttributeBegin\nColor [") + colour +
               "]\nAttribute \"visibility\" " + vis + "\nPolygon \"P\" [" +
               std::to_string(x0) + " -5 " + z + "  " + std::to_string(x1) + " -5 " + z +
               "  " + std::to_string(x1) + " 5 " + z + "  " + std::to_string(x0) + " 5 " +
               z + "]\nAttributeEnd\n";
    };
    Rendered direct =
        renderRib(cam + plane("10") + half("1 0 0", "\"int camera\" [0]", -5, 0, "5") +
                  half("0 0 1", "\"int trace\" [0]", 0, 5, "5") + "WorldEnd\n");
    EXPECT_NEAR(direct.mean(1, 0, 0, 8, 16), 1.0, 1e-6);  // left: green through the red
    EXPECT_NEAR(direct.mean(0, 0, 0, 8, 16), 0.0, 1e-6);
    EXPECT_NEAR(direct.mean(2, 8, 0, 16, 16), 1.0, 1e-6);  // right: blue
    EXPECT_TRUE(direct.stats.features.invisible);
    // (the mirror's reflection of x is at -x... seen from the camera looking down +z, a
    // ray at x reflects straight back to x, behind the camera)
    Rendered mirrored =
        renderRib(cam + plane("-10") + half("1 0 0", "\"int trace\" [0]", -5, 0, "-5") +
                  half("0 0 1", "\"int camera\" [1] \"int trace\" [1]", 0, 5, "-5") +
                  "AttributeBegin\nSurface \"mirror\"\nPolygon \"P\" [-5 -5 5  5 -5 5  5 "
                  "5 5  -5 5 5]\n"
                  "AttributeEnd\nWorldEnd\n");
    EXPECT_NEAR(mirrored.mean(1, 0, 0, 8, 16), 1.0, 1e-6);  // left: green, not red
    EXPECT_NEAR(mirrored.mean(0, 0, 0, 8, 16), 0.0, 1e-6);
    EXPECT_NEAR(mirrored.mean(2, 8, 0, 16, 16), 1.0, 1e-6);  // right: blue reflected
}

// Shadows through surfaces that let light through (DESIGN.md section 4): a shadow ray
// keeps 1 - Os of each surface it passes (PRMan's "primitive" transmission), all of it
// past a surface with "transmission" 0, none past an "opaque" one. A white matte floor
// under a distant light straight on; squares the camera does not see (visibility camera
// 0) float between, at x = -2 (two layers), 0 and 2.
TEST(GraphicsState, ShadowsThroughSurfacesTakeTheirTransmission) {
    auto square = [](double x, double z, const std::string& attributes) {
        std::ostringstream s;
        s << "AttributeBegin\nAttribute \"visibility\" \"int camera\" [0]\n"
          << attributes << "\nPolygon \"P\" [" << x - 0.6 << " -0.6 " << z << "  "
          << x + 0.6 << " -0.6 " << z << "  " << x + 0.6 << " 0.6 " << z << "  "
          << x - 0.6 << " 0.6 " << z << "]\nAttributeEnd\n";
        return s.str();
    };
    const std::string floor =
        "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n"
        "Surface \"matte\"\nPolygon \"P\" [-9 -9 0  9 -9 0  9 9 0  -9 9 0]\n";
    const std::string squares =
        square(-2, -1, "Opacity [0.25 0.5 1]") + square(-2, -2, "Opacity [0.5 0.5 0.5]") +
        square(0, -1, "Attribute \"visibility\" \"int transmission\" [0]") +
        square(2, -1,
               "Opacity [0.5 0.5 0.5]\nAttribute \"visibility\" \"string transmission\" "
               "[\"opaque\"]");
    Rendered r = renderRib(std::string(kCamera) + floor + squares + "WorldEnd\n");
    auto at = [&](int channel, int column) {
        return r.mean(channel, column - 2, 6, column + 2, 10);
    };
    EXPECT_NEAR(at(0, 8), 0.75 * 0.5, 1e-5);  // two layers: (1 - Os) each
    EXPECT_NEAR(at(1, 8), 0.5 * 0.5, 1e-5);
    EXPECT_NEAR(at(2, 8), 0.0, 1e-6);
    EXPECT_NEAR(at(0, 24), 1.0, 1e-5);  // casts no shadow
    EXPECT_NEAR(at(0, 40), 0.0, 1e-6);  // a full one
    EXPECT_NEAR(at(0, 16), 1.0, 1e-5);  // between them
    EXPECT_TRUE(r.stats.features.transparentShadows);
    EXPECT_FALSE(r.stats.features.shadowPackets);  // (the closest-hit walk)
    // A sphere is two surfaces on the way: (1 - Os)^2; a triangle mesh's closed box too.
    Rendered sphere =
        renderRib(std::string(kCamera) + floor +
                  "AttributeBegin\nAttribute \"visibility\" \"int camera\" [0]\nOpacity "
                  "[0.5 0.5 0.5]\n"
                  "Translate -2 0 -1\nSphere 0.9 -0.9 0.9 360\nTranslate 4 0 0\n"
                  "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 "
                  "6 4  1 5 7 3] "
                  "\"P\" [-0.6 -0.6 -0.6  0.6 -0.6 -0.6  -0.6 0.6 -0.6  0.6 0.6 -0.6  "
                  "-0.6 -0.6 0.6  "
                  "0.6 -0.6 0.6  -0.6 0.6 0.6  0.6 0.6 0.6]\nAttributeEnd\nWorldEnd\n");
    EXPECT_NEAR(sphere.mean(0, 7, 7, 9, 9), 0.25, 1e-5);
    EXPECT_NEAR(sphere.mean(0, 39, 6, 41, 10), 0.25, 1e-5);
    // Opaque surfaces alone keep the any-hit walk, in packets.
    Rendered opaque =
        renderRib(std::string(kCamera) + floor + square(0, -1, "") + "WorldEnd\n");
    EXPECT_FALSE(opaque.stats.features.transparentShadows);
    EXPECT_TRUE(opaque.stats.features.shadowPackets);
    EXPECT_NEAR(opaque.mean(0, 22, 6, 26, 10), 0.0, 1e-6);
}

// AreaLightSource: its light shader lights the scene like the same LightSource.
TEST(GraphicsState, AreaLightSourceLightsLikeItsShader) {
    const std::string rest =
        "\"from\" [0 0 0] \"to\" [0 0 1]\nSurface \"matte\"\n"
        "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\nWorldEnd\n";
    Rendered area = renderRib(std::string(kCamera) + "WorldBegin\nAreaLightSource \"distantlight\" \"a\" " + rest);
    Rendered plain = renderRib(std::string(kCamera) + "WorldBegin\nLightSource \"distantlight\" \"a\" " + rest);
    EXPECT_NEAR(area.mean(0, 22, 6, 26, 10), plain.mean(0, 22, 6, 26, 10), 1e-6);
    EXPECT_GT(area.mean(0, 22, 6, 26, 10), 0.5);
}

// The same scene as ASCII, binary-encoded (RI 3.2 appendix C, by the RIB writer) and
// gzip-compressed RIB renders to the same image.
TEST(GraphicsState, AsciiBinaryAndGzipRibGiveTheSameImage) {
    const std::string ascii =
        std::string(kCamera) +
        "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [1 1 -1] \"to\" [0 0 0]\n"
        "Surface \"plastic\"\nColor [0.8 0.4 0.2]\nSphere 0.8 -0.8 0.8 360\n"
        "Translate 1.8 0 0\nPolygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n"
        "WorldEnd\n";
    // binary: the ASCII text read back through the writer in binary encoding
    std::ostringstream bin;
    {
        rib::RibWriter writer(bin, rib::RibWriter::Encoding::Binary);
        rib::Diagnostics diag;
        ASSERT_TRUE(rib::readString(ascii, "scene.rib", writer, diag));
    }
    std::string dir = rd::test::scratchDir("raydrive_encodings");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/binary.rib", std::ios::binary) << bin.str();
    gzFile gz = gzopen((dir + "/scene.rib.gz").c_str(), "wb");
    ASSERT_NE(gz, nullptr);
    gzwrite(gz, ascii.data(), unsigned(ascii.size()));
    gzclose(gz);
    auto renderFile = [&](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        return text.str();
    };
    EXPECT_NE(bin.str(), ascii);
    Rendered a = renderRib(ascii);
    Rendered b = renderRib(renderFile(dir + "/binary.rib"));
    // gzip: read through the file reader, which detects the magic
    rib::Diagnostics diag;
    std::ostringstream roundTrip;
    {
        rib::RibWriter writer(roundTrip);
        ASSERT_TRUE(rib::readFile(dir + "/scene.rib.gz", writer, diag));
    }
    Rendered c = renderRib(roundTrip.str());
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    ASSERT_EQ(a.pixels.size(), c.pixels.size());
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        EXPECT_EQ(a.pixels[i].r, b.pixels[i].r) << "pixel " << i;
        EXPECT_EQ(a.pixels[i].r, c.pixels[i].r) << "pixel " << i;
        EXPECT_EQ(a.pixels[i].a, c.pixels[i].a) << "pixel " << i;
    }
}

namespace {
// Coverage of one unit square at the image centre (constant shader), after `state`.
double coverage(const std::string& state, bool clockwise) {
    const char* cw = "Polygon \"P\" [-0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0  0.5 -0.5 0]\n";
    const char* ccw = "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n";
    Rendered img = renderRib(std::string(kCamera) + "WorldBegin\nSurface \"constant\"\n" + state +
                             (clockwise ? cw : ccw) + "WorldEnd\n");
    return img.mean(3, 22, 6, 26, 10);
}
}  // namespace

// RI: a polygon's normal points toward the viewer who sees its vertices clockwise (camera
// space is left-handed); Sides 1 hides its back; Orientation/ReverseOrientation turn it
// inside out; a mirroring transform flips the coordinate system and the orientation
// together, so the front stays the front.
TEST(GraphicsState, SidesAndOrientation) {
    EXPECT_EQ(coverage("Sides 1\n", true), 1.0);   // clockwise from the eye: its front
    EXPECT_EQ(coverage("Sides 1\n", false), 0.0);  // counter-clockwise: its back, hidden
    EXPECT_EQ(coverage("Sides 2\n", false), 1.0);  // two-sided: both
    EXPECT_EQ(coverage("Sides 1 ReverseOrientation\n", false), 1.0);
    EXPECT_EQ(coverage("Sides 1 ReverseOrientation\n", true), 0.0);
    EXPECT_EQ(coverage("Sides 1 Orientation \"inside\"\n", true), 0.0);
    EXPECT_EQ(coverage("Sides 1 Orientation \"rh\"\n", true), 0.0);  // camera space is lh
    EXPECT_EQ(coverage("Sides 1 Orientation \"lh\"\n", true), 1.0);
    EXPECT_EQ(coverage("Sides 1 Scale -1 1 1\n", true), 1.0);  // mirrored: still its front
    EXPECT_EQ(coverage("Sides 1 Scale -1 1 1 Orientation \"lh\"\n", true), 0.0);
}

// From inside a sphere its outside faces away: one-sided it vanishes, reversed it shows.
TEST(GraphicsState, OneSidedSphereFromInside) {
    auto inside = [](const std::string& state) {
        Rendered img = renderRib("Format 16 16 1\nPixelSamples 1 1\nProjection \"perspective\" "
                                 "\"fov\" 60\nWorldBegin\nSurface \"constant\"\n" + state +
                                 "Sphere 2 -2 2 360\nWorldEnd\n");
        return img.mean(3, 0, 0, 16, 16);
    };
    EXPECT_EQ(inside(""), 1.0);
    EXPECT_EQ(inside("Sides 1\n"), 0.0);
    EXPECT_EQ(inside("Sides 1 ReverseOrientation\n"), 1.0);
}

// Skew 45 degrees turning the y axis toward x: x' = x + y, a square becomes a
// parallelogram of the same area leaning right.
TEST(GraphicsState, SkewShearsAlongTheSecondAxis) {
    Rendered img = renderRib(std::string(kCamera) +
                             "WorldBegin\nSurface \"constant\"\nSkew 45 0 1 0 1 0 0\n"
                             "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n"
                             "WorldEnd\n");
    auto alphaAt = [&](double x, double y) { return img.at(int((x + 3) * 8), int((1 - y) * 8)).a; };
    EXPECT_EQ(alphaAt(0.6, 0.4), 1.0f);    // x + y: the top moved right (unskewed: outside)
    EXPECT_EQ(alphaAt(-0.3, 0.4), 0.0f);
    EXPECT_EQ(alphaAt(-0.7, -0.4), 1.0f);  // the bottom moved left
    EXPECT_NEAR(img.mean(3, 0, 0, 48, 16) * 12.0, 1.0, 0.03);  // shear keeps the area
}

// TextureCoordinates give the default s, t of parametric surfaces: a disk whose v runs
// rim to centre shows s = 2 - 2v ... here t = 1 at the rim, 3 at the centre.
TEST(GraphicsState, TextureCoordinatesMapTheDefaultST) {
    std::string dir = rd::test::scratchDir("raydrive_texcoords");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/showt.sl") << "surface showt() {\n    Oi = 1;\n    Ci = color(t, s, 0);\n}\n";
    Rendered img = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                             std::string(kCamera) +
                             "WorldBegin\nSurface \"showt\"\nTextureCoordinates 0 1 0 1 0 3 0 3\n"
                             "Disk 0 1 360\nWorldEnd\n");
    // the centre pixel: v near 1, t near 3; s = 0 everywhere
    EXPECT_NEAR(img.at(24, 8).r, 3.0f, 0.2f);
    EXPECT_NEAR(img.at(24, 8).g, 0.0f, 1e-6f);
}

// Requests the renderer cannot honour say so instead of being ignored silently.
TEST(GraphicsState, UnsupportedRequestsWarn) {
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    rd::RibBuilder b(diag, "w.rib");
    rib::readString("WorldBegin\nPerspective 45\nWorldEnd\n", "w.rib", b, diag);
    EXPECT_NE(err.str().find("w.rib:2: warning: Perspective"), std::string::npos) << err.str();
}

// ColorSamples n: colours given with n values (Color, Opacity, "Cs" primitive variables,
// shader colour parameters) reach the renderer as RGB through the nRGB matrix. Here
// n = 4 with nRGB rows (1 0 0) (0 1 0) (0 0 1) (0.5 0.5 0.5).
TEST(GraphicsState, ColorSamplesConvertThroughNRGB) {
    const std::string cs =
        "ColorSamples [1 0 0  0 1 0  0 0 1  0.5 0.5 0.5] [1 0 0 0  0 1 0 0  0 0 1 0]\n"
        "Format 8 8 1\nPixelSamples 1 1\nProjection \"orthographic\"\nWorldBegin\n";
    // Color [0.2 0.1 0 0.4] -> (0.4, 0.3, 0.2)
    Rendered flat = renderRib(cs + "Color [0.2 0.1 0 0.4]\nSurface \"constant\"\n"
                              "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\nWorldEnd\n");
    EXPECT_NEAR(flat.at(4, 4).r, 0.4f, 1e-6f);
    EXPECT_NEAR(flat.at(4, 4).g, 0.3f, 1e-6f);
    EXPECT_NEAR(flat.at(4, 4).b, 0.2f, 1e-6f);
    // per-vertex "Cs" with 4 values a vertex, all (0 0 0 1) -> (0.5 0.5 0.5)
    Rendered varying = renderRib(cs + "Surface \"constant\"\n"
                                 "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5] \"Cs\" "
                                 "[0 0 0 1  0 0 0 1  0 0 0 1  0 0 0 1]\nWorldEnd\n");
    EXPECT_NEAR(varying.at(4, 4).g, 0.5f, 1e-6f);
    // a shader's colour parameter: matte's light, "lightcolor" [0 0 1 1], times Cs
    // [1 0 0 1] in the four channels: [0 0 0 1], (0.5, 0.5, 0.5); multiplied as RGB,
    // (1.5, 0.5, 0.5) times (0.5, 0.5, 1.5), it would be (0.75, 0.25, 0.75)
    Rendered lit = renderRib(cs + "LightSource \"ambientlight\" 1 \"lightcolor\" [0 0 1 1]\n"
                             "Color [1 0 0 1]\nSurface \"matte\" \"Ka\" 1 \"Kd\" 0\n"
                             "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\nWorldEnd\n");
    EXPECT_NEAR(lit.at(4, 4).r, 0.5f, 1e-6f);
    EXPECT_NEAR(lit.at(4, 4).g, 0.5f, 1e-6f);
    EXPECT_NEAR(lit.at(4, 4).b, 0.5f, 1e-6f);
    // More than 15 channels are converted to RGB as they are read, which is said once,
    // where ColorSamples is
    std::string nRGB, RGBn;
    for (int i = 0; i < 16 * 3; ++i) nRGB += i % 3 == 0 ? " 0.0625" : " 0", RGBn += " 1";
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    rd::RibBuilder b(diag, "c.rib");
    rib::readString("ColorSamples [" + nRGB + "] [" + RGBn + "]\nWorldBegin\nWorldEnd\n",
                    "c.rib", b, diag);
    EXPECT_NE(err.str().find("c.rib:1: warning: ColorSamples 16: more than 15 channels"),
              std::string::npos)
        << err.str();
}

// Exposure gain gamma: the resolved colour is (gain * colour)^(1 / gamma).
TEST(GraphicsState, ExposureScalesAndGammaCorrects) {
    auto centre = [](const std::string& exposure) {
        Rendered img = renderRib(std::string(kCamera) + exposure +
                                 "WorldBegin\nColor [0.25 0.25 0.25]\nSurface \"constant\"\n"
                                 "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\nWorldEnd\n");
        return img.at(24, 8);
    };
    EXPECT_NEAR(centre("").r, 0.25f, 1e-6f);
    EXPECT_NEAR(centre("Exposure 2 1\n").r, 0.5f, 1e-6f);
    EXPECT_NEAR(centre("Exposure 2 2\n").r, std::sqrt(0.5f), 1e-6f);
    EXPECT_EQ(centre("Exposure 2 2\n").a, 1.0f);
}

// An area light emits from its geometry: arealight on a disk of radius 0.5 at z = 3
// facing a wall at z = 5 (h = 2) lights a wall point p (matte, Kd 1) with the mean over
// the disk's points q of intensity cos / d^2 = intensity h / |p - q|^3 (quadrature here),
// one random point a sample. An occluder at z = 4 (half size 0.25) shadows the wall softly:
// for x in (0.5, 1) part of the disk is hidden (a penumbra), beyond x = 1 none of it.
TEST(GraphicsState, AreaLightGeometryEmitsWithSoftShadows) {
    auto scene = [](const std::string& occluder) {
        return renderRib("Format 32 32 1\nPixelSamples 16 16\nProjection \"orthographic\"\n"
                         "ScreenWindow -2 2 -2 2\nWorldBegin\n"
                         "AttributeBegin\nTranslate 0 0 3\n"
                         "AreaLightSource \"arealight\" 1 \"intensity\" 4\n"
                         "Surface \"constant\"\nDisk 0 0.5 360\nAttributeEnd\n" + occluder +
                         "Surface \"matte\"\nPolygon \"P\" [-4 -4 5  4 -4 5  4 4 5  -4 4 5]\n"
                         "WorldEnd\n");
    };
    auto irradiance = [](double x, double y) {  // 4 h / d^3 averaged over the disk
        const double h = 2, R = 0.5;
        double sum = 0, area = 0;
        for (int i = 0; i < 200; ++i)
            for (int j = 0; j < 200; ++j) {
                double r = R * (i + 0.5) / 200, a = 2 * 3.14159265358979 * (j + 0.5) / 200;
                double dx = x - r * std::cos(a), dy = y - r * std::sin(a);
                double d = std::sqrt(dx * dx + dy * dy + h * h);
                sum += r * 4 * h / (d * d * d);
                area += r;
            }
        return sum / area;
    };
    Rendered lit = scene("");
    // pixel column c is at x = -2 + (c + 0.5) / 8; rows 15, 16 at y = +-1/16
    for (int c : {24, 27}) {
        const double x = -2 + (c + 0.5) / 8;
        const double expect = 0.5 * (irradiance(x, 1.0 / 16) + irradiance(x, -1.0 / 16));
        const double measured = lit.mean(0, c, 15, c + 1, 17);
        EXPECT_NEAR(measured, expect, 0.03 * expect) << "x = " << x;
        std::printf("NUMERICS case=area_light_disk_x%.2f tolerance=0.03 measured=%.3g\n", x,
                    std::fabs(measured / expect - 1));
    }
    Rendered shadowed = scene("AttributeBegin\nSurface \"matte\"\nPolygon \"P\" "
                              "[-0.25 -0.25 4  0.25 -0.25 4  0.25 0.25 4  -0.25 0.25 4]\n"
                              "AttributeEnd\n");
    const double penumbra = shadowed.mean(0, 22, 15, 23, 17) / lit.mean(0, 22, 15, 23, 17);
    EXPECT_GT(penumbra, 0.1) << "x = 0.81: partly lit";
    EXPECT_LT(penumbra, 0.95) << "x = 0.81: partly shadowed";
    EXPECT_NEAR(shadowed.mean(0, 27, 15, 28, 17), lit.mean(0, 27, 15, 28, 17), 1e-6)
        << "x = 1.44: the whole disk is seen";
}

// Level of detail (RI 3.2 4.1.5): two representations of one square, red for a detail
// (the Detail bound's area in raster pixels) below 150 and blue above (DetailRange [0 0
// 100 200] and [100 200 1e38 1e38], each transition cut at its middle). The square's
// bound covers 8 x 8 = 64 pixels at Format 16 16 (red alone) and 32 x 32 = 1024 at 64 64
// (blue alone); RelativeDetail 0.1 brings the large image back to red. Red is nearer the
// camera, so a blue area shows that red was left out. Before, Detail and DetailRange were
// ignored and both were drawn (red everywhere).
TEST(GraphicsState, DetailRangePicksOneRepresentation) {
    auto render = [](int res, const std::string& options) {
        const std::string r = std::to_string(res);
        return renderRib(
            options + "Format " + r + " " + r +
            " 1\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n"
            "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n"
            "AttributeBegin\nDetail [-1 1 -1 1 0 0]\n"
            "AttributeBegin\nDetailRange [0 0 100 200]\nColor [1 0 0]\n"
            "Polygon \"P\" [-1 -1 -0.1  1 -1 -0.1  1 1 -0.1  -1 1 -0.1]\n"
            "AttributeEnd\n"
            "AttributeBegin\nDetailRange [100 200 1e38 1e38]\nColor [0 0 1]\n"
            "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\nAttributeEnd\n"
            "AttributeEnd\nWorldEnd\n");
    };
    Rendered small = render(16, ""), large = render(64, ""),
             relative = render(64, "RelativeDetail 0.1\n");
    EXPECT_NEAR(small.mean(0, 6, 6, 10, 10), 1.0, 1e-6);
    EXPECT_NEAR(small.mean(2, 6, 6, 10, 10), 0.0, 1e-6);
    EXPECT_NEAR(large.mean(0, 24, 24, 40, 40), 0.0, 1e-6);
    EXPECT_NEAR(large.mean(2, 24, 24, 40, 40), 1.0, 1e-6);
    EXPECT_NEAR(relative.mean(0, 24, 24, 40, 40), 1.0, 1e-6);
}

// Attribute "visibility" "int diffuse" and "int specular" apart (PRMan): the rays of
// occlusion() and indirectdiffuse() see what is visible to diffuse rays, trace()'s what
// is visible to specular ones, "int trace" sets both. A patch under a disk that covers
// 0.2 of its cosine-weighted hemisphere (as in
// Shading.OcclusionAndIndirectDiffuseAreTheirHemisphereFractions), its shader 1 -
// occlusion(), indirectdiffuse() or trace() straight up, the disk's constant red 1.
// Before, "diffuse" and "specular" did something only when both were given, together.
TEST(GraphicsState, DiffuseAndSpecularVisibilityApart) {
    const std::string dir = rd::test::scratchDir("raydrive_visibility_kinds");
    std::ofstream(dir + "/rays.sl")
        << "surface rays(float mode = 0) {\n"
           "  normal Nz = normal(0, 0, 1);\n"
           "  if (mode == 0) Ci = 1 - occlusion(P, Nz, 16);\n"
           "  else if (mode == 1) Ci = indirectdiffuse(P, Nz, 16);\n"
           "  else Ci = trace(P, vector(0, 0, 1));\n"
           "  Oi = 1;\n}\n";
    struct Case {
        const char* visibility;
        double open, indirect, traced;  // 1 - occlusion, indirectdiffuse, trace
    };
    for (const Case c :
         {Case{"", 0.8, 0.2, 1.0}, Case{"\"int diffuse\" [0]", 1.0, 0.0, 1.0},
          Case{"\"int specular\" [0]", 0.8, 0.2, 0.0},
          Case{"\"int trace\" [0]", 1.0, 0.0, 0.0}}) {
        const std::string above = (*c.visibility ? "Attribute \"visibility\" " +
                                                       std::string(c.visibility) + "\n"
                                                 : std::string()) +
                                  "Translate 0 0 7\nDisk 0 1 360\n";
        for (int mode = 0; mode < 3; ++mode) {
            const Rendered r = renderRib(rd::test::patchUnder(
                dir, 8, "\"rays\" \"float mode\" [" + std::to_string(mode) + "]", above));
            const double want = mode == 0 ? c.open : mode == 1 ? c.indirect : c.traced;
            EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), want, mode == 2 ? 1e-5 : 0.02)
                << c.visibility << " mode " << mode;
        }
    }
}
