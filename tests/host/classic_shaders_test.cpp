// classic_shaders_test.cpp: shaders written the way the RenderMan Companion and BMRT's
// examples write them, which RayDrive refused before session 36 (a compile error, and the
// surface fell back to defaultsurface): Ci used as a temporary for the base colour, N and
// P set in a surface shader's body, L set in a light's illuminate, setzcomp() of a vector,
// illuminance in a volume shader.
#include <gtest/gtest.h>

#include <cmath>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const char* const kShaders[][2] = {
    // txtplastic's way: Ci holds the base colour, then is lit
    {"citemp",
     "surface citemp(float Kd = 0.5;) {\n"
     "  normal Nf = faceforward(normalize(N), I);\n"
     "  Ci = Cs * 0.5;\n"
     "  Ci = Os * Ci * Kd * diffuse(Nf);\n"
     "  Ci *= 2;\n}\n"},
    // eroded's way: the surface bends its own normal and moves its own point
    {"bend",
     "surface bend() {\n"
     "  point P0 = P;\n"
     "  N = N + normal(1, 0, 0);\n"
     "  P += vector(0.5, 0, 0);\n"
     "  vector v = vector(1, 2, 3);\n"
     "  setzcomp(v, 0.25);\n"
     "  Ci = color(xcomp(normalize(N)), xcomp(P - P0), zcomp(v));\n}\n"},
    // slideprojector's way: the light sets L itself (to what illuminate gives)
    {"aiml",
     "light aiml(float intensity = 1; point from = point \"shader\" (0, 0, 0);) {\n"
     "  illuminate(from) {\n    L = Ps - from;\n    Cl = intensity / (L . L);\n  }\n}\n"},
    // a volume shader that scatters the lights it sees (ARMan's smoke, BMRT's noisysmoke)
    {"glowfog",
     "volume glowfog(float k = 0.5) {\n  color sc = 0;\n"
     "  illuminance(P) { sc += Cl; }\n  Ci = Ci + k * sc;\n}\n"},
    {"aim",
     "light aim(float intensity = 1; point from = point \"shader\" (0, 0, 0);) {\n"
     "  illuminate(from) {\n    Cl = intensity / (L . L);\n  }\n}\n"},
};

// A plane facing the orthographic camera, 16 x 16 pixels over [-1, 1]^2.
std::string plane(const std::string& dir, const std::string& lights,
                  const std::string& surface) {
    return "Option \"searchpath\" \"shader\" [\"" + dir +
           ":&\"]\nFormat 16 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
           "Translate 0 0 5\nWorldBegin\n" +
           lights + "Surface \"" + surface +
           "\"\nPolygon \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]\nWorldEnd\n";
}

}  // namespace

// Ci = Cs * 0.5, then Ci = Os * Ci * Kd * diffuse(Nf), then doubled: under a distant light
// straight on, 0.5. The affine check follows the code (rsl2cl affine.cpp).
TEST(ClassicShaders, CiAsATemporary) {
    const std::string dir = rd::test::shaderFolder("classic_shaders", kShaders);
    Rendered r = renderRib(plane(
        dir, "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n", "citemp"));
    EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), 0.5, 1e-5);
    EXPECT_NEAR(r.mean(3, 0, 0, 16, 16), 1.0, 1e-6);
}

// N + (1, 0, 0) for a plane facing the camera ((0, 0, -1) in camera space): x of the unit
// normal 1 / sqrt(2); P moved by 0.5 in x; setzcomp() of a vector.
TEST(ClassicShaders, SurfaceSetsNAndP) {
    const std::string dir = rd::test::shaderFolder("classic_shaders", kShaders);
    Rendered r = renderRib(plane(dir, "", "bend"));
    EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), std::sqrt(0.5), 1e-5);
    EXPECT_NEAR(r.mean(1, 0, 0, 16, 16), 0.5, 1e-5);
    EXPECT_NEAR(r.mean(2, 0, 0, 16, 16), 0.25, 1e-6);
}

// A light that sets L in its illuminate (as illuminate does) lights the plane as the same
// light without that line, pixel for pixel; and a matte plane 5 units from it at its
// middle takes intensity 25 / 25 = 1.
TEST(ClassicShaders, LightSetsL) {
    const std::string dir = rd::test::shaderFolder("classic_shaders", kShaders);
    const std::string light = "\" 1 \"intensity\" 25 \"from\" [0 0 -5]\n";
    Rendered a = renderRib(plane(dir, "LightSource \"aiml" + light, "matte"));
    Rendered b = renderRib(plane(dir, "LightSource \"aim" + light, "matte"));
    EXPECT_NEAR(a.mean(0, 7, 7, 9, 9), 1.0, 0.02);
    double worst = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            worst = std::max(worst, double(std::fabs(a.at(x, y).r - b.at(x, y).r)));
    EXPECT_LT(worst, 1e-6);
}

// An Atmosphere whose illuminance loop adds k times every light's Cl (each light's shadow
// ray from P reaching it: volume_shadows_test.cpp) to what reaches the eye: over a black
// constant plane under two distant lights of intensity 1 and 0.5, 0.5 x 1.5 = 0.75.
// Before, Cl was an unknown identifier in a volume shader and the atmosphere was left out
// (0).
TEST(ClassicShaders, VolumeShaderSeesTheLights) {
    const std::string dir = rd::test::shaderFolder("classic_shaders", kShaders);
    Rendered r = renderRib(plane(dir,
                                 "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n"
                                 "LightSource \"distantlight\" 2 \"intensity\" 0.5\n"
                                 "Atmosphere \"glowfog\"\nColor [0 0 0]\n",
                                 "constant"));
    EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), 0.75, 1e-5);
    EXPECT_TRUE(r.stats.features.atmosphere);
}

// The RenderMan Companion's listings declare a light before WorldBegin (and `Format 256 192
// -1`, -1 the default pixel aspect): the light is placed in camera space. A distant light
// toward camera +z, with the camera turned 30 degrees about y from a matte plane's normal,
// meets the plane at 30 degrees: cos 30. (In world space it would meet it head on: 1.)
// Before, both requests were errors and the light was left out.
TEST(ClassicShaders, LightBeforeWorldBeginIsInCameraSpace) {
    Rendered r = renderRib(
        "Format 16 16 -1\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n"
        "PixelSamples 2 2\nProjection \"orthographic\"\nRotate 30 0 1 0\nTranslate 0 0 5\n"
        "WorldBegin\nSurface \"matte\"\nPolygon \"P\" [-9 -9 0  9 -9 0  9 9 0  -9 9 0]\n"
        "WorldEnd\n");
    EXPECT_EQ(r.width, 16);
    EXPECT_NEAR(r.mean(0, 0, 0, 16, 16), std::cos(30.0 * M_PI / 180.0), 1e-4);
}
