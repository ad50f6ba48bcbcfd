// message_passing_test.cpp: what shaders ask the renderer by name (rsl_abi.h, MESSAGE
// PASSING): attribute() of the object shaded (Attribute values, "category:name"),
// option() (Option values), rayinfo() of the ray that reached the point, and the
// material's other shaders' parameters (surface(), displacement(), atmosphere(),
// incident(), opposite()).
#include <gtest/gtest.h>

#include "emit_cl.h"
#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// `msg` shows what it is given: red the attribute "user:k" (0.1 when there is none),
// green 1 on the object named "left", blue the option "user:gain", plus the attribute
// "user:tint" (a colour) and "user:lift" (a point's y, in current space: the camera's
// at z = -5 from world, so y is unchanged). `raydepth` shows rayinfo("depth") + 0.25 and,
// at depth 0, adds what a ray straight on brings back.
const char* kShaders[][2] = {{"msg", R"(
surface msg() {
    float k = 0.1, gain = 0, found = 0;
    string name = "";
    color tint = 0;
    point lift = 0;
    attribute("user:k", k);
    attribute("identifier:name", name);
    attribute("user:tint", tint);
    found = attribute("user:lift", lift);
    option("user:gain", gain);
    Ci = color(k, name == "left" ? 1 : 0, gain) + tint + found * ycomp(lift);
    Oi = 1;
}
)"},
                             {"showkd", R"(
surface showkd(float Kd = 0.25;) {
    float km = 0, dens = 0;
    displacement("Km", km);
    atmosphere("dens", dens);
    Ci = color(Kd, km, dens / 10);
    Oi = 1;
}
)"},
                             {"noop", R"(
volume noop(float dens = 7;) {
}
)"},
                             {"half", R"(
volume half(float dens = 7;) {
    Ci *= 0.5;
}
)"},
                             {"sides", R"(
surface sides() {
    float in = 0, out = 0;
    incident("dens", in);
    opposite("dens", out);
    Ci = color(in / 10, out / 10, 1);
    Oi = 1;
}
)"},
                             {"sumcl", R"(
surface sumcl(float Kd = 0.3;) {
    Ci = 0;
    illuminance(P) {
        Ci += Cl;
    }
    Oi = 1;
}
)"},
                             {"kdlight", R"(
light kdlight() {
    float kd = -1;
    surface("Kd", kd);
    solar(vector(0, 0, 1), 0) {
        Cl = kd;
    }
}
)"},
                             {"raydepth", R"(
surface raydepth() {
    float d = -1;
    color c = 0;
    rayinfo("depth", d);
    if (d < 1)
        c = trace(P, normalize(I));
    Ci = d + 0.25 + c;
    Oi = 1;
}
)"},
                             {"raylevel", R"(
surface raylevel() {
    float v[4] = {9, 9, 9, 9}, arr[3] = {1, 2, 3};
    color c = 0;
    string r = "", vs = "";
    if (raylevel() < 1)
        c = trace(P, normalize(I)) * color(1, 0, 0);
    float known = rendererinfo("renderer", r) + rendererinfo("version", v) +
                  rendererinfo("versionstring", vs) + rendererinfo("colour", vs);
    Ci = color(raylevel() + 0.25 + 100 * isshadowray(),
               (r == "RayDrive" ? 1 : 0) + (vs == "0.1.0" ? 1 : 0) + v[0] + v[1] + v[2] +
                   v[3] + arraylength(arr) + arraylength(known),
               known) + c;
    Oi = 1;
}
)"}};

const char* kCamera =
    "Format 48 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\nScreenWindow -3 3 -1 "
    "1\n"
    "Translate 0 0 5\n";

std::string square(double x, const std::string& attributes) {
    return "AttributeBegin\n" + attributes + "\nPolygon \"P\" [" +
           std::to_string(x - 0.6) + " -0.6 0  " + std::to_string(x + 0.6) + " -0.6 0  " +
           std::to_string(x + 0.6) + " 0.6 0  " + std::to_string(x - 0.6) +
           " 0.6 0]\nAttributeEnd\n";
}

}  // namespace

// Three squares with the msg shader: the left named "left" with k 0.5, the middle with k
// 0.25, a tint and a point, the right with none of them; the option's gain everywhere.
TEST(MessagePassing, AttributeAndOptionFindTheirValues) {
    const std::string dir = rd::test::shaderFolder("message_passing", kShaders);
    const std::string rib =
        "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
        "Option \"user\" \"float gain\" [0.75]\n" + kCamera +
        "WorldBegin\nSurface \"msg\"\n" +
        square(-2,
               "Attribute \"identifier\" \"name\" [\"left\"]\nAttribute \"user\" \"float "
               "k\" [0.5]") +
        square(0,
               "Attribute \"user\" \"float k\" [0.25] \"color tint\" [0 0.5 0]\n"
               "Attribute \"user\" \"point lift\" [0 0.125 0]") +
        square(2, "") + "WorldEnd\n";
    Rendered r = renderRib(rib);
    auto at = [&](int channel, int column) {
        return r.mean(channel, column - 2, 6, column + 2, 10);
    };
    EXPECT_NEAR(at(0, 8), 0.5, 1e-6);  // left: k, named "left", gain
    EXPECT_NEAR(at(1, 8), 1.0, 1e-6);
    EXPECT_NEAR(at(2, 8), 0.75, 1e-6);
    EXPECT_NEAR(at(0, 24), 0.25 + 0.125, 1e-6);  // middle: k, tint, lift
    EXPECT_NEAR(at(1, 24), 0.5 + 0.125, 1e-6);
    EXPECT_NEAR(at(2, 24), 0.75 + 0.125, 1e-6);
    EXPECT_NEAR(at(0, 40), 0.1, 1e-6);  // right: no attribute, its default kept
    EXPECT_NEAR(at(1, 40), 0.0, 1e-6);
    EXPECT_NEAR(at(2, 40), 0.75, 1e-6);
    // an attribute of another size than the variable asks for is not found
    std::string wrong = rib;
    wrong.replace(wrong.find("\"float k\" [0.5]"), 15, "\"float[2] k\" [0.5 0.5]");
    EXPECT_NEAR(renderRib(wrong).mean(0, 6, 6, 10, 10), 0.1, 1e-6);
}

// rayinfo("depth"): 0 for camera rays, 1 for the ray a trace() call sends. A square in
// front of another of the same size: the front one (depth 0) is 0.25 plus what its ray
// straight on brings back from the one behind (depth 1: 1.25, and it traces no further).
TEST(MessagePassing, RayinfoGivesTheRaysDepth) {
    const std::string dir = rd::test::shaderFolder("message_passing", kShaders);
    Rendered r = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                           std::string(kCamera) + "WorldBegin\nSurface \"raydepth\"\n" +
                           square(0, "") + square(0, "Translate 0 0 1") + "WorldEnd\n");
    EXPECT_NEAR(r.mean(0, 22, 6, 26, 10), 1.5, 1e-5);
    // the names rsl_rayinfo knows, as rsl_stdlib.clh spells their ids
    EXPECT_EQ(rsl::stringId("depth"), 7708394);
    EXPECT_EQ(rsl::stringId("type"), 2617677);
    EXPECT_EQ(rsl::stringId("origin"), 8362575);
    EXPECT_EQ(rsl::stringId("direction"), 7194474);
    EXPECT_EQ(rsl::stringId("length"), 13645333);
    EXPECT_EQ(rsl::stringId("camera"), 12490830);
    EXPECT_EQ(rsl::stringId("trace"), 4027822);
}

// BMRT's and PRMan's raylevel() (as rayinfo("depth": the front square 0.25 plus 1.25 of
// the one behind), isshadowray() (0 for camera and traced rays), arraylength() (3 for a
// float[3], -1 for a float), and rendererinfo(): "renderer" RayDrive, "versionstring"
// 0.1.0, "version" 0 1 0 0, each found (1), an unknown name not (0). Before, raylevel,
// isshadowray and arraylength were unknown functions and rendererinfo found nothing.
TEST(MessagePassing, RaylevelAndRendererinfo) {
    const std::string dir = rd::test::shaderFolder("message_passing", kShaders);
    Rendered r = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                           std::string(kCamera) + "WorldBegin\nSurface \"raylevel\"\n" +
                           square(0, "") + square(0, "Translate 0 0 1") + "WorldEnd\n");
    EXPECT_NEAR(r.mean(0, 22, 6, 26, 10), 1.5, 1e-5);
    EXPECT_NEAR(r.mean(1, 22, 6, 26, 10), 1 + 1 + 1 + 3 - 1, 1e-6);
    EXPECT_NEAR(r.mean(2, 22, 6, 26, 10), 3, 1e-6);
}

// surface(), displacement() and atmosphere(): a parameter of the shaded material's own
// shaders, as bound. showkd shows its Kd, its displacement's Km and its atmosphere's dens
// / 10: (0.5, 0.75, 0.4) on the left square, which has all three; (0.25, 0, 0) on the
// right, with its default Kd and neither of the others (not found). A light reads the
// surface it lights: kdlight's Cl is the surface's Kd (0.6 left, the default 0.3 right).
// Before, each of these calls found nothing (0).
TEST(MessagePassing, ShadersReadTheMaterialsOtherShaders) {
    const std::string dir = rd::test::shaderFolder("message_passing", kShaders);
    const std::string search = "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n";
    Rendered r = renderRib(search + kCamera + "WorldBegin\n" +
                           square(-2,
                                  "Surface \"showkd\" \"Kd\" [0.5]\n"
                                  "Displacement \"bumpy\" \"Km\" [0.75]\n"
                                  "Atmosphere \"noop\" \"dens\" [4]") +
                           square(2, "Surface \"showkd\"") + "WorldEnd\n");
    auto at = [&](const Rendered& img, int channel, int column) {
        return img.mean(channel, column - 2, 6, column + 2, 10);
    };
    EXPECT_NEAR(at(r, 0, 8), 0.5, 1e-6);
    EXPECT_NEAR(at(r, 1, 8), 0.75, 1e-6);
    EXPECT_NEAR(at(r, 2, 8), 0.4, 1e-6);
    EXPECT_NEAR(at(r, 0, 40), 0.25, 1e-6);
    EXPECT_NEAR(at(r, 1, 40), 0.0, 1e-6);
    EXPECT_NEAR(at(r, 2, 40), 0.0, 1e-6);
    Rendered lit =
        renderRib(search + kCamera + "WorldBegin\nLightSource \"kdlight\" 1\n" +
                  square(-2, "Surface \"sumcl\" \"Kd\" [0.6]") +
                  square(2, "Surface \"sumcl\"") + "WorldEnd\n");
    EXPECT_NEAR(at(lit, 0, 8), 0.6, 1e-6);
    EXPECT_NEAR(at(lit, 0, 40), 0.3, 1e-6);
}

// incident() and opposite(): the volume on the side the ray comes from and the other. Two
// squares with an Interior ("half": it halves what comes back through the inside, so
// the blue channel tells which square the renderer entered from its inside) of dens 3
// and an Exterior of dens 5, one wound each way: seen from the outside incident() is the
// exterior's 5 and opposite() the interior's 3; seen from the inside the two swap. A
// third, wound one way and then the other, has an Atmosphere (dens 8) and no Exterior:
// from outside the eye ray crossed the atmosphere, so incident() reads 8.
TEST(MessagePassing, IncidentAndOppositeReadTheVolumesEitherSide) {
    const std::string dir = rd::test::shaderFolder("message_passing", kShaders);
    const std::string search = "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n";
    const std::string volumes = "Surface \"sides\"\nInterior \"half\" \"dens\" [3]\n";
    auto reversed = [](double x, const std::string& attributes) {
        return "AttributeBegin\n" + attributes + "\nPolygon \"P\" [" +
               std::to_string(x - 0.6) + " -0.6 0  " + std::to_string(x - 0.6) +
               " 0.6 0  " + std::to_string(x + 0.6) + " 0.6 0  " +
               std::to_string(x + 0.6) + " -0.6 0]\nAttributeEnd\n";
    };
    auto at = [](const Rendered& img, int channel, int column) {
        return img.mean(channel, column - 2, 6, column + 2, 10);
    };
    for (int outwardFirst = 0; outwardFirst < 2; ++outwardFirst) {
        // which of the two windings faces the camera is the renderer's (RI's) rule; the
        // interior's halving says which one the ray met from inside
        Rendered r = renderRib(
            search + kCamera + "WorldBegin\n" +
            square(-2, volumes + "Exterior \"noop\" \"dens\" [5]") +
            reversed(0, volumes + "Exterior \"noop\" \"dens\" [5]") +
            (outwardFirst ? square(2, volumes + "Atmosphere \"noop\" \"dens\" [8]")
                          : reversed(2, volumes + "Atmosphere \"noop\" \"dens\" [8]")) +
            "WorldEnd\n");
        const bool squareFromInside = at(r, 2, 8) < 0.75;
        const int inside = squareFromInside ? 8 : 24, outside = squareFromInside ? 24 : 8;
        EXPECT_NEAR(at(r, 2, inside), 0.5, 1e-6);
        EXPECT_NEAR(at(r, 2, outside), 1.0, 1e-6);
        EXPECT_NEAR(at(r, 0, outside), 0.5, 1e-6);  // incident: the exterior's 5
        EXPECT_NEAR(at(r, 1, outside), 0.3, 1e-6);  // opposite: the interior's 3
        EXPECT_NEAR(at(r, 0, inside), 0.15, 1e-6);  // incident: the interior's 3, halved
        EXPECT_NEAR(at(r, 1, inside), 0.25, 1e-6);  // opposite: the exterior's 5, halved
        // the third square, wound as the square at -2 when outwardFirst
        const bool thirdOutside = bool(outwardFirst) != squareFromInside;
        if (thirdOutside) {
            EXPECT_NEAR(at(r, 0, 40), 0.8, 1e-6);  // no Exterior: the atmosphere's 8
            EXPECT_NEAR(at(r, 1, 40), 0.3, 1e-6);
        } else {  // seen from inside: the interior, and no exterior behind
            EXPECT_NEAR(at(r, 0, 40), 0.15, 1e-6);
            EXPECT_NEAR(at(r, 1, 40), 0.4, 1e-6);  // the atmosphere's 8, halved
        }
    }
}
