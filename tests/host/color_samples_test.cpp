// color_samples_test.cpp: ColorSamples n <= 15 shades, traces and sums samples in the n
// colour channels and converts each sample to RGB for the film (nRGB); RGB written in a
// shader (literals, colour-space casts, textures) comes in through RGBn. Analytic pixels
// for one, two and four channels; a permutation of the channels, and 6 and 12 channels
// repeating RGB's, that must give the RGB image (products commute with them, the
// conversions are exact or nearly).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

// Shaders of these tests, in a scratch folder on the shader search path.
std::string shaderPath() {
    static const std::string dir = [] {
        std::string d = rd::test::scratchDir("raydrive_color_samples");
        std::filesystem::create_directories(d);
        std::ofstream(d + "/csproduct.sl")
            << "surface csproduct() {\n    Ci = color(1, 0, 0) * color(0, 1, 0);\n    Oi = 1;\n}\n";
        std::ofstream(d + "/cshsv.sl")
            << "surface cshsv(float h = 0) {\n    Ci = color \"hsv\" (h, 1, 1);\n    Oi = 1;\n}\n";
        std::ofstream(d + "/cstinted.sl")
            << "surface cstinted(color tint = color(1, 0.5, 0.25)) {\n"
               "    normal Nf = faceforward(normalize(N), I);\n"
               "    Ci = Os * (Cs * tint * diffuse(Nf) + 0.1 * color \"hsv\" (0.6, 0.5, 1)\n"
               "               + ctransform(\"hsv\", \"rgb\", ctransform(\"hsv\", Cs)) * 0.05);\n"
               "    Oi = Os;\n}\n";
        std::ofstream(d + "/csparam.sl")
            << "surface csparam(color tint = 0) {\n    Ci = tint * ambient();\n    Oi = 1;\n}\n";
        std::ofstream(d + "/cstint.sl")
            << "imager cstint() {\n    Ci = Ci * color(1, 0.5, 0.25) + (1 - alpha) * color \"hsv\" (0.6, 1, 1);\n"
               "    alpha = 1;\n}\n";
        return d;
    }();
    return "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n";
}

const char* kFlat = "Format 8 8 1\nPixelSamples 1 1\nProjection \"orthographic\"\n";
const char* kQuad = "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\n";

// One channel: grey out (nRGB 1 1 1), luminance in (RGBn 0.299 0.587 0.114).
const char* kGrey = "ColorSamples [1 1 1] [0.299 0.587 0.114]\n";

Rendered flat(const std::string& options, const std::string& world) {
    return renderRib(shaderPath() + options + kFlat + "WorldBegin\n" + world + kQuad + "WorldEnd\n");
}

void expectGrey(const Rendered& img, float v, float tol, const char* what) {
    SCOPED_TRACE(what);
    EXPECT_NEAR(img.at(4, 4).r, v, tol);
    EXPECT_NEAR(img.at(4, 4).g, v, tol);
    EXPECT_NEAR(img.at(4, 4).b, v, tol);
}

// Every pixel of `got` equals `want`'s within 1e-6 (`grey`: got's red against each of
// want's channels). Returns the sum of want's pixels' channels.
double expectSameImage(const Rendered& want, const Rendered& got, bool grey) {
    EXPECT_EQ(want.pixels.size(), got.pixels.size());
    double sum = 0;
    for (size_t i = 0; i < want.pixels.size() && i < got.pixels.size(); ++i) {
        const rd::Rgba &a = want.pixels[i], &b = got.pixels[i];
        const float g = b.r;
        EXPECT_NEAR(a.r, b.r, 1e-6f) << "pixel " << i;
        EXPECT_NEAR(a.g, grey ? g : b.g, 1e-6f) << "pixel " << i;
        EXPECT_NEAR(a.b, grey ? g : b.b, 1e-6f) << "pixel " << i;
        EXPECT_NEAR(a.a, b.a, 1e-6f) << "pixel " << i;
        if (::testing::Test::HasFailure()) break;
        sum += a.r + a.g + a.b;
    }
    return sum;
}

// A lit scene for the channel tests: a distant and an ambient light, a transparent sphere
// whose shader writes RGB literals, colour-space casts and ctransform and has an RGB
// parameter default, a reflecting metal sphere (traced rays), a plastic wall. Every
// colour the RIB gives is written by c(r, g, b) in the scene's channels.
using ColorWriter = std::function<std::string(const char*, const char*, const char*)>;
Rendered litScene(const std::string& colorSamples, const ColorWriter& c) {
    return renderRib(
        shaderPath() + colorSamples +
        "Format 24 24 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 40\n"
        "WorldBegin\nLightSource \"distantlight\" 1 \"lightcolor\" " +
        c("1", "0.8", "0.6") +
        " \"from\" [1 1 -1] \"to\" [0 0 0]\n"
        "LightSource \"ambientlight\" 2 \"intensity\" 0.2 \"lightcolor\" " +
        c("0.3", "0.6", "1") +
        "\n"
        "AttributeBegin\nColor " +
        c("0.9", "0.5", "0.2") + "\nOpacity " + c("1", "0.5", "0.25") +
        "\nSurface \"cstinted\"\nTranslate -0.5 0 4\nSphere 1 -1 1 360\nAttributeEnd\n"
        "AttributeBegin\nColor " +
        c("0.2", "0.4", "0.9") +
        "\nSurface \"shinymetal\" \"Kr\" 0.5\n"
        "Translate 0.8 0 5\nSphere 1 -1 1 360\nAttributeEnd\n"
        "AttributeBegin\nColor " +
        c("0.3", "0.9", "0.4") +
        "\nSurface \"plastic\"\n"
        "Polygon \"P\" [-6 -6 8  6 -6 8  6 6 8  -6 6 8]\nAttributeEnd\nWorldEnd\n");
}

}  // namespace

// A colour of one value is that channel; the film shows it through nRGB.
TEST(ColorSamples, OneChannelColoursReachTheFilmThroughNRGB) {
    expectGrey(flat(kGrey, "Color [0.5]\nSurface \"constant\"\n"), 0.5f, 1e-6f, "Color [0.5]");
    // matte lit by an ambient light of one channel: 0.8 * 0.5
    expectGrey(flat(kGrey, "LightSource \"ambientlight\" 1 \"lightcolor\" [0.5]\n"
                           "Color [0.8]\nSurface \"matte\" \"Ka\" 1 \"Kd\" 0\n"),
               0.4f, 1e-6f, "ambient");
    // coverage is the opacity's mean over the channels
    Rendered half = flat(kGrey, "Opacity [0.5]\nSurface \"constant\"\n");
    EXPECT_NEAR(half.at(4, 4).a, 0.5f, 1e-6f);
    EXPECT_NEAR(half.at(4, 4).r, 0.5f, 1e-6f);
}

// Colours multiply in the scene's channels: red times green is black in RGB, but both are
// 0.299 and 0.587 of the one luminance channel, whose product the film shows as grey.
// (Converting colours to RGB as they are read, as before, gives 0 here.)
TEST(ColorSamples, ShaderColoursMultiplyInTheScenesChannels) {
    expectGrey(flat("", "Surface \"csproduct\"\n"), 0.0f, 0.0f, "RGB");
    expectGrey(flat(kGrey, "Surface \"csproduct\"\n"), 0.299f * 0.587f, 1e-6f, "one channel");
    // a colour-space cast is RGB too: hue 0 is red, hue 1/3 green
    expectGrey(flat(kGrey, "Surface \"cshsv\"\n"), 0.299f, 1e-6f, "hsv red");
    expectGrey(flat(kGrey, "Surface \"cshsv\" \"h\" 0.333333333\n"), 0.587f, 1e-5f, "hsv green");
}

// Two channels: channel 0 shows red, channel 1 cyan; coverage is the mean of the two
// channels' opacities (not of three lanes).
TEST(ColorSamples, TwoChannels) {
    const std::string two = "ColorSamples [1 0 0  0 1 1] [1 0  0 0.5  0 0.5]\n";
    Rendered img = flat(two, "Color [0.2 0.6]\nOpacity [1 0.5]\nSurface \"constant\"\n");
    EXPECT_NEAR(img.at(4, 4).a, 0.75f, 1e-6f);
    // Ci = Os * Cs = (0.2, 0.3): RGB (0.2, 0.3, 0.3)
    EXPECT_NEAR(img.at(4, 4).r, 0.2f, 1e-6f);
    EXPECT_NEAR(img.at(4, 4).g, 0.3f, 1e-6f);
    EXPECT_NEAR(img.at(4, 4).b, 0.3f, 1e-6f);
    const std::vector<std::string> names = img.stats.features.names();
    EXPECT_NE(std::find(names.begin(), names.end(), "color_samples_2"), names.end());
    EXPECT_EQ(img.stats.features.colors.n, 2);
}

// Three channels that are RGB's with red and blue swapped: every colour the RIB gives is
// written swapped, and the image must be the RGB one exactly - through lights, a shader
// parameter's RGB default, literals, colour-space casts and ctransform, partial opacity
// (continuation rays) and a mirror's traced rays.
TEST(ColorSamples, PermutedChannelsGiveTheRgbImage) {
    auto scene = [](bool swapped) {
        return litScene(
            swapped ? "ColorSamples [0 0 1 0 1 0 1 0 0] [0 0 1 0 1 0 1 0 0]\n" : "",
            [&](const char* r, const char* g, const char* b) {
                return std::string("[") + (swapped ? b : r) + " " + g + " " +
                       (swapped ? r : b) + "]";
            });
    };
    Rendered rgb = scene(false), swapped = scene(true);
    // Continuation rays through the transparent sphere reach opaque surfaces: their
    // transmitted coverage is exactly 0, never -3e-8 (1932 "negative results" were
    // reported here when the channels' mean was taken as a product with 1/3).
    EXPECT_EQ(rgb.stats.shadeNegative, 0u);
    EXPECT_EQ(swapped.stats.shadeNegative, 0u);
    EXPECT_GT(expectSameImage(rgb, swapped, false), 1.0);  // and not black
    // and a swap is no identity: the red and blue channels differ somewhere
    double rb = 0;
    for (const rd::Rgba& a : rgb.pixels) rb += std::fabs(a.r - a.b);
    EXPECT_GT(rb, 1.0);
}

// ColorSamples 1: a ray's weight is two floats (the channel, alpha) instead of four. A
// grey scene (every colour one value, shaders that write no RGB literal) gives the RGB
// render of the same greys: eye, shadow, mirror and glass (trace) and continuation rays,
// a pool of 256 rays whose spawned rays spill and come back.
TEST(ColorSamples, OneChannelRaysCarryTwoFloats) {
    auto scene = [](bool oneChannel) {
        auto c = [&](const char* v) {
            return std::string("[") + v + (oneChannel ? "" : std::string(" ") + v + " " + v) + "]";
        };
        rd::RenderSettings small;
        small.poolCapacity = 256;
        return renderRib(
            std::string(oneChannel ? "ColorSamples [1 1 1] [0.333333 0.333333 0.333333]\n" : "") +
                "Format 24 24 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 40\n"
                "WorldBegin\nLightSource \"distantlight\" 1 \"lightcolor\" " + c("0.9") +
                " \"from\" [1 1 -1] \"to\" [0 0 0]\n"
                "LightSource \"pointlight\" 2 \"lightcolor\" " + c("0.5") + " \"from\" [0 2 2]\n"
                "AttributeBegin\nColor " + c("0.8") + "\nOpacity " + c("0.4") +
                "\nSurface \"plastic\"\nTranslate -0.5 0 4\nSphere 1 -1 1 360\nAttributeEnd\n"
                "AttributeBegin\nSurface \"mirror\"\nTranslate 0.8 0 5\nSphere 1 -1 1 360\nAttributeEnd\n"
                "AttributeBegin\nSurface \"glass\"\nTranslate 0 0 2.5\nSphere 1 -1 1 360\nAttributeEnd\n"
                "AttributeBegin\nColor " + c("0.6") + "\nSurface \"matte\"\n"
                "Polygon \"P\" [-6 -6 8  6 -6 8  6 6 8  -6 6 8]\nAttributeEnd\nWorldEnd\n",
            small);
    };
    Rendered rgb = scene(false), grey = scene(true);
    EXPECT_EQ(grey.stats.features.colors.n, 1);
    // eye, spawned (3 a ray: its continuation and glass's two traced rays), spilled (9)
    // and shadow (2 lights) weights: 8 bytes less each
    EXPECT_EQ(rgb.stats.poolBytesPerRay - grey.stats.poolBytesPerRay, (1u + 3 + 9 + 2) * 8);
    EXPECT_GT(grey.stats.spilledRays, 0u) << grey.stats.spilledRays;  // the spill stack's weights are two floats too
    EXPECT_GT(expectSameImage(rgb, grey, true), 1.0);
}

// An imager works on the film's RGB: under swapped channels, and under six channels that
// repeat RGB's, its RGB literals, colour-space casts and the RIB's colours (given in the
// scene's channels) give the RGB image.
TEST(ColorSamples, ImagersWorkOnTheFilmsRgb) {
    const char* six =
        "ColorSamples [0.5 0 0 0 0.5 0 0 0 0.5 0.5 0 0 0 0.5 0 0 0 0.5] "
        "[1 0 0 1 0 0  0 1 0 0 1 0  0 0 1 0 0 1]\n";
    for (const char* imager : {"Imager \"background\" \"bgcolor\" ", "Imager \"cstint\" "}) {
        // mode 0: RGB, 1: red and blue swapped, 2: six channels
        auto scene = [&](int mode) {
            const bool bg = std::string(imager).find("background") != std::string::npos;
            const char* bgcolor[] = {"[0.2 0.4 0.6]", "[0.6 0.4 0.2]",
                                     "[0.2 0.4 0.6 0.2 0.4 0.6]"};
            const char* color[] = {"[0.9 0.8 0.3]", "[0.3 0.8 0.9]",
                                   "[0.9 0.8 0.3 0.9 0.8 0.3]"};
            const char* samples[] = {
                "", "ColorSamples [0 0 1 0 1 0 1 0 0] [0 0 1 0 1 0 1 0 0]\n", six};
            return renderRib(
                shaderPath() + samples[mode] + imager + (bg ? bgcolor[mode] : "") +
                "\nFormat 16 16 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                "WorldBegin\nColor " +
                color[mode] +
                "\nSurface \"constant\"\nTranslate 0 0 5\nSphere 0.6 -0.6 0.6 "
                "360\nWorldEnd\n");
        };
        SCOPED_TRACE(imager);
        Rendered rgb = scene(0), swapped = scene(1), wide = scene(2);
        EXPECT_GT(expectSameImage(rgb, swapped, false), 1.0);
        EXPECT_GT(expectSameImage(rgb, wide, false), 1.0);
        EXPECT_NE(rgb.at(0, 0).r, rgb.at(0, 0).b);  // the background is coloured
    }
}

// Four channels, the fourth showing yellow; RGB comes in as the first three.
const std::string kFour =
    "ColorSamples [1 0 0  0 1 0  0 0 1  0.5 0.5 0] [1 0 0 0  0 1 0 0  0 0 1 0]\n";

// More than three channels (rsl_abi.h COLOURS: float8 and float16 colours, ray weights of
// 8 and 16 floats): 6 and 12 channels that are RGB's repeated (channel i shows RGB's
// i % 3, with 1/2 or 1/4 of it) give the RGB image - lights, RGB literals and defaults,
// colour-space casts, transparency, traced rays.
TEST(ColorSamples, SixAndTwelveChannelsGiveTheRgbImage) {
    const Rendered rgb = litScene("", [](const char* r, const char* g, const char* b) {
        return std::string("[") + r + " " + g + " " + b + "]";
    });
    for (int n : {6, 12}) {
        SCOPED_TRACE(std::to_string(n) + " channels");
        std::string toRgb, fromRgb;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 3; ++j)
                toRgb += (i % 3 == j ? (n == 6 ? " 0.5" : " 0.25") : " 0");
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < n; ++i) fromRgb += (i % 3 == j ? " 1" : " 0");
        const Rendered wide =
            litScene("ColorSamples [" + toRgb + "] [" + fromRgb + "]\n",
                     [&](const char* r, const char* g, const char* b) {
                         std::string v = "[";
                         for (int i = 0; i < n / 3; ++i)
                             v += std::string(" ") + r + " " + g + " " + b;
                         return v + "]";
                     });
        EXPECT_EQ(wide.stats.features.colors.n, n);
        EXPECT_EQ(wide.stats.shadeNegative, 0u);
        // each weight (eye, spawned, spilled, shadow) is 8 or 16 floats instead of 4
        EXPECT_GT(wide.stats.poolBytesPerRay, rgb.stats.poolBytesPerRay);
        EXPECT_GT(expectSameImage(rgb, wide, false), 1.0);
    }
}

// Four channels where the fourth shows yellow: a surface reflecting channels 1 and 3 lit
// by a light of channels 0 and 3 shows the fourth's yellow alone, (0.5, 0.5, 0); taken in
// RGB (green + yellow times red + yellow) it would be (0.75, 0.75, 0). Coverage is the
// opacity's mean over the four channels.
TEST(ColorSamples, FourChannelsMultiplyAsChannels) {
    const std::string lit =
        "LightSource \"ambientlight\" 1 \"lightcolor\" [1 0 0 1]\n"
        "Color [0 1 0 1]\nSurface \"matte\" \"Ka\" 1 \"Kd\" 0\n";
    Rendered opaque = flat(kFour, lit);
    EXPECT_NEAR(opaque.at(4, 4).r, 0.5f, 1e-6f);
    EXPECT_NEAR(opaque.at(4, 4).g, 0.5f, 1e-6f);
    EXPECT_NEAR(opaque.at(4, 4).b, 0.0f, 1e-6f);
    EXPECT_NEAR(opaque.at(4, 4).a, 1.0f, 1e-6f);
    const std::vector<std::string> names = opaque.stats.features.names();
    EXPECT_NE(std::find(names.begin(), names.end(), "color_samples_4"), names.end());
    // Opacity [1 1 0.5 0.5]: Ci = Os Cs Ka ambient = (0, 0, 0, 0.5), alpha 0.75
    Rendered half = flat(kFour, "Opacity [1 1 0.5 0.5]\n" + lit);
    EXPECT_NEAR(half.at(4, 4).r, 0.25f, 1e-6f);
    EXPECT_NEAR(half.at(4, 4).g, 0.25f, 1e-6f);
    EXPECT_NEAR(half.at(4, 4).a, 0.75f, 1e-6f);
    // a shader's RGB literal comes in through RGBn: red times green is black here
    expectGrey(flat(kFour, "Surface \"csproduct\"\n"), 0.0f, 1e-6f, "csproduct");
}

// Cs given per vertex, per corner of a quadric, or as a quadric's constant keeps the four
// channels (float8 per-vertex colours): lit as in FourChannelsMultiplyAsChannels it shows
// (0.5, 0.5, 0), where RGB would give (0.75, 0.75, 0).
TEST(ColorSamples, PrimitiveColoursKeepTheirChannels) {
    const std::string lit =
        "LightSource \"ambientlight\" 1 \"lightcolor\" [1 0 0 1]\n"
        "Surface \"matte\" \"Ka\" 1 \"Kd\" 0\n";
    const std::string cs4 = "0 1 0 1  0 1 0 1  0 1 0 1  0 1 0 1";
    auto render = [&](const std::string& geometry) {
        return renderRib(shaderPath() + kFour + kFlat + "WorldBegin\n" + lit + geometry +
                         "WorldEnd\n");
    };
    for (const std::string& geometry :
         {"Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5] \"Cs\" [" + cs4 + "]\n",
          std::string(
              "Translate 0 0 5\nSphere 3 -3 3 360 \"constant color Cs\" [0 1 0 1]\n"),
          "Translate 0 0 5\nSphere 3 -3 3 360 \"varying color Cs\" [" + cs4 + "]\n"}) {
        SCOPED_TRACE(geometry);
        const Rendered img = render(geometry);
        EXPECT_NEAR(img.at(4, 4).r, 0.5f, 1e-6f);
        EXPECT_NEAR(img.at(4, 4).g, 0.5f, 1e-6f);
        EXPECT_NEAR(img.at(4, 4).b, 0.0f, 1e-6f);
    }
    // a vertex Os of four channels: coverage is its mean
    const Rendered half =
        render("Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5] \"Cs\" [" + cs4 +
               "] \"Os\" [1 1 0.5 0.5  1 1 0.5 0.5  1 1 0.5 0.5  "
               "1 1 0.5 0.5]\n");
    EXPECT_NEAR(half.at(4, 4).a, 0.75f, 1e-6f);
    EXPECT_NEAR(half.at(4, 4).r, 0.25f, 1e-6f);
}

// A shader's colour parameter given per point keeps the n channels (ceil(n / 3) values a
// point, rsl_abi.h PER-POINT PARAMETERS), at 4, 7, 12 and 15 channels (two pieces, the
// last lane of float8, four pieces, five): channel i of "tint" is (i + 1) / 16 on the
// left face and half that on the right, given per face ("uniform" over a two-face
// PointsPolygons) and per corner of an exact sphere, and once for a whole polygon
// ("constant"); nRGB takes channel i to (1, i / n, (i / n)^2), so a channel lost or
// moved changes the sums the film shows. (As before, per-point values taken as RGB
// keep three dimensions of the n, and the constant one was ignored with a warning.)
TEST(ColorSamples, PerPointParametersKeepTheirChannels) {
    for (int n : {4, 7, 12, 15}) {
        SCOPED_TRACE(std::to_string(n) + " channels");
        std::string nrgb, rgbn, one, left, right;
        double want[3] = {0, 0, 0};
        for (int i = 0; i < n; ++i) {
            const std::string fs = std::to_string(double(i) / n);  // the RIB's digits
            const double f = std::stod(fs), t = (i + 1) / 16.0;
            nrgb += " 1 " + fs + " " + std::to_string(f * f);
            one += " 1";
            left += " " + std::to_string(t);
            right += " " + std::to_string(t / 2);
            want[0] += t, want[1] += t * f, want[2] += t * std::stod(std::to_string(f * f));
        }
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < n; ++i) rgbn += i == j ? " 1" : " 0";
        const std::string head = shaderPath() + "ColorSamples [" + nrgb + "] [" + rgbn + "]\n" +
                                 kFlat + "WorldBegin\nLightSource \"ambientlight\" 1 " +
                                 "\"lightcolor\" [" + one + "]\nSurface \"csparam\"\n";
        const Rendered faces = renderRib(
            head + "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                   "\"P\" [-2 -2 5  0 -2 5  2 -2 5  -2 2 5  0 2 5  2 2 5] "
                   "\"uniform color tint\" [" + left + right + "]\nWorldEnd\n");
        const Rendered sphere =
            renderRib(head + "Translate 0 0 5\nSphere 3 -3 3 360 \"varying color tint\" [" +
                      left + left + left + left + "]\nWorldEnd\n");
        // one value for the whole primitive: the instance's parameter value
        const Rendered constant =
            renderRib(head + "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5] "
                             "\"constant color tint\" [" + right + "]\nWorldEnd\n");
        const Rendered* img[4] = {&faces, &faces, &sphere, &constant};
        const int x[4] = {1, 6, 4, 4};
        const double scale[4] = {1, 0.5, 1, 0.5};
        const char* what[4] = {"left face", "right face", "sphere", "constant"};
        for (int k = 0; k < 4; ++k) {
            const rd::Rgba& got = img[k]->at(x[k], 4);
            EXPECT_NEAR(got.r, scale[k] * want[0], 1e-5 * want[0]) << what[k];
            EXPECT_NEAR(got.g, scale[k] * want[1], 1e-5 * want[1]) << what[k];
            EXPECT_NEAR(got.b, scale[k] * want[2], 1e-5 * want[2]) << what[k];
        }
    }
}

// Every kind of geometry carries a per-point colour parameter's pieces (a colour of six
// channels in two values a point, of fifteen in five): polygons (varying, facevarying, a
// general polygon), patches (bilinear varying, bicubic vertex, a mesh's uniform values),
// a NuPatch, subdivision meshes (vertex values refined to the limit, uniform per face),
// curves, points and a sphere's corners. In 6 and 15 channels, three to each piece p of
// m: a value is RGB times p + 1 in piece p, and nRGB takes piece p's channels to RGB
// times 1 / (m (p + 1)), so the image is the RGB one (within 1e-6) only if every piece
// arrives in its place.
TEST(ColorSamples, PerPointParametersOnEveryGeometryGiveTheRgbImage) {
    auto num = [](double x) {
        char b[32];
        std::snprintf(b, sizeof b, "%.9g", x);
        return std::string(b);
    };
    auto scene = [&](const std::string& colorSamples, int pieces) {
        int k = 0;  // the next value's colour: a fixed spread over [0, 1]
        auto tints = [&](int count) {
            std::string v = "[";
            for (int i = 0; i < count; ++i, ++k)
                for (int p = 0; p < pieces; ++p)
                    for (double c : {(k * 7 % 11) / 10.0, (k * 5 % 13) / 12.0, (k * 3 % 7) / 6.0})
                        v += " " + num(c * (p + 1));
            return v + "]";
        };
        std::string one = "[";
        for (int r = 0; r < 3 * pieces; ++r) one += " 1";
        one += "]";
        auto at = [](int cell, const std::string& geometry) {  // a 4 x 3 grid of cells
            return "AttributeBegin\nTranslate " + std::to_string(-0.75 + 0.5 * (cell % 4)) + " " +
                   std::to_string(-0.5 + 0.5 * (cell / 4)) + " 2\nScale 0.2 0.2 0.2\n" +
                   geometry + "\nAttributeEnd\n";
        };
        const std::string quad = "\"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] ";
        std::string bicubic;
        for (int b = 0; b < 4; ++b)
            for (int a = 0; a < 4; ++a)
                bicubic += std::to_string(-1 + 2 * a / 3.0) + " " + std::to_string(-1 + 2 * b / 3.0) + " 0 ";
        const std::string cage =
            "SubdivisionMesh \"catmull-clark\" [4 4 4 4] [0 1 4 3  1 2 5 4  3 4 7 6  4 5 8 7] "
            "[\"interpolateboundary\"] [0 0] [] [] "
            "\"P\" [-1 -1 0  0 -1 0  1 -1 0  -1 0 0  0 0 0  1 0 0  -1 1 0  0 1 0  1 1 0] ";
        std::string world =
            at(0, "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0] \"varying color tint\" " +
                      tints(4)) +
            at(1, "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] "
                  "\"P\" [-1 -1 0  0 -1 0  1 -1 0  -1 1 0  0 1 0  1 1 0] "
                  "\"facevarying color tint\" " + tints(8)) +
            at(2, "GeneralPolygon [4 4] \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0  "
                  "-0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0  0.5 -0.5 0] \"varying color tint\" " +
                      tints(8)) +
            at(3, "Patch \"bilinear\" " + quad + "\"varying color tint\" " + tints(4)) +
            at(4, "Patch \"bicubic\" \"P\" [" + bicubic + "] \"vertex color tint\" " + tints(16)) +
            at(5, "PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" "
                  "\"P\" [-1 -1 0  0 -1 0  1 -1 0  -1 1 0  0 1 0  1 1 0] "
                  "\"uniform color tint\" " + tints(2)) +
            at(6, "NuPatch 3 2 [0 0 1 3 3] 0 3 2 2 [0 0 1 1] 0 1 "
                  "\"P\" [-1 -1 0  0 -1 0  1 -1 0  -1 1 0  0 1 0  1 1 0] "
                  "\"varying color tint\" " + tints(6)) +
            at(7, cage + "\"vertex color tint\" " + tints(9)) +
            at(8, cage + "\"uniform color tint\" " + tints(4)) +
            at(9, "Curves \"linear\" [3] \"nonperiodic\" \"P\" [-1 0 0  0 0 0  1 0 0] "
                  "\"constantwidth\" [1] \"varying color tint\" " + tints(3)) +
            at(10, "Points \"P\" [-0.5 0 0  0.5 0 0] \"constantwidth\" [0.8] "
                   "\"varying color tint\" " + tints(2)) +
            at(11, "Sphere 1 -1 1 360 \"varying color tint\" " + tints(4));
        return renderRib(shaderPath() + colorSamples +
                         "Format 32 24 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                         "WorldBegin\nLightSource \"ambientlight\" 1 \"lightcolor\" " + one +
                         "\nSurface \"csparam\"\n" + world + "WorldEnd\n");
    };
    const Rendered rgb = scene("", 1);
    EXPECT_EQ(rgb.stats.features.pointParams, 1);
    for (int cell = 0; cell < 12; ++cell) {  // each object shows its colours (0.32-1.29)
        const int x = int((-0.75 + 0.5 * (cell % 4) + 4.0 / 3) * 12), y = 18 - 6 * (cell / 4);
        double sum = 0;
        for (int c = 0; c < 3; ++c) sum += rgb.mean(c, x - 2, y - 2, x + 3, y + 3);
        EXPECT_GT(sum, 0.2) << "cell " << cell;
    }
    for (int n : {6, 15}) {
        SCOPED_TRACE(std::to_string(n) + " channels");
        std::string toRgb, fromRgb;
        const int m = n / 3;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 3; ++j)
                toRgb += " " + (i % 3 == j ? num(1.0 / (m * (i / 3 + 1))) : std::string("0"));
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < n; ++i) fromRgb += (i % 3 == j ? " 1" : " 0");
        const Rendered wide = scene("ColorSamples [" + toRgb + "] [" + fromRgb + "]\n", m);
        EXPECT_EQ(wide.stats.features.pointParams, n / 3);  // values a point (RGB: 1)
        EXPECT_GT(expectSameImage(rgb, wide, false), 100.0);
    }
}

// Metamers (examples/metamers.rib): six channels, two to each of red, green and blue. A
// surface reflecting channels 0, 2, 4 and one reflecting 1, 3, 5 are the same grey in RGB
// and under a light even in every channel, but under a light of channels 0, 2, 4 alone
// the second is black. Taken in RGB, as before, the two would match under both lights.
TEST(ColorSamples, MetamersMatchUnderAnEvenLightOnly) {
    const std::string six = "ColorSamples [0.5 0 0  0.5 0 0  0 0.5 0  0 0.5 0  0 0 0.5  0 0 0.5] "
                            "[1 1 0 0 0 0  0 0 1 1 0 0  0 0 0 0 1 1]\n";
    auto patch = [&](const char* light, const char* surface) {
        return flat(six, std::string("LightSource \"ambientlight\" 1 \"lightcolor\" ") + light +
                             "\nColor " + surface + "\nSurface \"matte\" \"Ka\" 1 \"Kd\" 0\n");
    };
    const char* even = "[1 1 1 1 1 1]";
    const char* spiky = "[1 0 1 0 1 0]";
    expectGrey(patch(even, "[1 0 1 0 1 0]"), 0.5f, 1e-6f, "A, even light");
    expectGrey(patch(even, "[0 1 0 1 0 1]"), 0.5f, 1e-6f, "B, even light");
    expectGrey(patch(spiky, "[1 0 1 0 1 0]"), 0.5f, 1e-6f, "A, spiky light");
    expectGrey(patch(spiky, "[0 1 0 1 0 1]"), 0.0f, 1e-6f, "B, spiky light");
}
