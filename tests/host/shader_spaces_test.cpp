// shader_spaces_test.cpp: the coordinate systems shaders name, rendered through the
// whole pipeline: "shader" (where the shader was declared), "world" (the RIB's, though
// the device keeps the scene relative to the eye) and "object" (each primitive's own,
// where the shader reads it: an instance per object space).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "render_harness.h"
#include "shaders/space_services.h"

using rd::test::Rendered;
using rd::test::renderRib;

// "shader" space is the coordinate system current at the Surface call: a shader that
// prints transform("shader", P) sees world x shifted by the Translate before Surface.
TEST(Shading, ShaderSpaceIsWhereTheSurfaceWasDeclared) {
    const std::string dir = rd::test::scratchDir("raydrive_space");
    std::ofstream(dir + "/showspace.sl")
        << "surface showspace() {\n    Oi = 1;\n"
           "    Ci = color(xcomp(transform(\"shader\", P)) + 2, 0, 0);\n}\n";
    Rendered img =
        renderRib("Option \"searchpath\" \"shader\" [\"" + dir +
                  ":&\"]\n"
                  "Format 16 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                  "WorldBegin\nAttributeBegin\nTranslate 0.5 0 0\n"
                  "Surface \"showspace\"\nTranslate -0.5 0 0\n"
                  "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1]\n"
                  "AttributeEnd\nWorldEnd\n");
    // world x at the centre of column 8 is 0.0625: shader x = 0.0625 - 0.5
    EXPECT_NEAR(img.mean(0, 8, 0, 9, 16), 0.0625 - 0.5 + 2, 0.02);
}

// "world" space is the RIB's world even though the renderer keeps the scene relative to
// the eye (for precision far from the origin): a camera at world (10, 0, -5) looking at
// the point (10, 0, 0) sees transform("world", P) = (10, 0, 0) at the image centre.
TEST(Shading, WorldSpaceIsTheRibWorld) {
    const std::string dir = rd::test::scratchDir("raydrive_world");
    std::ofstream(dir + "/showworld.sl")
        << "surface showworld() {\n    Oi = 1;\n    point w = transform(\"world\", P);\n"
           "    Ci = color(xcomp(w) / 10, ycomp(w) + 1, zcomp(w) + 1);\n}\n";
    Rendered img =
        renderRib("Option \"searchpath\" \"shader\" [\"" + dir +
                  ":&\"]\n"
                  "Format 16 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                  "ScreenWindow -0.5 0.5 -0.5 0.5\nTranslate -10 0 5\n"
                  "WorldBegin\nSurface \"showworld\"\n"
                  "Polygon \"P\" [9 -1 0  11 -1 0  11 1 0  9 1 0]\nWorldEnd\n");
    EXPECT_NEAR(img.mean(0, 7, 7, 9, 9), 1.0, 0.01);
    EXPECT_NEAR(img.mean(1, 7, 7, 9, 9), 1.0, 0.05);
    EXPECT_NEAR(img.mean(2, 7, 7, 9, 9), 1.0, 0.01);
}

// "object" space is the coordinate system current at each primitive, not at the Surface
// call (RI 3.2): one Surface declared at the world's top shades spheres translated to
// x = -2 and x = 2 (the second turned 90 degrees about y) and a square pushed to z = 0.5.
// transform("object", P) at the front of each sphere, head on, is the sphere's own
// (0, 0, -1), turned to (1, 0, 0) on the second; the square's z is its own 0. A default
// written in "object" space (point "object" (0, 0, 0)) is each sphere's centre, so
// length(P - centre) is the radius (1, and 0.3 for a small one moved in front); a
// displacement that reads "object" space gets the primitive's too. Before, all three saw
// the declaration's space (the world's).
TEST(Shading, ObjectSpaceIsEachPrimitivesOwn) {
    const std::string dir = rd::test::scratchDir("raydrive_object_space");
    std::ofstream(dir + "/showobject.sl")
        << "surface showobject() {\n    Oi = 1;\n    point o = transform(\"object\", "
           "P);\n"
           "    Ci = color(xcomp(o) + 2, ycomp(o) + 2, zcomp(o) + 2);\n}\n";
    std::ofstream(dir + "/objcentre.sl")
        << "surface objcentre(point centre = point \"object\" (0, 0, 0)) {\n"
           "    Oi = 1;\n    Ci = length(P - centre);\n}\n";
    std::ofstream(dir + "/objnormal.sl")
        << "displacement objnormal() {\n    point o = transform(\"object\", P);\n"
           "    N = normal(xcomp(o), ycomp(o), zcomp(o));\n}\n";
    std::ofstream(dir + "/shownormal.sl")
        << "surface shownormal() {\n    Oi = 1;\n    normal n = normalize(N);\n"
           "    Ci = color(xcomp(n), ycomp(n), zcomp(n)) + 2;\n}\n";
    const std::string camera = "Option \"searchpath\" \"shader\" [\"" + dir +
                               ":&\"]\nFormat 64 32 1\nPixelSamples 2 2\n"
                               "Projection \"orthographic\"\nScreenWindow -4 4 -2 2\n"
                               "Translate 0 0 5\nWorldBegin\n";
    const Rendered img = renderRib(
        camera +
        "Surface \"showobject\"\n"
        "AttributeBegin\nTranslate -2 0 0\nSphere 1 -1 1 360\nAttributeEnd\n"
        "AttributeBegin\nTranslate 2 0 0\nRotate 90 0 1 0\nSphere 1 -1 1 "
        "360\nAttributeEnd\n"
        "AttributeBegin\nTranslate 0 0 0.5\n"
        "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\nAttributeEnd\n"
        "WorldEnd\n");
    // pixel 16 is world x = -2, 48 is x = 2 (8 units over 64 pixels); z is about -0.99
    // over the 2 x 2 pixels at a sphere's front
    auto expectOwnSpaces = [](const Rendered& r, const char* what) {
        EXPECT_NEAR(r.mean(0, 15, 15, 17, 17), 2.0, 0.02)
            << "the first " << what << "'s x";
        EXPECT_NEAR(r.mean(2, 15, 15, 17, 17), 1.0, 0.02)
            << "the first " << what << "'s z";
        EXPECT_NEAR(r.mean(0, 47, 15, 49, 17), 3.0, 0.02)
            << "the turned " << what << "'s x";
        EXPECT_NEAR(r.mean(2, 47, 15, 49, 17), 2.0, 0.02)
            << "the turned " << what << "'s z";
    };
    expectOwnSpaces(img, "sphere");
    EXPECT_NEAR(img.mean(2, 30, 14, 34, 18), 2.0, 1e-4) << "the square's own z";
    const Rendered mixed = renderRib(
        camera +
        "AttributeBegin\nSurface \"shownormal\"\nDisplacement \"objnormal\"\n"
        "Translate -2 0 0\nSphere 1 -1 1 360\nAttributeEnd\n"
        "AttributeBegin\nSurface \"objcentre\"\nTranslate 2 0 0\nSphere 1 -1 1 360\n"
        "Translate 0 0 -1.2\nSphere 0.3 -0.3 0.3 360\nAttributeEnd\nWorldEnd\n");
    EXPECT_NEAR(mixed.mean(0, 15, 15, 17, 17), 2.0, 0.02) << "the displacement's own x";
    EXPECT_NEAR(mixed.mean(2, 15, 15, 17, 17), 1.0, 0.02) << "the displacement's own z";
    // (x 1.125 to 1.5 on the unit sphere, beside the small one in front of it)
    EXPECT_NEAR(mixed.mean(0, 41, 14, 44, 18), 1.0, 1e-3) << "each sphere's own centre";
    EXPECT_NEAR(mixed.mean(0, 47, 15, 49, 17), 0.3, 1e-3) << "the nearer sphere's centre";
    // instances: each ObjectInstance's space is its primitives' object space
    const Rendered instanced = renderRib(
        camera +
        "Surface \"showobject\"\nObjectBegin \"ball\"\nSphere 1 -1 1 360\nObjectEnd\n"
        "AttributeBegin\nTranslate -2 0 0\nObjectInstance \"ball\"\nAttributeEnd\n"
        "AttributeBegin\nTranslate 2 0 0\nRotate 90 0 1 0\nObjectInstance \"ball\"\n"
        "AttributeEnd\nWorldEnd\n");
    expectOwnSpaces(instanced, "instance");
}

// "raster", "NDC" and "screen" (RI 3.2 section 4.1; identity before session 35): on a
// plane seen in perspective (fov 40 over 16 of 32 x 16 pixels, the screen window
// [-2, 2] x [-1, 1]), transform("raster", P) and transform("NDC", P) against the camera
// point projected by hand in the shader, the screen z against PRMan's depth between the
// clipping planes, f (z - n) / ((f - n) z) with n = 1, f = 10, and a point sent to raster
// space and back against where it was: each residual at every sample, in the image.
TEST(Shading, ProjectedSpacesArePixelsAndTheScreen) {
    const std::string dir = rd::test::scratchDir("raydrive_projected_spaces");
    std::ofstream(dir + "/showraster.sl")
        << "surface showraster(float ndc = 0) {\n    Oi = 1;\n"
           "    point c = transform(\"camera\", P);\n"
           "    float t = tan(radians(20)), z = zcomp(c);\n"
           "    float x = (xcomp(c) / (z * t) + 2) / 4, y = (1 - ycomp(c) / (z * t)) / "
           "2;\n"
           "    if (ndc == 0) { x *= 32; y *= 16; }\n"
           "    point r = transform(ndc > 0 ? \"NDC\" : \"raster\", P);\n"
           "    point back = transform(\"raster\", \"current\", transform(\"raster\", "
           "P));\n"
           "    Ci = color(abs(xcomp(r) - x) + abs(ycomp(r) - y),\n"
           "               abs(zcomp(transform(\"screen\", P)) - 10 * (z - 1) / (9 * "
           "z)),\n"
           "               length(back - P));\n}\n";
    for (const bool ndc : {false, true}) {
        const Rendered img = renderRib(
            "Option \"searchpath\" \"shader\" [\"" + dir +
            ":&\"]\nFormat 32 16 1\nPixelSamples 2 2\nClipping 1 10\n"
            "Projection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\n"
            "Surface \"showraster\" \"float ndc\" [" +
            (ndc ? "1" : "0") +
            "]\nRotate 30 0 1 0\nPolygon \"P\" [-9 -9 0  9 -9 0  9 9 0  -9 9 "
            "0]\nWorldEnd\n");
        float worst[3] = {0, 0, 0};
        for (const rd::Rgba& p : img.pixels)
            worst[0] = std::max(worst[0], p.r), worst[1] = std::max(worst[1], p.g),
            worst[2] = std::max(worst[2], p.b);
        EXPECT_LT(worst[0], ndc ? 1e-6 : 2e-5) << (ndc ? "NDC" : "raster");
        EXPECT_LT(worst[1], 1e-6) << "screen z";
        EXPECT_LT(worst[2], 1e-5) << "to raster space and back";
    }
}

// Named coordinate systems (CoordinateSystem, Camera "name", a ScopedCoordinateSystem's
// last placement), by a literal name and by
// a string parameter's value: transform("proj", P) for a system placed at (1, 2, 3) and
// turned 90 degrees about z gives P's coordinates in it, (y - 2, 1 - x, z - 3) of the
// world's (residuals at every sample, in the image); a name the scene does not define is
// a warning at the Surface's line (an error before session 35).
TEST(Shading, NamedCoordinateSystemsAreTheScenes) {
    const std::string dir = rd::test::scratchDir("raydrive_named_spaces");
    std::ofstream(dir + "/shownamed.sl")
        << "surface shownamed(string space = \"proj\") {\n    Oi = 1;\n"
           "    point a = transform(space, P), b = transform(\"proj\", P);\n"
           "    point w = transform(\"world\", P);\n"
           "    Ci = color(abs(xcomp(a) - ycomp(w) + 2) + abs(ycomp(a) + xcomp(w) - 1) "
           "+\n"
           "               abs(zcomp(a) - zcomp(w) + 3), length(a - b), 1);\n}\n";
    std::ofstream(dir + "/nowhere.sl") << "surface nowhere() {\n    Oi = 1;\n    Ci = "
                                          "xcomp(transform(\"nowhere\", P));\n}\n";
    const std::string out = rd::test::scratchDir("raydrive_named_spaces_out");
    const std::string options = "Option \"searchpath\" \"shader\" [\"" + dir +
                                ":&\"]\nFormat 16 16 1\nPixelSamples 2 2\n"
                                "Projection \"orthographic\"\nTranslate 0 0 5\n";
    const std::string world =
        "WorldBegin\nAttributeBegin\nTranslate 1 2 3\nRotate 90 0 0 1\n"
        "CoordinateSystem \"proj\"\nAttributeEnd\n";
    // (a ScopedCoordinateSystem's last placement serves the same)
    const std::string scoped =
        "WorldBegin\nAttributeBegin\nTranslate 1 2 3\nRotate 90 0 0 1\n"
        "ScopedCoordinateSystem \"proj\"\nAttributeEnd\n";
    const std::string square =
        "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\nWorldEnd\n";
    // (and a name only the call gives: "proj2", placed alike, reaches the table too)
    const std::string byCall =
        world.substr(0, world.size() - 13) + "CoordinateSystem \"proj2\"\nAttributeEnd\n";
    for (int k = 0; k < 3; ++k) {
        const std::string& placed = k == 0 ? world : k == 1 ? scoped : byCall;
        const std::string surface =
            k == 2 ? "Surface \"shownamed\" \"string space\" [\"proj2\"]\n"
                   : "Surface \"shownamed\"\n";
        const Rendered img = renderRib(options + placed + surface + square);
        float worst[2] = {0, 0};
        for (const rd::Rgba& p : img.pixels)
            worst[0] = std::max(worst[0], p.r), worst[1] = std::max(worst[1], p.g);
        EXPECT_LT(worst[0], 1e-5) << "P in proj";
        EXPECT_EQ(worst[1], 0.0f) << "the name by value and as a literal";
        EXPECT_NEAR(img.mean(2, 0, 0, 16, 16), 1.0, 1e-6) << "the square fills the image";
    }
    const std::string messages = rd::test::renderRibToFiles(
        options + "Display \"" + out + "/nowhere.exr\" \"file\" \"rgba\"\n" + world +
        "Surface \"nowhere\"\n" + square);
    EXPECT_NE(messages.find("test.rib:13: warning: surface shader \"nowhere\" names "
                            "coordinate system \"nowhere\""),
              std::string::npos)
        << messages;
}

// The table of spaces holds the projected ones and the named systems shaders may ask for
// (their literals, the strings their calls and defaults give), not every system the
// scene names: its size and search stay as the shaders make them.
TEST(Shading, TableOfSpacesHoldsWhatShadersName) {
    rd::Scene scene;
    scene.coordinateSystems["asked"] = glm::mat4(2.0f);
    scene.coordinateSystems["other"] = glm::mat4(3.0f);
    const auto spaces = rd::tableSpaces(scene, {"asked", "unknown"});
    std::vector<std::string> names;
    for (const auto& [name, m] : spaces) names.push_back(name);
    EXPECT_EQ(names, (std::vector<std::string>{"screen", "NDC", "raster", "asked"}));
    EXPECT_EQ(spaces[3].second[0][0], 2.0);
}
