// aov_test.cpp: shader AOVs (PRMan's arbitrary output variables): a surface shader's
// output variables and the shading globals as image channels, the parts that depend on a
// light carried by its shadow ray (so they are shadowed), and secondary displays
// (Display "+name") written as files of their own.
#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "film/exr_output.h"
#include "render_harness.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"
#include "shaders/shader_set.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// albedo and mask do not depend on the lights; diff does (so the shader is evaluated
// per light, and diff's light part rides on the shadow ray).
const char* kShader = R"(
surface aovtest(output varying color albedo = 0; output varying float mask = 0;
                output varying color diff = 0;) {
    normal Nf = faceforward(normalize(N), I);
    albedo = Cs;
    mask = 1;
    diff = diffuse(Nf);
    Ci = Cs * diff;
    Oi = Os;
}
)";

// Ci takes nothing from the lights; diff does.
const char* kUnlit = R"(
surface aovunlit(output varying color diff = 0;) {
    diff = diffuse(faceforward(normalize(N), I));
    Ci = Cs;
    Oi = Os;
}
)";

std::string shaderDir(const std::string& name) {
    std::string dir = rd::test::scratchDir(name);
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/aovtest.sl") << kShader;
    std::ofstream(dir + "/aovunlit.sl") << kUnlit;
    return dir;
}

// Orthographic, 1/16 unit a pixel: x = -2 + (px + 0.5) / 16, y = 1 - (py + 0.5) / 16.
// The camera is 5 units from the world's origin, so RayDrive's own origin (the eye) is
// not the world's. A plane of Cs (0.2, 0.4, 0.6) over [-1.5, 1.5] x [-0.75, 0.75] (pixels
// [8, 56) x [4, 28)) at z = 0 with aovtest; a constant white square over [-0.25, 0.25]^2
// at z = -1 (pixels [28, 36) x [12, 20)) in front of it; a distant light toward (1, 0, 1):
// the plane is lit at cos 45 degrees, and the square's shadow falls on x in
// [0.75, 1.25] (pixels [44, 52) x [12, 20)).
std::string scene(const std::string& dir, const std::string& displays,
                  const std::string& shader = "aovtest") {
    return "Option \"searchpath\" \"shader\" [\"" + dir +
           ":&\"]\nFormat 64 32 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
           "ScreenWindow -2 2 -1 1\n" +
           displays +
           "Translate 0 0 5\nWorldBegin\n"
           "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [1 0 1]\n"
           "AttributeBegin\nSurface \"" +
           shader +
           "\"\nColor [0.2 0.4 0.6]\n"
           "Polygon \"P\" [-1.5 -0.75 0  1.5 -0.75 0  1.5 0.75 0  -1.5 0.75 0]\n"
           "AttributeEnd\n"
           "AttributeBegin\nSurface \"constant\"\nTranslate 0 0 -1\n"
           "Polygon \"P\" [-0.25 -0.25 0  0.25 -0.25 0  0.25 0.25 0  -0.25 0.25 0]\n"
           "AttributeEnd\nWorldEnd\n";
}

// Mean of a channel over pixels [x0, x1) x [y0, y1).
double mean(const std::vector<rd::Channel>& channels, const std::string& name, int x0,
            int y0, int x1, int y1, int width = 64) {
    for (const rd::Channel& c : channels)
        if (c.name == name) {
            double sum = 0;
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) sum += c.values[size_t(y) * width + x];
            return sum / ((x1 - x0) * (y1 - y0));
        }
    ADD_FAILURE() << "no channel " << name;
    return -1;
}

std::vector<rd::Channel> channels(const rd::Film& film, const std::vector<std::string>& names) {
    std::vector<rd::Channel> out;
    for (const std::string& n : names)
        for (rd::Channel& c : film.aovChannels(n)) out.push_back(std::move(c));
    return out;
}

}  // namespace

// Output variables are the channels of the first surface each camera ray is shaded at:
// albedo is Cs on the plane and 0 where the constant square (which has no such output)
// or nothing is; diff is cos 45 degrees where the light reaches the plane and 0 in the
// square's shadow, as Ci = Cs * diff is in the image.
TEST(ShaderAovs, OutputVariablesAreTheFirstSurfacesAndShadowed) {
    rd::RenderSettings settings;
    settings.extraAovs = {"albedo", "mask", "diff"};
    Rendered r = renderRib(scene(shaderDir("aov_outputs"), ""), settings);
    const std::vector<rd::Channel> c = channels(r.film, {"albedo", "mask", "diff"});
    const double lit = std::sqrt(0.5);
    // the plane, lit
    EXPECT_NEAR(mean(c, "albedo.R", 12, 8, 24, 24), 0.2, 1e-6);
    EXPECT_NEAR(mean(c, "albedo.G", 12, 8, 24, 24), 0.4, 1e-6);
    EXPECT_NEAR(mean(c, "albedo.B", 12, 8, 24, 24), 0.6, 1e-6);
    EXPECT_NEAR(mean(c, "mask", 12, 8, 24, 24), 1.0, 1e-6);
    EXPECT_NEAR(mean(c, "diff.G", 12, 8, 24, 24), lit, 1e-5);
    EXPECT_NEAR(r.mean(0, 12, 8, 24, 24), 0.2 * lit, 1e-5);
    // the plane in the square's shadow: the light's part of diff never arrived
    EXPECT_NEAR(mean(c, "albedo.R", 45, 13, 51, 19), 0.2, 1e-6);
    EXPECT_NEAR(mean(c, "diff.G", 45, 13, 51, 19), 0.0, 1e-6);
    EXPECT_NEAR(r.mean(0, 45, 13, 51, 19), 0.0, 1e-6);
    // the constant square (no output variables): 0, while the image is white
    EXPECT_NEAR(mean(c, "albedo.R", 29, 13, 35, 19), 0.0, 1e-6);
    EXPECT_NEAR(mean(c, "mask", 29, 13, 35, 19), 0.0, 1e-6);
    EXPECT_NEAR(r.mean(0, 29, 13, 35, 19), 1.0, 1e-6);
    // nothing
    EXPECT_NEAR(mean(c, "mask", 0, 0, 6, 32), 0.0, 1e-6);
    // An edge pixel is the fraction of its samples on the plane: between 0 and 1.
    EXPECT_NEAR(mean(c, "mask", 8, 4, 56, 28), 1.0 - 64.0 / (48 * 24), 1e-6);
    EXPECT_NE(r.stats.program.options.find("-DRT_SHADER_AOVS=7"), std::string::npos)
        << r.stats.program.options;

    // Without AOVs the kernels carry none of it.
    Rendered plain = renderRib(scene(shaderDir("aov_outputs"), ""));
    EXPECT_EQ(plain.stats.program.options.find("RT_SHADER_AOVS"), std::string::npos);
    EXPECT_NEAR(plain.mean(0, 12, 8, 24, 24), 0.2 * lit, 1e-5);
}

// A light's part of an output rides on its shadow ray even when Ci takes nothing from
// that light (no light weight to carry): diff is lit and shadowed as before, while the
// image is Cs throughout.
TEST(ShaderAovs, ALightsPartRidesWhenCiTakesNothingFromIt) {
    rd::RenderSettings settings;
    settings.extraAovs = {"diff"};
    Rendered r = renderRib(scene(shaderDir("aov_unlit"), "", "aovunlit"), settings);
    const std::vector<rd::Channel> c = channels(r.film, {"diff"});
    EXPECT_NEAR(mean(c, "diff.G", 12, 8, 24, 24), std::sqrt(0.5), 1e-5);
    EXPECT_NEAR(mean(c, "diff.G", 45, 13, 51, 19), 0.0, 1e-6);
    EXPECT_NEAR(r.mean(0, 12, 8, 24, 24), 0.2, 1e-6);  // Cs: no light, no alpha from it
    EXPECT_NEAR(r.mean(0, 45, 13, 51, 19), 0.2, 1e-6);
    EXPECT_NEAR(r.mean(3, 12, 8, 24, 24), 1.0, 1e-6);
}

// Through a transparent surface the AOVs are composited as Ci is: the white constant
// square (no outputs) at Opacity 0.5 in front of the plane gives albedo = 0.5 Cs, mask
// 0.5 and diff 0.5 cos 45 there (the plane's light part scaled too), while a point (P)
// stays the first surface's. Before, the plane behind gave nothing (albedo 0); and in the
// square's shadow diff was cos 45, the light's part undimmed by the square.
TEST(ShaderAovs, CompositedThroughTransparentSurfaces) {
    std::string rib = scene(shaderDir("aov_composite"), "");
    rib.replace(rib.find("Surface \"constant\"\n"), 19,
                "Surface \"constant\"\nOpacity [0.5 0.5 0.5]\n");
    rd::RenderSettings settings;
    settings.extraAovs = {"albedo", "mask", "diff", "P"};
    Rendered r = renderRib(rib, settings);
    const std::vector<rd::Channel> c = channels(r.film, {"albedo", "mask", "diff", "P"});
    const double lit = std::sqrt(0.5);
    EXPECT_NEAR(mean(c, "albedo.R", 29, 13, 35, 19), 0.1, 1e-6);
    EXPECT_NEAR(mean(c, "albedo.B", 29, 13, 35, 19), 0.3, 1e-6);
    EXPECT_NEAR(mean(c, "mask", 29, 13, 35, 19), 0.5, 1e-6);
    EXPECT_NEAR(mean(c, "diff.G", 29, 13, 35, 19), 0.5 * lit, 1e-5);
    EXPECT_NEAR(mean(c, "P.Z", 29, 13, 35, 19), -1.0, 1e-4);
    EXPECT_NEAR(r.mean(0, 29, 13, 35, 19), 0.5 + 0.5 * 0.2 * lit, 1e-5);
    // beside the square, the plane's own in full; in the square's shadow the light's part
    // comes through dimmed as the light is (transparent shadows), as Ci = Cs diff there
    EXPECT_NEAR(mean(c, "albedo.R", 12, 8, 24, 24), 0.2, 1e-6);
    EXPECT_NEAR(mean(c, "diff.G", 45, 13, 51, 19), 0.5 * lit, 1e-5);
    EXPECT_NEAR(r.mean(0, 45, 13, 51, 19), 0.2 * 0.5 * lit, 1e-5);
    EXPECT_NEAR(mean(c, "P.Z", 12, 8, 24, 24), 0.0, 1e-4);
    EXPECT_NE(r.stats.program.options.find("-DRT_RAY_AOVS"), std::string::npos);
    // through treelets the shadow rays walk the square as well, and dim the part alike
    settings.treeletBytes = 1;
    Rendered t = renderRib(rib, settings);
    EXPECT_TRUE(t.stats.treelets.used);
    EXPECT_NEAR(mean(channels(t.film, {"diff"}), "diff.G", 45, 13, 51, 19), 0.5 * lit,
                1e-5);
    EXPECT_NEAR(t.mean(0, 45, 13, 51, 19), 0.2 * 0.5 * lit, 1e-5);
}

// A colour AOV in the scene's own channels reaches the image as RGB through nRGB: two
// channels shown as red and blue, Cs (0.2, 0.5) gives albedo (0.2, 0, 0.5) (kept as the
// channels it would read (0.2, 0.5, 0.5)), and diff, lit by white, (cos 45, 0, cos 45).
TEST(ShaderAovs, ColourAovsAreMadeRgb) {
    std::string rib = "ColorSamples [1 0 0  0 0 1] [1 0  0 0  0 1]\n" +
                      scene(shaderDir("aov_two_channels"), "");
    rib.replace(rib.find("Color [0.2 0.4 0.6]"), 19, "Color [0.2 0.5]");
    rd::RenderSettings settings;
    settings.extraAovs = {"albedo", "diff"};
    Rendered r = renderRib(rib, settings);
    const std::vector<rd::Channel> c = channels(r.film, {"albedo", "diff"});
    EXPECT_NEAR(mean(c, "albedo.R", 12, 8, 24, 24), 0.2, 1e-6);
    EXPECT_NEAR(mean(c, "albedo.G", 12, 8, 24, 24), 0.0, 1e-6);
    EXPECT_NEAR(mean(c, "albedo.B", 12, 8, 24, 24), 0.5, 1e-6);
    EXPECT_NEAR(mean(c, "diff.G", 12, 8, 24, 24), 0.0, 1e-6);
    EXPECT_NEAR(mean(c, "diff.B", 12, 8, 24, 24), std::sqrt(0.5), 1e-5);
}

// The globals as AOVs: Cs, Oi, and P in the RIB's world space (the camera is 5 units
// from its origin, RayDrive's own origin), s on the plane.
TEST(ShaderAovs, GlobalsInWorldSpace) {
    rd::RenderSettings settings;
    settings.extraAovs = {"Cs", "P", "Oi"};
    Rendered r = renderRib(scene(shaderDir("aov_globals"), ""), settings);
    const std::vector<rd::Channel> c = channels(r.film, {"Cs", "P", "Oi"});
    EXPECT_NEAR(mean(c, "Cs.B", 12, 8, 24, 24), 0.6, 1e-6);
    EXPECT_NEAR(mean(c, "Oi.R", 12, 8, 24, 24), 1.0, 1e-6);
    // pixels [12, 24) are x in [-1.25, -0.5): the mean is their middle, up to where
    // the 768 samples fall in their pixels (a pixel is 0.0625 wide)
    EXPECT_NEAR(mean(c, "P.X", 12, 8, 24, 24), -0.875, 4e-3);
    EXPECT_NEAR(mean(c, "P.Y", 12, 8, 24, 24), 0.0, 4e-3);
    EXPECT_NEAR(mean(c, "P.Z", 12, 8, 24, 24), 0.0, 1e-4);
    // the square, one unit nearer the camera
    EXPECT_NEAR(mean(c, "P.Z", 29, 13, 35, 19), -1.0, 1e-4);
}

// Display "+name" writes a file of its own: one colour AOV as R, G, B; one float as Y;
// several by their names. The main image holds only what its own Display and
// DisplayChannel name.
TEST(ShaderAovs, SecondaryDisplaysAreFilesOfTheirOwn) {
    const std::string dir = shaderDir("aov_displays");
    const std::string out = dir + "/out";
    std::filesystem::create_directories(out);
    const std::string rib =
        scene(dir, "Display \"" + out + "/main.exr\" \"file\" \"rgba\"\n"
                   "DisplayChannel \"varying float mask\"\n"
                   "Display \"+" + out + "/albedo.exr\" \"file\" \"color albedo\"\n"
                   "Display \"+" + out + "/mask.exr\" \"file\" \"mask\"\n"
                   "Display \"+" + out + "/both.exr\" \"file\" \"rgb,diff,z\"\n");
    const std::string messages = rd::test::renderRibToFiles(rib);
    EXPECT_EQ(messages.find("warning"), std::string::npos) << messages;

    auto names = [](const std::string& file) {
        Imf::InputFile f(file.c_str());
        std::string all;
        for (auto it = f.header().channels().begin(); it != f.header().channels().end(); ++it)
            all += std::string(all.empty() ? "" : " ") + it.name();
        return all;
    };
    EXPECT_EQ(names(out + "/main.exr"), "A B G R mask");
    EXPECT_EQ(names(out + "/albedo.exr"), "B G R");
    EXPECT_EQ(names(out + "/mask.exr"), "Y");
    EXPECT_EQ(names(out + "/both.exr"), "B G R Z diff.B diff.G diff.R");
    int w = 0, h = 0;
    const std::vector<rd::Rgba> albedo = rd::readExr(out + "/albedo.exr", w, h);
    ASSERT_EQ(w, 64);
    EXPECT_NEAR(albedo[size_t(16) * 64 + 16].g, 0.4f, 1e-6f);
    EXPECT_NEAR(albedo[size_t(16) * 64 + 32].g, 0.0f, 1e-6f);  // the constant square
}

// AOVs no shader writes, and outputs of another type than the AOV declared, are
// reported; the layout gives each AOV its declared type's floats.
TEST(ShaderAovs, UnwrittenAndMistypedAovsAreReported) {
    const std::string dir = shaderDir("aov_layout");
    std::ostringstream messages;
    rib::Diagnostics diag(&messages);
    rd::RibBuilder builder(diag, "t.rib");
    rib::readString(scene(dir, "DisplayChannel \"float albedo\"\n"), "t.rib", builder, diag);
    ASSERT_EQ(builder.scenes().size(), 1u);
    rd::ShadingSetup setup =
        rd::ShaderSet(builder.scenes()[0], diag).prepare({"z", "albedo", "nothing", "diff", "s"});
    ASSERT_EQ(setup.aovs.size(), 4u);  // z is the renderer's own
    EXPECT_EQ(setup.aovs[0].type, "float");  // as declared
    EXPECT_EQ(setup.aovs[1].floats, 1);
    EXPECT_EQ(setup.aovs[2].type, "color");  // the shader's
    EXPECT_EQ(setup.aovs[2].offset, 2);
    EXPECT_EQ(setup.aovs[3].type, "float");  // the global s
    EXPECT_EQ(setup.aovFloats, 1 + 1 + 3 + 1);
    const std::string m = messages.str();
    EXPECT_NE(m.find("output variable \"albedo\" is a color, the AOV a float: not written"),
              std::string::npos) << m;
    EXPECT_NE(m.find("AOV \"nothing\": no surface shader"), std::string::npos) << m;
    EXPECT_EQ(m.find("AOV \"s\""), std::string::npos) << m;
}
