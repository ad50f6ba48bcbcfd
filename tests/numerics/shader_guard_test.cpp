// shader_guard_test.cpp: case 5, shaders that produce NaN, Inf, huge (1e30) or denormal
// radiance, or such weights for traced rays, shadow rays and continuations, or a
// negative opacity: none of it reaches the film (which stays finite), and every fault is
// counted (--stats). A negative colour is no fault: it reaches the film as it is.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cl/include/numerics_slots.h"
#include "cl/include/compat.h"
#include "numerics_util.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"

using namespace rd::numerics;

namespace {

// bad(a, b, where): the value a / b (computed on the device) as the emission (where 0),
// the weight of a trace() (1), the coefficient of a light (2), or the opacity (3).
const char* kBadShader =
    "surface bad(float a = 1, b = 1, where = 0;) {\n"
    "    color v = color(a / b);\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    Oi = 1;\n"
    "    if (where == 3) Oi = v;\n"
    "    Ci = (where == 0 ? v : color(0)) + (where == 1 ? v : color(0)) * trace(P, reflect(I, Nf))\n"
    "       + (where == 2 ? v : color(0)) * diffuse(Nf);\n"
    "}\n";

std::string shaderDir() {
    std::string dir = rd::test::scratchDir("raydrive_numerics_guard");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/bad.sl") << kBadShader;
    return dir;
}

// The bad shader on the left half of a plane at z = 5, constant 0.5 grey on the right;
// behind the eye a small white constant square that trace() reaches, and a distant
// light at 60 degrees from the normal whose shadow rays pass beside that square.
// veiled: that square lets half through (Opacity 0.5) to a second one behind it, so a
// traced ray goes on through it with half its weight.
std::string scene(double a, double b, int where, bool veiled = false) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "Surface \"bad\" \"a\" %.9g \"b\" %.9g \"where\" %d\n", a,
                  b, where);
    return "Option \"searchpath\" \"shader\" [\"" + shaderDir() + ":&\"]\n" + camera(8, 40, 1) +
           "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0.8660254 -0.5] \"to\" [0 0 0]\n"
           "AttributeBegin\n" + buf +
           "Polygon \"P\" [-50 -50 5  0 -50 5  0 50 5  -50 50 5]\nAttributeEnd\n"
           "AttributeBegin\nSurface \"constant\"\nColor [0.5 0.5 0.5]\n"
           "Polygon \"P\" [0 -50 5  50 -50 5  50 50 5  0 50 5]\nAttributeEnd\n"
           "AttributeBegin\nSurface \"constant\"\n" + (veiled ? "Opacity [0.5 0.5 0.5]\n" : "") +
           squareAtZ(-5.0, 5.0) + "AttributeEnd\n" +
           (veiled ? "AttributeBegin\nSurface \"constant\"\n" + squareAtZ(-6.0, 6.0) +
                         "AttributeEnd\n"
                   : "") +
           "WorldEnd\n";
}

struct Fault {
    const char* name;
    double a, b;
    uint64_t rd::RenderStats::*counter;
};

}  // namespace

// Tolerance 0 (well, 1e-6): a dropped contribution is exactly zero; the left half is
// black with alpha 1 (alpha 0 where the opacity itself was bad), the right half 0.5.
TEST(Numerics, BadShaderResultsNeverReachTheFilm) {
    const Fault faults[] = {{"nan", 0, 0, &rd::RenderStats::shadeNonfinite},
                            {"inf", 1, 0, &rd::RenderStats::shadeNonfinite},
                            {"negative", -1, 1, &rd::RenderStats::shadeNegative},
                            {"huge", 1e30, 1, &rd::RenderStats::shadeHuge},
                            {"denormal", 1e-30, 1e10, &rd::RenderStats::shadeDenormal}};
    const char* whereName[] = {"emission", "trace_weight", "light_weight", "opacity"};
    for (const Fault& f : faults)
        for (int where = 0; where < 4; ++where) {
            // a negative colour is no fault (NegativeColoursReachTheFilm); an opacity is
            if (f.counter == &rd::RenderStats::shadeNegative && where != 3) continue;
            Diagnosed d = renderWithDiagnostics(scene(f.a, f.b, where));
            const rd::test::Rendered& img = d.image;
            ASSERT_EQ(img.pixels.size(), 64u);
            const bool badAlpha = where == 3;  // (a denormal opacity is transparent too)
            double err = allFinite(img) ? 0.0 : INFINITY;
            for (int y = 0; y < 8; ++y)
                for (int x = 0; x < 8; ++x) {
                    const rd::Rgba& p = img.at(x, y);
                    const double c = x < 4 ? 0.0 : 0.5, alpha = x < 4 && badAlpha ? 0.0 : 1.0;
                    err = std::fmax(err, std::fmax(std::fabs(p.r - c), std::fabs(p.a - alpha)));
                }
            char name[64];
            std::snprintf(name, sizeof name, "bad_shader_%s_%s", f.name, whereName[where]);
            EXPECT_TRUE(report(name, 1e-6, err));
            EXPECT_GT(img.stats.*f.counter, 0u) << name << " must be counted";
            EXPECT_EQ(img.stats.nonfiniteSamples, 0u) << name;
            if (f.counter != &rd::RenderStats::shadeDenormal) {
                EXPECT_EQ(countOf(d.messages, "left out of the image"), 1) << d.messages;
            }
        }
}

// A negative emission, trace() weight or light coefficient is the positive one's image
// negated, as PRMan writes it (a shader showing a coordinate, a light that takes light
// away): nothing counted, no warning. Tolerance 1e-6 (the same arithmetic, one sign).
// The veiled case: the traced ray's weight, negative, goes on through a surface that
// lets half through (a continuation once dropped as "nothing left" by its largest channel).
TEST(Numerics, NegativeColoursReachTheFilm) {
    const char* whereName[] = {"emission", "trace_weight", "light_weight", "veiled_trace_weight"};
    for (int c = 0; c < 4; ++c) {
        const int where = c == 3 ? 1 : c;
        Diagnosed pos = renderWithDiagnostics(scene(1, 1, where, c == 3));
        Diagnosed neg = renderWithDiagnostics(scene(-1, 1, where, c == 3));
        ASSERT_EQ(neg.image.pixels.size(), 64u);
        double err = allFinite(neg.image) ? 0.0 : INFINITY, largest = 0;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                const rd::Rgba &p = pos.image.at(x, y), &n = neg.image.at(x, y);
                const double want = x < 4 ? -p.r : 0.5;
                err = std::fmax(err, std::fmax(std::fabs(n.r - want), std::fabs(n.a - 1.0)));
                if (x < 4) largest = std::fmax(largest, p.r);
            }
        char name[64];
        std::snprintf(name, sizeof name, "negative_%s", whereName[c]);
        EXPECT_TRUE(report(name, 1e-6, err));
        EXPECT_GT(largest, 0.2) << name << ": the positive image shows the left half";
        const auto& st = neg.image.stats;
        EXPECT_EQ(st.shadeNonfinite + st.shadeNegative + st.shadeHuge, 0u) << name;
        EXPECT_EQ(countOf(neg.messages, "left out of the image"), 0) << neg.messages;
    }
}

// A well-behaved scene counts nothing and warns about nothing.
TEST(Numerics, GoodShadersCountNoFaults) {
    Diagnosed d = renderWithDiagnostics(scene(1, 2, 2));
    const auto& st = d.image.stats;
    EXPECT_EQ(st.shadeNonfinite + st.shadeNegative + st.shadeHuge + st.shadeDenormal, 0u);
    EXPECT_EQ(d.warnings, 0) << d.messages;
    EXPECT_NEAR(d.image.at(1, 4).r, 0.25, 1e-6);  // 0.5 * diffuse = 0.5 cos 60
}

// A shader loop that never ends (a float counter that sticks at 2^24, a while (1) whose break
// is never reached, a for (;;) in a function, a while in a light's solar block)
// is cut after RSL_MAX_LOOP_ITERATIONS passes, so the render ends, and its points are
// counted and reported. Each loop leaves with its value at the cut: Ci is exact.
TEST(Numerics, ShaderLoopThatNeverEndsIsCutAndReported) {
    const std::string dir = rd::test::scratchDir("raydrive_numerics_loops");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/stuck.sl")
        << "float spin() { float n = 0; for (;;) { n += 1; } return n; }\n"
           "surface stuck() {\n"
           "    float x = 0, y = 0;\n"
           "    while (x >= 0) { x += 1; }\n"  // would stick at 2^24: cut at 65536
           "    while (1) { y += 1; if (y < 0) break; }\n"
           "    Ci = color(x == 65536 ? 0.25 : 1, y == 65536 ? 0.5 : 1, spin() / 65536);\n"
           "    Oi = 1;\n}\n";
    std::ofstream(dir + "/stucklight.sl")
        << "light stucklight() {\n"
           "    solar(vector(0, 0, 1), 0) { float k = 0; while (k < 1) { k = k * 1; } Cl = 0.1; }\n}\n";
    const std::string rib = "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                            camera(8, 40, 1) + "WorldBegin\nLightSource \"stucklight\" 1\n"
                            "Surface \"stuck\"\n" + squareAtZ(5.0, 50.0) + "WorldEnd\n";
    Diagnosed d = renderWithDiagnostics(rib);
    const rd::test::Rendered& img = d.image;
    ASSERT_EQ(img.pixels.size(), 64u);
    double err = 0;
    for (const rd::Rgba& p : img.pixels)
        err = std::fmax(err, std::fmax(std::fabs(p.r - 0.25),
                                       std::fmax(std::fabs(p.g - 0.5), std::fabs(p.b - 1.0))));
    EXPECT_TRUE(report("shader_loop_cut", 1e-6, err));
    EXPECT_GE(img.stats.shaderLoopsCut, 64u) << "every shaded point";
    EXPECT_EQ(countOf(d.messages, "shader loop ran past 65536 passes"), 1) << d.messages;
}

// rt_sanitize itself (cl/lib/numerics.clh) on edge values, through a probe kernel: its
// fast path (every channel zero or a normal number up to RT_MAX_RADIANCE) passes them
// unchanged; anything else takes the checks: the faulty part (colour or alpha) zeroed,
// denormals flushed, each fault counted once.
TEST(Numerics, SanitizeKeepsGoodValuesAndCountsEachFault) {
    const rd::ClContext& ctx = rd::test::testContext();
    const std::string probe =
        "#include \"numerics.clh\"\n"
        "__kernel void sanitize_probe(uint n, __global float4* v, __global uint* counters,\n"
        "                             __global uint* active) {\n"
        "    uint i = get_global_id(0);\n"
        "    if (i < n) v[i] = rt_sanitize(v[i], counters);\n}\n";
    rd::Program program(ctx, rd::assembleClSource({"sanitize_probe.cl"},
                                                  {{"sanitize_probe.cl", probe}}),
                        "-cl-std=CL1.2");
    rd::Profiler prof(ctx);
    rd::Kernel k(ctx, program.get(), "sanitize_probe", prof);
    const float inf = INFINITY, nan = NAN, fmin = FLT_MIN;
    struct Case {
        rt_float4 in, out;
        int counter;  // RT_NUM_* slot it adds one to, or -1
    } cases[] = {
        {{0.5f, 1.0f, 0.0f, -0.0f}, {0.5f, 1.0f, 0.0f, -0.0f}, -1},
        {{fmin, 1e10f, 0.0f, 1.0f}, {fmin, 1e10f, 0.0f, 1.0f}, -1},
        {{1e-40f, 1.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 1.0f, 0.0f}, RT_NUM_DENORMAL},
        {{-1.0f, 1.0f, -0.5f, 1.0f}, {-1.0f, 1.0f, -0.5f, 1.0f}, -1},  // a colour may be < 0
        {{0.5f, 0.5f, 0.5f, -1.0f}, {0.5f, 0.5f, 0.5f, 0.0f}, RT_NUM_NEGATIVE},  // alpha not
        {{-2e10f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f, 1.0f}, RT_NUM_HUGE},
        {{-1e-40f, -1.0f, 1.0f, 1.0f}, {0.0f, -1.0f, 1.0f, 1.0f}, RT_NUM_DENORMAL},
        {{1.0f, 1.0f, 1.0f, nan}, {1.0f, 1.0f, 1.0f, 0.0f}, RT_NUM_NONFINITE},
        {{2e10f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f, 1.0f}, RT_NUM_HUGE},
        {{0.0f, inf, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f, 1.0f}, RT_NUM_NONFINITE},
    };
    for (const Case& c : cases) {
        rd::DeviceBuffer<rt_float4> v(ctx, std::vector<rt_float4>{c.in}, CL_MEM_READ_WRITE);
        rd::DeviceBuffer<uint32_t> counters(ctx, RT_NUM_COUNTERS);
        counters.fillZero();
        k.launch(1, cl_uint(1), v, counters);
        const rt_float4 got = v.download()[0];
        const std::vector<uint32_t> n = counters.download();
        const float* g = &got.x;
        const float* want = &c.out.x;
        for (int ch = 0; ch < 4; ++ch) {
            EXPECT_EQ(g[ch], want[ch]) << "channel " << ch << " of case " << (&c - cases);
            EXPECT_EQ(std::signbit(g[ch]), std::signbit(want[ch])) << "case " << (&c - cases);
        }
        for (int s = 0; s < RT_NUM_COUNTERS; ++s)
            EXPECT_EQ(n[size_t(s)], s == c.counter ? 1u : 0u)
                << "counter " << s << " of case " << (&c - cases);
    }
}
