// message_passing_test.cpp: what shaders ask the renderer by name (rsl_abi.h, MESSAGE
// PASSING): attribute() of the object shaded (Attribute values, "category:name"),
// option() (Option values) and rayinfo() of the ray that reached the point.
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
