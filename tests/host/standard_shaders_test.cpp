// standard_shaders_test.cpp: the RI standard shaders not covered elsewhere, each in a
// small reference scene against its closed form: metal's highlight, paintedplastic
// without a texture equal to plastic, shinymetal without an environment equal to metal,
// and the depthcue atmosphere with depth() normalised between the clipping planes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "render_harness.h"
#include "rsl2cl/src/emit_cl.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// A square facing an orthographic eye, lit head-on by a distant light of intensity 1.
Rendered square(const std::string& surface, const std::string& options = "") {
    return renderRib("Format 16 16 1\nPixelSamples 1 1\nProjection \"orthographic\"\n" + options +
                     "Translate 0 0 5\nWorldBegin\n"
                     "LightSource \"distantlight\" 1 \"from\" [0 0 -5] \"to\" [0 0 0]\n"
                     "Color [0.5 0.25 1]\n" + surface +
                     "\nPolygon \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]\nWorldEnd\n");
}

}  // namespace

// metal: Cs (Ka ambient + Ks specular); head-on, H = N, specular = Cl = 1 -> Ci = Cs.
TEST(StandardShaders, MetalHighlightHeadOn) {
    Rendered img = square("Surface \"metal\"");
    EXPECT_NEAR(img.at(8, 8).r, 0.5f, 1e-4f);
    EXPECT_NEAR(img.at(8, 8).g, 0.25f, 1e-4f);
    EXPECT_NEAR(img.at(8, 8).b, 1.0f, 1e-4f);
}

// Without a texture paintedplastic is plastic; without an environment shinymetal is metal.
TEST(StandardShaders, TexturelessVariantsEqualTheirBases) {
    EXPECT_NEAR(square("Surface \"paintedplastic\"").at(8, 8).r,
                square("Surface \"plastic\"").at(8, 8).r, 1e-6f);
    EXPECT_NEAR(square("Surface \"shinymetal\"").at(8, 8).g,
                square("Surface \"metal\"").at(8, 8).g, 1e-6f);
}

// depthcue: depth(P) is 0 at the near and 1 at the far clipping plane; the square at
// camera z = 5 between Clipping 1 and 9 has depth 0.5, so Ci is half way to background.
TEST(StandardShaders, DepthcueAtmosphereUsesNormalisedDepth) {
    EXPECT_EQ(rsl::stringId("Clipping"), 16130671);  // RSL_ID_CLIPPING in rsl_stdlib.clh
    Rendered img = square("Surface \"constant\"\nAtmosphere \"depthcue\" \"background\" [0 0 0]",
                          "Clipping 1 9\n");
    EXPECT_NEAR(img.at(8, 8).r, 0.25f, 1e-4f);
    EXPECT_NEAR(img.at(8, 8).b, 0.5f, 1e-4f);
}

// Imager "background": uncovered pixels take bgcolor, covered ones keep their colour,
// the image becomes opaque. The square covers x, y in [-2, 2] of the [-4, 4] view.
TEST(StandardShaders, BackgroundImagerFillsUncoveredPixels) {
    Rendered img = renderRib("Format 16 16 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                             "ScreenWindow -4 4 -4 4\n"
                             "Imager \"background\" \"color bgcolor\" [0.25 0.5 0.75]\n"
                             "Translate 0 0 5\nWorldBegin\nColor [1 0 0]\nSurface \"constant\"\n"
                             "Polygon \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]\nWorldEnd\n");
    EXPECT_NEAR(img.at(0, 0).r, 0.25f, 1e-6f);
    EXPECT_NEAR(img.at(0, 0).g, 0.5f, 1e-6f);
    EXPECT_NEAR(img.at(0, 0).b, 0.75f, 1e-6f);
    EXPECT_NEAR(img.at(0, 0).a, 1.0f, 1e-6f);
    EXPECT_NEAR(img.at(8, 8).r, 1.0f, 1e-6f);
    EXPECT_NEAR(img.at(8, 8).g, 0.0f, 1e-6f);
    EXPECT_NEAR(img.at(8, 8).a, 1.0f, 1e-6f);
}

// A user's imager sees the raster position in P and sets alpha; Exposure comes after
// the imager (RI order), so gain 2 doubles what the imager wrote.
TEST(StandardShaders, UserImagerSeesRasterPositionThenExposure) {
    std::string dir = rd::test::scratchDir("raydrive_imagers");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/ramp.sl") << "imager ramp(float scale = 1) {\n"
                                       "    Ci = color(xcomp(P), ycomp(P), alpha) * scale;\n"
                                       "    alpha = 0.5;\n}\n";
    Rendered img = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n"
                             "Format 8 4 1\nPixelSamples 1 1\nExposure 2 1\n"
                             "Imager \"ramp\" \"scale\" 0.5\nWorldBegin\nWorldEnd\n");
    EXPECT_NEAR(img.at(3, 2).r, 3.5f, 1e-6f);  // (x + 0.5) * 0.5 * gain 2
    EXPECT_NEAR(img.at(3, 2).g, 2.5f, 1e-6f);
    EXPECT_NEAR(img.at(3, 2).b, 0.0f, 1e-6f);  // nothing covered: alpha was 0
    EXPECT_NEAR(img.at(3, 2).a, 0.5f, 1e-6f);
}

// An imager that is not found is reported, and the image is left as rendered.
TEST(StandardShaders, MissingImagerIsLeftOut) {
    Rendered img = renderRib("Format 4 4 1\nPixelSamples 1 1\nImager \"no_such_imager\"\n"
                             "WorldBegin\nWorldEnd\n");
    EXPECT_EQ(img.at(1, 1).a, 0.0f);
}

namespace {

// A wall at z = 5 seen orthographically over [-4, 4]^2 (32 pixels, 0.25 each), lit by
// `light`; an occluder at z = 4 over x in [0.5, 1.5], y in [-0.5, 0.5] (seen too).
Rendered litWall(const std::string& light) {
    return renderRib("Format 32 32 1\nPixelSamples 4 4\nProjection \"orthographic\"\n"
                     "ScreenWindow -4 4 -4 4\nWorldBegin\n" + light + "\nSurface \"matte\"\n"
                     "Polygon \"P\" [-8 -8 5  8 -8 5  8 8 5  -8 8 5]\n"
                     "Polygon \"P\" [0.5 -0.5 4  1.5 -0.5 4  1.5 0.5 4  0.5 0.5 4]\nWorldEnd\n");
}

// matte under a point light of intensity I at (0, 0, 3): I / d^2 * cos at a wall pixel.
double pointLit(int px, int py, double intensity) {
    double x = -4 + (px + 0.5) * 0.25, y = 4 - (py + 0.5) * 0.25, dz = 2;
    double d2 = x * x + y * y + dz * dz;
    return intensity / d2 * dz / std::sqrt(d2);
}

}  // namespace

// shadowpoint "raytrace": I / d^2 falloff on the wall; the occluder's shadow (x in
// [1, 3] on the wall, twice its size from the light at z = 3) is black.
TEST(StandardShaders, ShadowpointFalloffAndShadow) {
    Rendered img = litWall("LightSource \"shadowpoint\" 1 \"intensity\" 4 \"from\" [0 0 3] "
                           "\"shadowname\" \"raytrace\"");
    EXPECT_NEAR(img.at(6, 16).r, pointLit(6, 16, 4), 5e-3);
    EXPECT_NEAR(img.at(16, 8).r, pointLit(16, 8, 4), 5e-3);
    EXPECT_NEAR(img.at(25, 16).r, 0.0, 1e-6) << "in the occluder's shadow";
}

// shadowdistant "raytrace" along +z: the wall is lit at 1 (N.L = 1) except behind the
// occluder, whose shadow is its own size: x in [0.5, 1.5] hides under the occluder
// itself, so the occluder's face (also lit at 1) fills it; the wall beside it is lit.
TEST(StandardShaders, ShadowdistantLightsAndShadows) {
    Rendered img = renderRib("Format 32 32 1\nPixelSamples 1 1\nProjection \"perspective\" "
                             "\"fov\" 60\nWorldBegin\n"
                             "LightSource \"shadowdistant\" 1 \"from\" [0 0 0] \"to\" [1 0 1] "
                             "\"shadowname\" \"raytrace\"\nSurface \"matte\"\n"
                             "Polygon \"P\" [-8 -8 5  8 -8 5  8 8 5  -8 8 5]\n"
                             "Polygon \"P\" [-0.5 -0.5 4  0.5 -0.5 4  0.5 0.5 4  -0.5 0.5 4]\n"
                             "WorldEnd\n");
    // light along (1, 0, 1)/sqrt2: N.L = 0.7071 on both faces; the occluder's shadow
    // falls one unit to +x of it on the wall (x in [0.5, 1.5] at z = 5)
    const double lit = std::sqrt(0.5);
    EXPECT_NEAR(img.at(8, 16).r, lit, 1e-4) << "wall, lit";
    EXPECT_NEAR(img.at(16, 16).r, lit, 1e-4) << "occluder, lit";
    // x = 1 at z = 5 is at the raster column 16 + 1/(5 tan 30deg) * 16 = 21.5
    EXPECT_NEAR(img.at(21, 15).r, 0.0, 1e-6) << "wall, in the shadow";
}

// arealight through AreaLightSource: its light shader at the light's own place (shader
// space origin, +z normal; the geometry is not yet the emitter) lights like a point
// light into the hemisphere it faces.
TEST(StandardShaders, ArealightLightsItsHemisphere) {
    Rendered img = litWall("AttributeBegin\nTranslate 0 0 3\nAreaLightSource \"arealight\" 1 "
                           "\"intensity\" 4\nAttributeEnd");
    EXPECT_NEAR(img.at(6, 16).r, pointLit(6, 16, 4), 5e-3);
    Rendered away = litWall("AttributeBegin\nTranslate 0 0 3\nRotate 180 1 0 0\n"
                            "AreaLightSource \"arealight\" 1 \"intensity\" 4\nAttributeEnd");
    EXPECT_NEAR(away.at(6, 16).r, 0.0, 1e-6) << "facing away from the wall";
}

// bumpy without a texture map bumps by texture() = 0 (textures are issue 9): the image
// is the undisplaced one, through the whole displacement path.
TEST(StandardShaders, BumpyWithoutATextureIsFlat) {
    Rendered flat = litWall("LightSource \"distantlight\" 1");
    Rendered bumpy = litWall("LightSource \"distantlight\" 1\nDisplacement \"bumpy\"");
    EXPECT_TRUE(bumpy.stats.features.displacement);
    for (int x : {4, 12, 20, 28}) EXPECT_NEAR(bumpy.at(x, 10).r, flat.at(x, 10).r, 1e-6);
}
