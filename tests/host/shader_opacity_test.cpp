// shader_opacity_test.cpp: what a surface shader's Oi lets through: camera rays where it
// sets Oi below Os, and shadows through surfaces whose shader says what they let through
// (PRMan's "string transmission" "shader", "shade" "transmissionhitmode" "shader", BMRT's
// "casts_shadows" "shade"): the shadow ray goes on in the pool from such a surface, its
// shader runs for Oi alone, and the rest of the way is a shadow ray again (ray.h
// RT_ALIVE_SHADOW).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "film/film.h"
#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// Oi by where the point lies: opaque left of x = edge (world space), (0.25, 0.5, 0.75)
// to the right. Never seen by the camera.
const char* const kShaders[][2] = {
    {"halfop",
     "surface halfop(float edge = 0) {\n"
     "  point Pw = transform(\"world\", P);\n"
     "  Oi = xcomp(Pw) < edge ? color(1) : color(0.25, 0.5, 0.75);\n"
     "  Ci = 0;\n}\n"},
    {"shy",
     "surface shy() {\n  string kind = \"\";\n  rayinfo(\"type\", kind);\n"
     "  Oi = isshadowray() > 0 ? 0.5 : 1;\n  if (kind == \"transmission\") Oi *= 0.5;\n"
     "  Ci = 0.3 * Oi;\n}\n"},
    {"aovlit",
     "surface aovlit(output varying color lit = 0;) {\n"
     "  normal Nf = faceforward(normalize(N), I);\n"
     "  illuminance(P, Nf, PI / 2) {\n"
     "    lit += Cl * (Nf . normalize(L));\n  }\n"
     "  Ci = lit;\n  Oi = 1;\n}\n"},
    {"hole", "surface hole(float o = 0.25) {\n  Oi = o;\n  Ci = Oi * color(1, 0, 0);\n}\n"},
};

// 48 x 16 pixels over x in [-3, 3]: column c is x = (c - 24) / 8.
const char* kCamera =
    "Format 48 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\nScreenWindow -3 3 -1 1\n"
    "Translate 0 0 5\n";

// A square of side 1.2 at (x, 0, z), facing the camera, which does not see it.
std::string square(double x, double z, const std::string& attributes) {
    std::ostringstream s;
    s << "AttributeBegin\nAttribute \"visibility\" \"int camera\" [0]\n"
      << attributes << "\nPolygon \"P\" [" << x - 0.6 << " -0.6 " << z << "  " << x + 0.6
      << " -0.6 " << z << "  " << x + 0.6 << " 0.6 " << z << "  " << x - 0.6 << " 0.6 "
      << z << "]\nAttributeEnd\n";
    return s.str();
}

// The scene of every test here: the camera, the shaders' folder, a distant light of
// intensity 1 straight on (and `lights`), and a floor at z = 0 of `floor`.
std::string floorScene(const std::string& dir, const std::string& floor = "matte",
                       const std::string& lights = "") {
    return std::string(kCamera) + "Option \"searchpath\" \"shader\" [\"" + dir +
           ":&\"]\nWorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n" +
           lights + "Surface \"" + floor + "\"\nPolygon \"P\" [-9 -9 0  9 -9 0  9 9 0  -9 9 0]\n";
}

}  // namespace

// A white matte floor under two distant lights straight on, of intensity 1 and 0.5 (lit,
// it is 1.5; the second light's shadow rays are handed over from its slots); squares between
// at x = -2.25, -0.75, 0.75 and 2.25. The first's shader is opaque over its left half:
// under it the floor is black, under the right half it keeps 1 - Oi. The second is three
// layers: a shader's square, one of constant Opacity 0.5, the shader's again; the third
// runs the same shader but takes its Os (transmission "Os"); the fourth asks for its
// shader by transmissionhitmode.
TEST(ShaderOpacity, ShadowsTakeTheShadersOi) {
    const std::string dir = rd::test::shaderFolder("shader_shadows", kShaders);
    const std::string shader = "Attribute \"visibility\" \"string transmission\" [\"shader\"]\n";
    const std::string world =
        floorScene(dir, "matte",
                   "LightSource \"distantlight\" 2 \"intensity\" 0.5 \"from\" [0 0 0] "
                   "\"to\" [0 0 1]\n") +
        square(-2.25, -1, shader + "Surface \"halfop\" \"edge\" -2.25") +
        square(-0.75, -1, shader + "Surface \"halfop\" \"edge\" -9") +
        square(-0.75, -2, "Opacity [0.5 0.5 0.5]") +
        square(-0.75, -3, shader + "Surface \"halfop\" \"edge\" -9") +
        square(0.75, -1,
               "Attribute \"visibility\" \"string transmission\" [\"Os\"]\n"
               "Opacity [0.5 0.5 0.5]\nSurface \"halfop\" \"edge\" -9") +
        square(2.25, -1,
               "Attribute \"shade\" \"string transmissionhitmode\" [\"shader\"]\n"
               "Attribute \"visibility\" \"int transmission\" [1]\n"
               "Surface \"halfop\" \"edge\" -9") +
        "WorldEnd\n";
    Rendered r = renderRib(world);
    ASSERT_EQ(r.width, 48);
    auto at = [&](int channel, int column) { return r.mean(channel, column, 6, column + 2, 10); };
    const double through[3] = {1.5 * 0.75, 1.5 * 0.5, 1.5 * 0.25};
    for (int c = 0; c < 3; ++c) {
        SCOPED_TRACE(c);
        EXPECT_NEAR(at(c, 3), 0.0, 1e-6);                  // the opaque half
        EXPECT_NEAR(at(c, 7), through[c], 1e-5);           // 1 - Oi
        EXPECT_NEAR(at(c, 17), through[c] * through[c] / 1.5 * 0.5, 1e-5);  // three layers
        EXPECT_NEAR(at(c, 29), 1.5 * 0.5, 1e-5);           // Os, not the shader's
        EXPECT_NEAR(at(c, 41), through[c], 1e-5);          // transmissionhitmode
        EXPECT_NEAR(at(c, 23), 1.5, 1e-5);                 // between the squares
    }
    EXPECT_TRUE(r.stats.features.shaderShadows);
    EXPECT_TRUE(r.stats.features.transparentShadows);

    // The same image whatever the pool's capacity (64 rays: the handed-over rays wait for
    // room behind the others).
    rd::RenderSettings small;
    small.poolCapacity = 64;
    Rendered s = renderRib(world, small);
    double worst = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 48; ++x)
            worst = std::max(worst, double(std::fabs(s.at(x, y).r - r.at(x, y).r) +
                                           std::fabs(s.at(x, y).b - r.at(x, y).b)));
    EXPECT_LT(worst, 1e-6);

    // Through treelets, whose shadow walk hands the rays over as intersect_shadow does
    // (session 36 gave way to the resident traversal): the same image, also with a pool of
    // 64 rays. (80 more squares of the shader, out of sight above y = 3, for a tree that
    // a budget of 1024 bytes cuts into several treelets.)
    std::string more;
    for (int k = 0; k < 80; ++k)
        more += "AttributeBegin\nTranslate " + std::to_string(-4 + (k % 10)) + " " +
                std::to_string(3 + k / 10) + " 0\nScale 0.3 0.3 1\n" +
                square(0, 1, "Surface \"halfop\" \"edge\" 0\n"
                             "Attribute \"visibility\" \"string transmission\" [\"shader\"]") +
                "AttributeEnd\n";
    const std::string busy = world.substr(0, world.rfind("WorldEnd")) + more + "WorldEnd\n";
    const Rendered resident = renderRib(busy);
    for (size_t pool : {size_t(0), size_t(64)}) {
        rd::RenderSettings treelets;
        treelets.treeletBytes = 1024;
        treelets.poolCapacity = pool;
        Rendered t = renderRib(busy, treelets);
        EXPECT_TRUE(t.stats.features.treelets) << t.stats.treelets.why;
        EXPECT_GT(t.stats.treelets.treelets, 3u);
        double off = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 48; ++x)
                for (int c = 0; c < 3; ++c)
                    off = std::max(off, double(std::fabs((&t.at(x, y).r)[c] -
                                                         (&resident.at(x, y).r)[c])));
        EXPECT_LT(off, 1e-6) << "pool " << pool;
        std::printf("pool %zu: %zu treelets, largest difference %.2g\n", pool,
                    t.stats.treelets.treelets, off);
    }
    EXPECT_NEAR(resident.mean(0, 7, 6, 9, 10), through[0], 1e-5);
}

// Without a shader's transmission asked for, the same scene's shadows are the squares' Os
// (1, the default): the feature is not built, and no shadow ray goes to the pool.
TEST(ShaderOpacity, OnlyAskedForIsTheShaderRun) {
    const std::string dir = rd::test::shaderFolder("shader_shadows", kShaders);
    Rendered r = renderRib(floorScene(dir) + square(0, -1, "Surface \"halfop\" \"edge\" -9") +
                           "WorldEnd\n");
    EXPECT_FALSE(r.stats.features.shaderShadows);
    EXPECT_NEAR(r.mean(0, 22, 6, 26, 10), 0.0, 1e-6);
    EXPECT_NEAR(r.mean(0, 2, 6, 6, 10), 1.0, 1e-5);
}

// A shader that sets Oi below Os lets camera rays through though every Os is 1 (a leaf
// cut out by its alpha): red at Oi 0.25 over a green plane is (0.25, 0.75, 0), alpha 1.
// `constant` (Oi = Os) builds no transparency and hides the plane.
TEST(ShaderOpacity, CameraRaysGoThroughTheShadersOi) {
    const std::string dir = rd::test::shaderFolder("shader_opacity", kShaders);
    auto scene = [&](const std::string& front) {
        return std::string(kCamera) + "Option \"searchpath\" \"shader\" [\"" + dir +
               ":&\"]\nWorldBegin\nSurface \"constant\"\nColor [0 1 0]\n"
               "Polygon \"P\" [-9 -9 2  9 -9 2  9 9 2  -9 9 2]\nColor [1 0 0]\n" +
               front + "\nPolygon \"P\" [-9 -9 0  0 -9 0  0 9 0  -9 9 0]\nWorldEnd\n";
    };
    Rendered r = renderRib(scene("Surface \"hole\""));
    EXPECT_TRUE(r.stats.features.transparency);
    EXPECT_NEAR(r.mean(0, 0, 0, 24, 16), 0.25, 1e-6);
    EXPECT_NEAR(r.mean(1, 0, 0, 24, 16), 0.75, 1e-6);
    EXPECT_NEAR(r.mean(3, 0, 0, 24, 16), 1.0, 1e-6);
    EXPECT_NEAR(r.mean(1, 24, 0, 48, 16), 1.0, 1e-6);
    Rendered c = renderRib(scene("Surface \"constant\""));
    EXPECT_FALSE(c.stats.features.transparency);
    EXPECT_NEAR(c.mean(0, 0, 0, 24, 16), 1.0, 1e-6);
    EXPECT_NEAR(c.mean(1, 0, 0, 24, 16), 0.0, 1e-6);
}

// The same on exact quadrics and instances: a sphere (two surfaces on the way, (1 - Oi)^2)
// at x = -1.5 and an ObjectInstance of a square at x = 1.5, both of "shader" transmission.
TEST(ShaderOpacity, ShadowsThroughQuadricsAndInstances) {
    const std::string dir = rd::test::shaderFolder("shader_shadows", kShaders);
    Rendered r = renderRib(
        floorScene(dir) +
        "ObjectBegin 1\nPolygon \"P\" [-0.6 -0.6 0  0.6 -0.6 0  0.6 0.6 0  -0.6 0.6 0]\n"
        "ObjectEnd\nAttribute \"visibility\" \"int camera\" [0]\n"
        "Attribute \"visibility\" \"string transmission\" [\"shader\"]\n"
        "Surface \"halfop\" \"edge\" -9\n"
        "AttributeBegin\nTranslate -1.5 0 -2\nSphere 0.5 -0.5 0.5 360\nAttributeEnd\n"
        "AttributeBegin\nTranslate 1.5 0 -1\nObjectInstance 1\nAttributeEnd\nWorldEnd\n");
    const double through[3] = {0.75, 0.5, 0.25};
    for (int c = 0; c < 3; ++c) {
        SCOPED_TRACE(c);
        EXPECT_NEAR(r.mean(c, 11, 7, 13, 9), through[c] * through[c], 1e-5);  // the sphere
        EXPECT_NEAR(r.mean(c, 35, 7, 37, 9), through[c], 1e-5);  // the instance
    }
    EXPECT_TRUE(r.stats.features.quadrics);
    EXPECT_TRUE(r.stats.features.instances);
}

// A shader knows when it runs for a shadow ray's Oi: isshadowray() is 1 and rayinfo("type")
// "transmission". Its Oi is 0.5 * 0.5 for shadow rays, 1 for camera rays: the floor under
// a square the camera does not see keeps 0.75, and a square the camera sees is opaque
// (0.3, alpha 1).
TEST(ShaderOpacity, ShadersKnowAShadowRay) {
    const std::string dir = rd::test::shaderFolder("shader_shadows", kShaders);
    Rendered r = renderRib(
        floorScene(dir) +
        "Attribute \"visibility\" \"string transmission\" [\"shader\"]\nSurface \"shy\"\n" +
        square(-1.5, -1, "") + square(1.5, -1, "Attribute \"visibility\" \"int camera\" [1]") +
        "WorldEnd\n");
    EXPECT_NEAR(r.mean(0, 11, 7, 13, 9), 0.75, 1e-5);  // the shadow
    EXPECT_NEAR(r.mean(0, 35, 7, 37, 9), 0.3, 1e-5);   // the square itself
    EXPECT_NEAR(r.mean(3, 35, 7, 37, 9), 1.0, 1e-6);
}

// The lights' parts of shader AOVs go with the shadow rays through the pool: a floor whose
// output `lit` is its Ci, under the squares of
// ShadowsTakeTheShadersOi (the three layers, "shader" transmission): each AOV shows the
// same shadow as the image, channel by channel.
TEST(ShaderOpacity, AovsTakeTheShadowsTheImageDoes) {
    const std::string dir = rd::test::shaderFolder("shader_shadows", kShaders);
    const std::string shader = "Attribute \"visibility\" \"string transmission\" [\"shader\"]\n";
    rd::RenderSettings settings;
    settings.extraAovs = {"lit"};
    Rendered r = renderRib(
        floorScene(dir, "aovlit") + square(-0.75, -1, shader + "Surface \"halfop\" \"edge\" -9") +
            square(-0.75, -2, "Opacity [0.5 0.5 0.5]") +
            square(-0.75, -3, shader + "Surface \"halfop\" \"edge\" -9") + "WorldEnd\n",
        settings);
    EXPECT_TRUE(r.stats.features.shaderShadows);
    auto aov = [&](const std::string& name, int x0, int x1) {
        for (const rd::Channel& c : r.film.aovChannels(name.substr(0, name.find('.'))))
            if (c.name == name) {
                double sum = 0;
                for (int y = 6; y < 10; ++y)
                    for (int x = x0; x < x1; ++x) sum += c.values[size_t(y) * 48 + size_t(x)];
                return sum / (4.0 * (x1 - x0));
            }
        ADD_FAILURE() << "no channel " << name;
        return -1.0;
    };
    const double through[3] = {0.75 * 0.75 * 0.5, 0.5 * 0.5 * 0.5, 0.25 * 0.25 * 0.5};
    const char* channel[3] = {"lit.R", "lit.G", "lit.B"};
    for (int c = 0; c < 3; ++c) {
        SCOPED_TRACE(c);
        EXPECT_NEAR(r.mean(c, 17, 6, 19, 10), through[c], 1e-5);
        EXPECT_NEAR(aov(channel[c], 17, 19), through[c], 1e-5);
        EXPECT_NEAR(aov(channel[c], 26, 30), 1.0, 1e-5);  // out of the shadow
    }
}
