// trace_aov_test.cpp: the parts of shader AOVs that come back along traced rays
// (cl/lib/ray_aovs.clh): `output color refl = Kr * trace(P, R)` gets what its ray
// brings back, emission and light (shadowed) alike, whether or not Ci takes it too; and
// a float output of occlusion() equals the same occlusion() in Ci.
#include <gtest/gtest.h>

#include <array>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const char* kShaders[][2] = {
    // refl in Ci and in the AOV
    {"aovrefl", R"(
surface aovrefl(output varying color refl = 0; float Kr = 0.5;) {
    normal Nf = faceforward(normalize(N), I);
    refl = Kr * trace(P, reflect(normalize(I), Nf));
    Ci = Cs * diffuse(Nf) + refl;
    Oi = Os;
}
)"},
    // refl in the AOV alone: Ci takes nothing from the traced ray
    {"aovreflonly", R"(
surface aovreflonly(output varying color refl = 0; float Kr = 0.5;) {
    normal Nf = faceforward(normalize(N), I);
    refl = Kr * trace(P, reflect(normalize(I), Nf));
    Ci = Cs;
    Oi = Os;
}
)"},
    {"aovocc", R"(
surface aovocc(output varying float occ = 0;) {
    normal Nf = faceforward(normalize(N), I);
    occ = occlusion(P, Nf, 16);
    Ci = color(occ);
    Oi = 1;
}
)"}};

std::string shaderDir(const std::string& name) {
    return rd::test::shaderFolder(name, kShaders);
}

// Orthographic, 1/16 unit a pixel: x = -2 + (px + 0.5) / 16, y = 1 - (py + 0.5) / 16. A
// plane of Cs (0.2, 0.4, 0.6) over [-1.5, 1.5] x [-0.75, 0.75] at z = 0 with `shader`,
// facing the camera; its reflected rays go straight back (-z). At z = -1, hidden from the
// camera but not from traced rays: a constant square of (1, 0.5, 0.25) over x in
// [-1, -0.5] (pixels [16, 24)), and a matte one of Cs (0.25, 0.5, 1) over x in [0.5, 1]
// (pixels [40, 48)), y in [-0.25, 0.25] (pixels [12, 20)). A distant light toward -z
// lights the squares' sides the reflected rays meet (cos 1, matte: its Cs) and the
// plane's back; the plane casts no shadow unless `planeShadows`, and then the matte
// square is dark.
std::string scene(const std::string& dir, const std::string& shader, bool planeShadows) {
    return "Option \"searchpath\" \"shader\" [\"" + dir +
           ":&\"]\nFormat 64 32 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
           "ScreenWindow -2 2 -1 1\nTranslate 0 0 5\nWorldBegin\n"
           "LightSource \"distantlight\" 1 \"from\" [0 0 1] \"to\" [0 0 0]\n"
           "AttributeBegin\nSurface \"" +
           shader + "\"\nColor [0.2 0.4 0.6]\n" +
           (planeShadows ? "" : "Attribute \"visibility\" \"transmission\" 0\n") +
           "Polygon \"P\" [-1.5 -0.75 0  1.5 -0.75 0  1.5 0.75 0  -1.5 0.75 0]\n"
           "AttributeEnd\n"
           "Attribute \"visibility\" \"camera\" 0 \"trace\" 1\n"
           "AttributeBegin\nSurface \"constant\"\nColor [1 0.5 0.25]\n"
           "Polygon \"P\" [-1 -0.25 -1  -0.5 -0.25 -1  -0.5 0.25 -1  -1 0.25 -1]\n"
           "AttributeEnd\n"
           "AttributeBegin\nSurface \"matte\"\nColor [0.25 0.5 1]\n"
           "Polygon \"P\" [0.5 -0.25 -1  1 -0.25 -1  1 0.25 -1  0.5 0.25 -1]\n"
           "AttributeEnd\nWorldEnd\n";
}

// Mean of channel `name` (an AOV's, else the image's R, G, B: "Ci.R" ...) over pixels
// [x0, x1) x [y0, y1).
double mean(const Rendered& r, const std::string& name, int x0, int y0, int x1, int y1) {
    std::vector<rd::Channel> channels;
    const std::string aov = name.substr(0, name.find('.'));
    if (aov != "Ci") channels = r.film.aovChannels(aov);
    for (const rd::Channel& c : channels)
        if (c.name == name) {
            double sum = 0;
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) sum += c.values[size_t(y) * r.width + x];
            return sum / ((x1 - x0) * (y1 - y0));
        }
    if (aov == "Ci") {
        const int k = name.back() == 'R' ? 0 : name.back() == 'G' ? 1 : 2;
        return r.mean(k, x0, y0, x1, y1);
    }
    ADD_FAILURE() << "no channel " << name;
    return -1;
}

// The regions: pixels inside the constant square's reflection, the matte one's, and the
// plane's middle, whose rays escape.
using Box = std::array<int, 4>;
constexpr Box kLeft{17, 13, 23, 19}, kRight{41, 13, 47, 19}, kMiddle{28, 8, 36, 24};
double mean(const Rendered& r, const std::string& name, const Box& box) {
    return mean(r, name, box[0], box[1], box[2], box[3]);
}

// The scene rendered with the AOV `aov` (shaders in a scratch folder of their own).
Rendered renderAov(const std::string& aov, const std::string& folder,
                   const std::string& shader, bool planeShadows) {
    rd::RenderSettings settings;
    settings.extraAovs = {aov};
    return renderRib(scene(shaderDir(folder), shader, planeShadows), settings);
}

}  // namespace

// refl is Kr times what its ray brings back: the constant square's emission, the matte
// square's light (a shadow ray below the traced one), nothing where the ray escapes; the
// image holds the same in Ci.
TEST(TraceAovs, AnOutputGetsWhatItsTracedRayBringsBack) {
    const Rendered r = renderAov("refl", "trace_aov", "aovrefl", false);
    EXPECT_NEAR(mean(r, "refl.R", kLeft), 0.5, 1e-5);
    EXPECT_NEAR(mean(r, "refl.G", kLeft), 0.25, 1e-5);
    EXPECT_NEAR(mean(r, "refl.B", kLeft), 0.125, 1e-5);
    EXPECT_NEAR(mean(r, "refl.R", kRight), 0.125, 1e-5);
    EXPECT_NEAR(mean(r, "refl.B", kRight), 0.5, 1e-5);
    EXPECT_NEAR(mean(r, "refl.G", kMiddle), 0.0, 1e-6);
    for (const char* c :
         {"R", "G", "B"}) {  // the plane's own light is behind it: Ci = refl
        EXPECT_NEAR(mean(r, std::string("Ci.") + c, kLeft),
                    mean(r, std::string("refl.") + c, kLeft), 1e-5);
        EXPECT_NEAR(mean(r, std::string("Ci.") + c, kRight),
                    mean(r, std::string("refl.") + c, kRight), 1e-5);
    }
    EXPECT_NE(r.stats.program.options.find("-DRT_RAY_AOVS"), std::string::npos)
        << r.stats.program.options;

    // Without the AOV the kernels carry no AOV weights.
    const Rendered plain = renderRib(scene(shaderDir("trace_aov"), "aovrefl", false));
    EXPECT_EQ(plain.stats.program.options.find("RT_RAY_AOVS"), std::string::npos);
    EXPECT_NEAR(mean(plain, "Ci.B", kRight), 0.5, 1e-5);
}

// When Ci takes nothing from trace(), the ray is traced for the AOV alone: refl as
// before, the image Cs.
TEST(TraceAovs, ARayIsTracedForTheAovAlone) {
    const Rendered r = renderAov("refl", "trace_aov_only", "aovreflonly", false);
    EXPECT_NEAR(mean(r, "refl.R", kLeft), 0.5, 1e-5);
    EXPECT_NEAR(mean(r, "refl.B", kRight), 0.5, 1e-5);
    EXPECT_NEAR(mean(r, "Ci.R", kLeft), 0.2, 1e-6);
    EXPECT_NEAR(mean(r, "Ci.B", kRight), 0.6, 1e-6);
}

// The matte square's light rides on a shadow ray below the traced one: when the plane
// casts its shadow over the square, refl has none of it (the constant square's emission
// stays).
TEST(TraceAovs, TheLightBelowATracedRayIsShadowed) {
    const Rendered r = renderAov("refl", "trace_aov_shadow", "aovreflonly", true);
    EXPECT_NEAR(mean(r, "refl.R", kLeft), 0.5, 1e-5);
    EXPECT_NEAR(mean(r, "refl.B", kRight), 0.0, 1e-6);
}

// A float output of occlusion() (visibility rays: a part counts when the ray escapes)
// equals the image, whose Ci is the same occlusion(), region by region; the squares
// occlude some of the plane's hemisphere. (Ci = occlusion() gives its rays weights below
// zero, 1 less a part for each that escapes: they were refused as negative shader
// results, and the image was 1.)
TEST(TraceAovs, AnOcclusionOutputIsTheOcclusion) {
    const Rendered r = renderAov("occ", "trace_aov_occ", "aovocc", false);
    for (const Box& box : {kLeft, kRight, kMiddle})
        EXPECT_NEAR(mean(r, "occ", box), mean(r, "Ci.R", box), 1e-5);
    EXPECT_GT(mean(r, "occ", kLeft), 0.05);
    EXPECT_LT(mean(r, "occ", kLeft), 0.95);
}
