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
    // not affine in Cl (a test on a light's luminance, channels swapped): shaded light
    // by light (a warning), each light's part scaled by its shadow
    {"toon",
     "surface toon() {\n  normal Nf = faceforward(normalize(N), I);\n"
     "  color d = diffuse(Nf);\n  Ci = Cs * (0.3 * comp(d, 0) + 0.6 * comp(d, 1) + 0.1 * "
     "comp(d, 2) > 0.5 ? 1 : 0.25);\n}\n"},
    {"swap",
     "surface swap() {\n  color c = 0;\n  illuminance(P) { c += Cl; }\n"
     "  Ci = color(comp(c, 1), comp(c, 2), comp(c, 0));\n}\n"},
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

// Shaders not affine in Cl (Advanced RenderMan's toon shaders, a light's luminance or one
// channel of it), refused before session 42 (a compile error, and defaultsurface): each
// light is evaluated on its own and its shadow ray scales its part, exact for one light.
// A distant light straight on, a square the camera does not see shading the left half:
// the toon shader's 1 lit and 0.25 (its unlit base) in the shadow; channels swapped under
// a light of colour (1, 0.5, 0.25): (0.5, 0.25, 1) lit, 0 in the shadow.
TEST(ClassicShaders, ShadersNotAffineInClAreShadedLightByLight) {
    const std::string dir = rd::test::shaderFolder("classic_shaders", kShaders);
    const std::string shade =
        "AttributeBegin\nAttribute \"visibility\" \"int camera\" [0]\n"
        "Polygon \"P\" [-3 -3 -1  0 -3 -1  0 3 -1  -3 3 -1]\nAttributeEnd\n";
    Rendered toon = renderRib(plane(
        dir, "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n" + shade,
        "toon"));
    EXPECT_NEAR(toon.mean(0, 0, 0, 7, 16), 0.25, 1e-5) << "in the shadow";
    EXPECT_NEAR(toon.mean(0, 9, 0, 16, 16), 1.0, 1e-5) << "lit";
    Rendered swap =
        renderRib(plane(dir,
                        "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" "
                        "[0 0 1] \"lightcolor\" [1 0.5 0.25]\n" +
                            shade,
                        "swap"));
    EXPECT_NEAR(swap.mean(0, 9, 0, 16, 16), 0.5, 1e-5);
    EXPECT_NEAR(swap.mean(1, 9, 0, 16, 16), 0.25, 1e-5);
    EXPECT_NEAR(swap.mean(2, 9, 0, 16, 16), 1.0, 1e-5);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(swap.mean(c, 0, 0, 7, 16), 0.0, 1e-6);
}
