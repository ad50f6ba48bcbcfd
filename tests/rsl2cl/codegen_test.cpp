// codegen_test.cpp: the code generator end to end on PoCL: every standard shader builds,
// the classic surfaces give their closed forms in base and light modes, the ray-traced
// ones record the right rays and coefficients, and the lights give the expected Cl, L.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "testshade.h"

namespace {

using V3 = std::array<float, 3>;
V3 v3(const float* p) { return {p[0], p[1], p[2]}; }
float dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 add(V3 a, V3 b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 mul(V3 a, float s) { return {a[0] * s, a[1] * s, a[2] * s}; }
V3 mulv(V3 a, V3 b) { return {a[0] * b[0], a[1] * b[1], a[2] * b[2]}; }
V3 norm(V3 a) { return mul(a, 1.0f / std::sqrt(dot(a, a))); }

void expectNear(const float* got, V3 want, float tol, const std::string& what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], tol * std::max(1.0f, std::fabs(want[c])))
            << what << " channel " << c;
}

std::string shaderPath(const std::string& n) {
    if (n == "spd") return std::string(RSL2CL_TEST_DATA) + "/spd.sl";
    return std::string(RSL2CL_SHADER_DIR) + "/" + n + ".sl";
}

#define REQUIRE_DEVICE() \
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device"

// ---- (b) every standard shader compiles to OpenCL C that builds ---------------------
class CodegenShader : public ::testing::TestWithParam<std::string> {};

TEST_P(CodegenShader, BuildsOnDevice) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath(GetParam()), &err)) << err;
    EXPECT_EQ(sh.shader.functionName, "rsl_" + sh.shader.kind + "_" + GetParam());
    ts::Scene sc;
    sc.lights.push_back({{0, 0, 1}, {1, 1, 1}});
    std::string log;
    ASSERT_TRUE(sh.buildOnDevice(sc, &log)) << log;
    auto out = sh.run(ts::grid(4), sc);
    ASSERT_EQ(out.size(), 16u);
    for (const ts::Out& o : out)
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(o.Ci[c]));
            EXPECT_TRUE(std::isfinite(o.Cl[c]));
        }
}

// Colours of 6 and 12 channels (rsl_abi.h COLOURS: float8 and float16 lanes), each of
// RGB's repeated, so that every RGB value maps to itself: a shader gives what it gives in
// RGB, in base, light, trace and coefficient modes (up to the rounding of 1/4).
void expectSameInSixAndTwelveChannels(
    const std::function<bool(ts::Shade&, std::string*)>& compile) {
    ts::Scene sc;
    sc.lights.push_back({{0, 0, 1}, {0.9f, 0.6f, 0.3f}});
    sc.ambient[0] = 0.2f, sc.ambient[1] = 0.1f, sc.ambient[2] = 0.05f;
    std::vector<ts::Point> pts = ts::grid(4);
    for (size_t i = 0; i < pts.size(); ++i) {
        const float c[3] = {0.2f + 0.05f * float(i % 4), 0.7f, 0.4f + 0.03f * float(i)};
        std::copy(c, c + 3, pts[i].Cs);
        pts[i].Os[0] = 1.0f, pts[i].Os[1] = 0.5f, pts[i].Os[2] = 0.75f;
    }
    auto runAll = [&](int channels) {
        ts::Shade sh;
        sh.colorChannels = channels;
        std::string err, log;
        EXPECT_TRUE(compile(sh, &err)) << err;
        EXPECT_TRUE(sh.buildOnDevice(sc, &log)) << log.substr(0, 4000);
        std::vector<std::vector<ts::Out>> modes;
        for (auto [light, trace] :
             {std::pair{-1, -1}, {0, -1}, {-1, 0}, {ts::kCoefficients, -1}})
            modes.push_back(sh.run(pts, sc, light, trace));
        return modes;
    };
    const auto rgb = runAll(3);
    for (int channels : {6, 12}) {
        SCOPED_TRACE(std::to_string(channels) + " channels");
        const auto wide = runAll(channels);
        ASSERT_EQ(wide.size(), rgb.size());
        for (size_t m = 0; m < rgb.size(); ++m) {
            ASSERT_EQ(wide[m].size(), rgb[m].size()) << "mode " << m;
            for (size_t i = 0; i < rgb[m].size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const ts::Out &a = rgb[m][i], &b = wide[m][i];
                    EXPECT_NEAR(b.Ci[c], a.Ci[c], 1e-5f)
                        << "mode " << m << " point " << i;
                    EXPECT_NEAR(b.Oi[c], a.Oi[c], 1e-6f)
                        << "mode " << m << " point " << i;
                    EXPECT_NEAR(b.Cl[c], a.Cl[c], 1e-5f)
                        << "mode " << m << " point " << i;
                    if (m == 3 && a.CiLight[0][c] != -12345.0f) {  // (with coefficients)
                        EXPECT_NEAR(b.CiLight[0][c], a.CiLight[0][c], 1e-5f);
                    }
                }
        }
    }
}

TEST_P(CodegenShader, GivesTheSameInSixAndTwelveChannels) {
    REQUIRE_DEVICE();
    expectSameInSixAndTwelveChannels([](ts::Shade& sh, std::string* err) {
        return sh.compileFile(shaderPath(GetParam()), err);
    });
}

// The colour builtins the standard shaders do not call, in their _c forms (noise and
// random excepted: a channel's stream depends on its index, so repeated channels differ):
// spline, mix, clamp, min, max, division by a colour and a float, equality, comp and
// setcomp, ctransform and colour-space casts, an RGB parameter default, a colour array
// parameter, illuminance with the light's Cl, an output colour. (A point cast to a colour
// is not among them: its components are the first three channels, RGB's or not.)
TEST(Codegen, ColourBuiltinsGiveTheSameInSixAndTwelveChannels) {
    REQUIRE_DEVICE();
    const std::string src =
        "surface s(color tint = color(0.9, 0.5, 0.2); color pal[2] = {color(1, 0, 0), "
        "color(0, 0.5, 1)}; output varying color aov = 0) {\n"
        "  color a = spline(s, color(0.1), Cs, tint, color(0.3, 0.6, 0.9), pal[1]);\n"
        "  color b = mix(Cs, tint, t) / (color(1.5) + Cs) + clamp(Cs * 2, color(0.2), "
        "tint);\n"
        "  color c = min(a, b) + max(a, color(0.25)) / 2;\n"
        "  color h = ctransform(\"hsv\", c);\n"
        "  setcomp(h, 2, comp(h, 2) * 0.5);\n"
        "  color d = ctransform(\"hsv\", \"rgb\", h) + color \"hsl\" (0.3, 0.5, 0.4) * "
        "0.1;\n"
        "  if (a == b || c != color(0.5)) d += 0.1;\n"
        "  color lit = 0;\n"
        "  illuminance (P, N, PI / 2) { lit += Cl * tint; }\n"
        "  aov = d;\n"
        "  Ci = Os * (d + lit + pal[0] * 0.1);\n"
        "  Oi = Os;\n}\n";
    expectSameInSixAndTwelveChannels([&](ts::Shade& sh, std::string* err) {
        return sh.compileSource(src, "s.sl", err);
    });
}

INSTANTIATE_TEST_SUITE_P(
    All, CodegenShader,
    ::testing::Values("ambientlight", "arealight", "bumpy", "constant", "depthcue", "distantlight",
                      "fog", "glass", "matte", "metal", "mirror", "paintedplastic", "plastic",
                      "pointlight", "shadowdistant", "shadowpoint", "shadowspot", "shinymetal",
                      "spotlight", "spd"));

TEST(Codegen, ParamLayoutAndMetadata) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("spotlight"), &err)) << err;
    const auto& p = sh.shader.params;
    ASSERT_EQ(p.size(), 7u);
    EXPECT_EQ(p[1].name, "lightcolor");
    EXPECT_EQ(p[1].offset, 1);
    EXPECT_EQ(p[1].size, 3);
    EXPECT_EQ(p[4].name, "coneangle");
    EXPECT_EQ(p[4].offset, 10);
    EXPECT_NEAR(p[4].defaults[0], 30 * M_PI / 180, 1e-6);
    EXPECT_EQ(p[3].space, "shader");
    EXPECT_EQ(sh.shader.paramFloats, 13);
    EXPECT_FALSE(sh.shader.ambientLight);
    ASSERT_TRUE(sh.compileFile(shaderPath("ambientlight"), &err)) << err;
    EXPECT_TRUE(sh.shader.ambientLight);
    ASSERT_TRUE(sh.compileFile(shaderPath("glass"), &err)) << err;
    EXPECT_TRUE(sh.shader.usesTrace);
    ASSERT_TRUE(sh.compileFile(shaderPath("paintedplastic"), &err));
    EXPECT_TRUE(sh.shader.usesTexture);
    EXPECT_TRUE(sh.shader.usesDerivatives) << "texture filters take the footprint";
    EXPECT_EQ(err.find("warning"), std::string::npos) << err;
    ASSERT_TRUE(sh.compileSource("surface s(string tex = \"grid.tx\"; color c = Cs;) { Ci = c; }",
                                 "s.sl", &err)) << err;
    EXPECT_EQ(sh.shader.params[0].defaults[0], float(rsl::stringId("grid.tx")));
    EXPECT_FALSE(sh.shader.params[1].constantDefault);
    EXPECT_FALSE(sh.shader.usesObjectSpace);
    // "object" space read (an instance per primitive's object space, rsl_abi.h SPACES):
    // by name, or by a space named at run time; a default written in it is computed where
    // the shader runs, one in "shader" space is the host's to convert
    ASSERT_TRUE(
        sh.compileSource("surface s(point c = point \"object\" (1, 2, 3); point d = "
                         "point \"shader\" (1, 2, 3)) { Ci = length(P - c - d); }",
                         "s.sl", &err))
        << err;
    EXPECT_TRUE(sh.shader.usesObjectSpace);
    EXPECT_FALSE(sh.shader.params[0].constantDefault);
    EXPECT_TRUE(sh.shader.params[1].constantDefault);
    EXPECT_EQ(sh.shader.params[1].space, "shader");
    ASSERT_TRUE(
        sh.compileSource("surface s(string sp = \"world\") { Ci = xcomp(transform(sp, "
                         "P)); }",
                         "s.sl", &err))
        << err;
    EXPECT_TRUE(sh.shader.usesObjectSpace);
    EXPECT_TRUE(sh.shader.usesSpaceTable);
    ASSERT_TRUE(sh.compileSource("surface s() { Ci = xcomp(transform(\"camera\", P)); }",
                                 "s.sl", &err))
        << err;
    EXPECT_FALSE(sh.shader.usesObjectSpace);
    EXPECT_FALSE(sh.shader.usesSpaceTable);
    // the projected spaces and named ones come from the renderer's table of spaces
    ASSERT_TRUE(
        sh.compileSource("surface s() { Ci = xcomp(transform(\"raster\", P)) + "
                         "xcomp(point \"proj\" (1, 2, 3)) + xcomp(transform(\"proj\", "
                         "\"NDC\", P)); }",
                         "s.sl", &err))
        << err;
    EXPECT_TRUE(sh.shader.usesSpaceTable);
    EXPECT_FALSE(sh.shader.usesObjectSpace);
    EXPECT_EQ(sh.shader.namedSpaces, std::vector<std::string>{"proj"});
    // environment("raytrace", R) is trace(P, R) (PRMan); its other parameters a warning
    ASSERT_TRUE(sh.compileSource(
        "surface s() { Ci = environment(\"raytrace\", I, \"blur\", 0.1); }", "s.sl",
        &err))
        << err;
    EXPECT_TRUE(sh.shader.usesTrace);
    EXPECT_FALSE(sh.shader.usesTexture);
    EXPECT_NE(err.find("s.sl:1:47: warning: environment(\"raytrace\", R): one ray"),
              std::string::npos)
        << err;
}

// The most trace() calls one evaluation makes (traceBound, what the renderer sizes its
// spawned rays by): a call site each in the body, whatever branches it sits in; the ABI's
// RSL_MAX_TRACE (8) when a call may run more than once: in a loop, an illuminance loop or
// a user function (called from anywhere, any number of times).
TEST(Codegen, TraceBoundCountsCallsOnceEach) {
    ts::Shade sh;
    std::string err;
    auto bound = [&](const std::string& body, const std::string& functions = "") {
        err.clear();
        EXPECT_TRUE(sh.compileSource(functions + "surface s(float k = 1;) {\n" + body + "\n}",
                                     "s.sl", &err))
            << err;
        return sh.shader.traceBound;
    };
    EXPECT_EQ(bound("Ci = Cs;"), 0);
    EXPECT_EQ(bound("Ci = trace(P, N);"), 1);
    EXPECT_EQ(bound("color c = 0; if (k > 0) c = trace(P, N); else c = trace(P, -N);\n"
                    "Ci = c + (k > 2 ? trace(P, I) : color(0));"),
              3);
    EXPECT_EQ(bound("color c = 0; float i; for (i = 0; i < 2; i += 1) c += trace(P, N);\n"
                    "Ci = c;"),
              8);
    EXPECT_EQ(bound("color c = 0; while (k < 0) { c += trace(P, N); }\nCi = c;"), 8);
    EXPECT_EQ(bound("color c = 0; illuminance(P) { c += trace(P, L); }\nCi = c;"), 8);
    EXPECT_EQ(bound("Ci = refl(N);", "color refl(normal n) { return trace(P, n); }\n"), 8);
    std::string many = "color c = 0;";
    for (int i = 0; i < 10; ++i) many += " c += trace(P, N + " + std::to_string(i) + ");";
    EXPECT_EQ(bound(many + "\nCi = c;"), 8);
    ASSERT_TRUE(sh.compileFile(shaderPath("spd"), &err)) << err;
    EXPECT_EQ(sh.shader.traceBound, 2) << "a reflected and a refracted ray";
}

// A builtin the renderer answers at compile time as a statement of its own (an unknown
// lightsource() parameter, textureinfo()'s "viewingmatrix": 0) is cast to void: a bare
// `0.0f;` made PoCL print "1 warning generated." for shaders of the RenderMan Repository.
TEST(Codegen, ConstantStatementsAreVoid) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface s() {\n  float x = 0;\n  matrix m = 0;\n"
                                 "  illuminance(P) { lightsource(\"__nonspecular\", x); }\n"
                                 "  textureinfo(\"\", \"viewingmatrix\", m);\n  Ci = x;\n}\n",
                                 "s.sl", &err))
        << err;
    EXPECT_NE(sh.shader.source.find("(void)0.0f;"), std::string::npos) << sh.shader.source;
    EXPECT_EQ(sh.shader.source.find("\n  0.0f;"), std::string::npos) << sh.shader.source;
}

// random() call sites are numbered in the shader; a colour or point takes three (its
// components' sites), so no float call shares a site, and so a number, with one of them
// (rsl_abi.h RANDOM: under the Sobol sampler sites k and k + 1 are a stratified pair).
TEST(Codegen, RandomSitesAreNeverShared) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface s() {\n  color c = random();\n  float a = random(), "
                                 "b = random();\n  Ci = c * a * b;\n}",
                                 "s.sl", &err))
        << err;
    const std::string& src = sh.shader.source;
    EXPECT_NE(src.find("rsl_random_c(g, 0)"), std::string::npos) << src;
    EXPECT_NE(src.find("rsl_random_f(g, 3)"), std::string::npos) << src;
    EXPECT_NE(src.find("rsl_random_f(g, 4)"), std::string::npos) << src;
    EXPECT_EQ(src.find("rsl_random_f(g, 1)"), std::string::npos) << src;
}

// Colour defaults reach the host as RGB, whatever space they are written in, and say
// whether they were written as RGB triples (rgbDefault: a renderer shading in other
// colour channels converts them) or as one float for every channel.
TEST(Codegen, ColourDefaultsAreRgb) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(
        "surface s(color a = color \"hsv\" (0.5, 1, 1); color b = color \"hsl\" (0, 1, 0.5);\n"
        "          color c = color \"YIQ\" (0.5, 0, 0); color d = color \"xyY\" (0.3127, 0.3290, 1);\n"
        "          color e = (0.2, 0.4, 0.6); color f = 0.5;) { Ci = a + b + c + d + e + f; }",
        "s.sl", &err)) << err;
    const auto& p = sh.shader.params;
    auto expectRgb = [&](size_t i, float r, float g, float b, float tol) {
        SCOPED_TRACE(p[i].name);
        EXPECT_NEAR(p[i].defaults[0], r, tol);
        EXPECT_NEAR(p[i].defaults[1], g, tol);
        EXPECT_NEAR(p[i].defaults[2], b, tol);
        EXPECT_TRUE(p[i].rgbDefault);
    };
    expectRgb(0, 0, 1, 1, 1e-6f);         // hue 0.5: cyan
    expectRgb(1, 1, 0, 0, 1e-6f);         // hue 0, lightness 0.5: red
    expectRgb(2, 0.5f, 0.5f, 0.5f, 1e-6f);
    expectRgb(3, 1, 1, 1, 2e-3f);         // D65's white point at Y = 1
    expectRgb(4, 0.2f, 0.4f, 0.6f, 1e-6f);
    EXPECT_EQ(p[5].defaults[1], 0.5f);
    EXPECT_FALSE(p[5].rgbDefault);
}

TEST(Codegen, NonConstantDefaultIsComputedUnlessOverridden) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface s(color c = Cs * 0.5;) { Ci = c; Oi = 1; }", "s.sl", &err))
        << err;
    ts::Scene sc;
    auto pts = ts::grid(2);
    for (auto& p : pts) p.Cs[0] = 0.8f, p.Cs[1] = 0.4f, p.Cs[2] = 0.2f;
    auto out = sh.run(pts, sc);
    ASSERT_EQ(out.size(), 4u);
    expectNear(out[0].Ci, {0.4f, 0.2f, 0.1f}, 1e-6f, "default");
    sh.setParam("c", {1, 2, 3});
    out = sh.run(pts, sc);
    expectNear(out[0].Ci, {1, 2, 3}, 1e-6f, "override");
}

// break N and continue N leave or continue the N-th enclosing loop (RI 3.2 RSL).
TEST(Codegen, BreakAndContinueWithALevel) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(
        "surface s() {\n"
        "    float n = 0, m = 0, i, j;\n"
        "    for (i = 0; i < 5; i += 1) {\n"
        "        for (j = 0; j < 5; j += 1) {\n"
        "            if (j == 2) continue 2;\n"  // skips the rest of the outer body
        "            n += 1;\n"
        "        }\n"
        "        n += 100;\n"
        "    }\n"
        "    i = 0;\n"
        "    while (i < 5) {\n"
        "        i += 1;\n"
        "        for (j = 0; j < 5; j += 1) {\n"
        "            if (i == 3) break 2;\n"
        "            m += 1;\n"
        "        }\n"
        "    }\n"
        "    Ci = color(n, m, i); Oi = 1;\n}\n",
        "s.sl", &err))
        << err;
    ts::Scene sc;
    auto out = sh.run(ts::grid(1), sc);
    ASSERT_EQ(out.size(), 1u);
    expectNear(out[0].Ci, {10, 10, 3}, 1e-6f, "break/continue N");
}

// A whole array assigned as a statement copies it (a colour array too); the copy does not
// follow later changes of the source; another length is an error with its place. (Before,
// every whole-array assignment was an error of the code generator.)
TEST(Codegen, WholeArraysAreAssigned) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(
        "surface s(float k[3] = {1, 2, 3};) {\n"
        "    float b[3];\n"
        "    b = k;\n"
        "    b[1] += 10;\n"
        "    color c[2] = {color(1, 0, 0), color(0, 0, 4)}, d[2];\n"
        "    d = c;\n"
        "    c[1] = 0;\n"
        "    Ci = color(b[0], b[1], b[2]) + d[1] + 100 * c[1]; Oi = 1;\n}\n",
        "s.sl", &err))
        << err;
    ts::Scene sc;
    auto out = sh.run(ts::grid(1), sc);
    ASSERT_EQ(out.size(), 1u);
    expectNear(out[0].Ci, {1, 12, 7}, 1e-6f, "whole arrays");
    EXPECT_FALSE(sh.compileSource("surface s() {\n  float a[2], b[3];\n  b = a;\n}\n",
                                  "s.sl", &err));
    EXPECT_NE(err.find("s.sl:3:5: error: cannot assign a value of type 'float[2]' to "
                       "'float[3]' 'b'"),
              std::string::npos)
        << err;
}

// ---- (c) closed forms with one distant light ------------------------------------------
struct Closed {
    ts::Scene sc;
    std::vector<ts::Point> pts;
    V3 Ln, Cl, amb;
    Closed() {
        Ln = norm({0.3f, 0.4f, 1.0f});
        Cl = {0.8f, 0.6f, 0.4f};
        amb = {0.1f, 0.2f, 0.3f};
        sc.lights.push_back({{Ln[0] * 5, Ln[1] * 5, Ln[2] * 5}, {Cl[0], Cl[1], Cl[2]}});
        for (int c = 0; c < 3; ++c) sc.ambient[c] = amb[c];
        pts = ts::grid(3);
        for (auto& p : pts) {
            p.Cs[0] = 0.9f, p.Cs[1] = 0.5f, p.Cs[2] = 0.3f;
            p.Os[0] = 0.8f, p.Os[1] = 0.9f, p.Os[2] = 1.0f;
        }
    }
    // Blinn specular of RI 3.2 for point p
    float spec(const ts::Point& p, float roughness) const {
        V3 V = mul(norm(v3(p.I)), -1);
        V3 H = norm(add(Ln, V));
        return std::pow(std::max(0.0f, dot({0, 0, 1}, H)), 1.0f / roughness);
    }
};

struct SurfaceCase {
    const char* name;
    // Ci in base mode and Ci - E in light mode 0
    V3 (*base)(const Closed&, const ts::Point&);
    V3 (*light)(const Closed&, const ts::Point&);
};

V3 baseAmb(const Closed& k, const ts::Point& p) {  // Os * Cs * Ka(1) * ambient
    return mulv(mulv(v3(p.Os), v3(p.Cs)), k.amb);
}
V3 plasticLight(const Closed& k, const ts::Point& p) {  // Kd .5, Ks .5, roughness .1
    V3 d = mul(mulv(v3(p.Cs), k.Cl), 0.5f * k.Ln[2]);
    V3 s = mul(k.Cl, 0.5f * k.spec(p, 0.1f));
    return mulv(v3(p.Os), add(d, s));
}
V3 metalLight(const Closed& k, const ts::Point& p) {  // Ks 1, roughness .1
    return mulv(mulv(v3(p.Os), v3(p.Cs)), mul(k.Cl, k.spec(p, 0.1f)));
}

const SurfaceCase kSurfaces[] = {
    {"constant", [](const Closed&, const ts::Point& p) { return mulv(v3(p.Os), v3(p.Cs)); },
     [](const Closed&, const ts::Point&) { return V3{0, 0, 0}; }},
    {"matte", baseAmb,
     [](const Closed& k, const ts::Point& p) {
         return mul(mulv(mulv(v3(p.Os), v3(p.Cs)), k.Cl), k.Ln[2]);
     }},
    {"plastic", baseAmb, plasticLight},
    {"paintedplastic", baseAmb, plasticLight},
    {"metal", baseAmb, metalLight},
    {"shinymetal", baseAmb, metalLight},
};

class CodegenClosedForm : public ::testing::TestWithParam<SurfaceCase> {};

TEST_P(CodegenClosedForm, BaseAndLightModes) {
    REQUIRE_DEVICE();
    const SurfaceCase& c = GetParam();
    Closed k;
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath(c.name), &err)) << err;
    auto base = sh.run(k.pts, k.sc, -1, -1);
    auto lit = sh.run(k.pts, k.sc, 0, -1);
    ASSERT_EQ(base.size(), k.pts.size());
    ASSERT_EQ(lit.size(), k.pts.size());
    for (size_t i = 0; i < k.pts.size(); ++i) {
        expectNear(base[i].Ci, c.base(k, k.pts[i]), 1e-4f, std::string(c.name) + " base");
        expectNear(base[i].Oi, v3(k.pts[i].Os), 1e-6f, std::string(c.name) + " Oi");
        EXPECT_EQ(base[i].traceCount, 0);
        V3 diff = sub(v3(lit[i].Ci), v3(base[i].Ci));
        expectNear(diff.data(), c.light(k, k.pts[i]), 1e-4f, std::string(c.name) + " light");
    }
}

INSTANTIATE_TEST_SUITE_P(Std, CodegenClosedForm, ::testing::ValuesIn(kSurfaces),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Codegen, LightModeOfAnotherLightIsZero) {
    REQUIRE_DEVICE();
    Closed k;
    k.sc.lights.push_back({{0, 0, 1}, {5, 5, 5}});
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("matte"), &err)) << err;
    auto base = sh.run(k.pts, k.sc, -1, -1);
    auto l1 = sh.run(k.pts, k.sc, 1, -1);
    for (size_t i = 0; i < k.pts.size(); ++i) {
        V3 want = mulv(mulv(v3(k.pts[i].Os), v3(k.pts[i].Cs)), {5, 5, 5});
        V3 diff = sub(v3(l1[i].Ci), v3(base[i].Ci));
        expectNear(diff.data(), want, 1e-4f, "light 1");
    }
}

// ---- (d) trace() requests and coefficients ---------------------------------------------
V3 reflectv(V3 i, V3 n) { return sub(i, mul(n, 2 * dot(i, n))); }

TEST(Codegen, MirrorRecordsReflectionRay) {
    REQUIRE_DEVICE();
    Closed k;
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("mirror"), &err)) << err;
    auto base = sh.run(k.pts, k.sc, -1, -1);
    auto tr = sh.run(k.pts, k.sc, -1, 0);
    auto tr1 = sh.run(k.pts, k.sc, -1, 1);
    for (size_t i = 0; i < k.pts.size(); ++i) {
        const ts::Point& p = k.pts[i];
        ASSERT_EQ(base[i].traceCount, 1);
        expectNear(base[i].Ci, {0, 0, 0}, 1e-6f, "mirror base");
        expectNear(base[i].org[0], v3(p.P), 1e-6f, "org");
        expectNear(base[i].dir[0], reflectv(norm(v3(p.I)), {0, 0, 1}), 1e-5f, "dir");
        expectNear(tr[i].Ci, v3(p.Os), 1e-5f, "mirror trace coefficient");
        expectNear(tr1[i].Ci, {0, 0, 0}, 1e-6f, "no second trace");
    }
}

// independent unpolarised Fresnel (Snell + the two Fresnel amplitude terms)
void fresnelRef(V3 I, V3 N, float eta, float& kr, float& kt, V3& R, V3& T) {
    float cosi = -dot(I, N);
    R = add(I, mul(N, 2 * cosi));
    float sint2 = eta * eta * (1 - cosi * cosi);
    float cost = std::sqrt(1 - sint2);
    float n1 = 1, n2 = 1 / eta;
    float rs = (n1 * cosi - n2 * cost) / (n1 * cosi + n2 * cost);
    float rp = (n2 * cosi - n1 * cost) / (n2 * cosi + n1 * cost);
    kr = 0.5f * (rs * rs + rp * rp);
    kt = 1 - kr;
    T = add(mul(I, eta), mul(N, eta * cosi - cost));
}

TEST(Codegen, GlassRecordsReflectionAndRefraction) {
    REQUIRE_DEVICE();
    Closed k;
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("glass"), &err)) << err;
    auto base = sh.run(k.pts, k.sc, -1, -1);
    auto t0 = sh.run(k.pts, k.sc, -1, 0);
    auto t1 = sh.run(k.pts, k.sc, -1, 1);
    for (size_t i = 0; i < k.pts.size(); ++i) {
        const ts::Point& p = k.pts[i];
        V3 In = norm(v3(p.I));
        float kr, kt;
        V3 R, T;
        fresnelRef(In, {0, 0, 1}, 1 / 1.5f, kr, kt, R, T);
        ASSERT_EQ(base[i].traceCount, 2);
        expectNear(base[i].dir[0], R, 1e-4f, "R");
        expectNear(base[i].dir[1], T, 1e-4f, "T");
        expectNear(base[i].org[1], v3(p.P), 1e-6f, "org");
        expectNear(base[i].Oi, {1, 1, 1}, 1e-6f, "Oi");
        V3 c0 = sub(v3(t0[i].Ci), v3(base[i].Ci)), c1 = sub(v3(t1[i].Ci), v3(base[i].Ci));
        expectNear(c0.data(), {kr, kr, kr}, 1e-4f, "Kr * kr");
        expectNear(c1.data(), {kt, kt, kt}, 1e-4f, "Kt * kt * transmitcolor");
    }
}

TEST(Codegen, SpdTracesOnlyWhenAsked) {
    REQUIRE_DEVICE();
    Closed k;
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("spd"), &err)) << err;
    auto base = sh.run(k.pts, k.sc, -1, -1);
    for (const auto& o : base) EXPECT_EQ(o.traceCount, 0);
    sh.setParam("reflected", {0.5f});
    base = sh.run(k.pts, k.sc, -1, -1);
    auto t0 = sh.run(k.pts, k.sc, -1, 0);
    for (size_t i = 0; i < k.pts.size(); ++i) {
        const ts::Point& p = k.pts[i];
        ASSERT_EQ(base[i].traceCount, 1);
        expectNear(base[i].dir[0], norm(reflectv(norm(v3(p.I)), {0, 0, 1})), 1e-5f, "dir");
        V3 c = sub(v3(t0[i].Ci), v3(base[i].Ci));
        expectNear(c.data(), mul(mulv(v3(p.Os), v3(p.Cs)), 0.5f), 1e-5f, "coefficient");
    }
}

// ---- (f) light shaders -------------------------------------------------------------------
ts::Point at(float x, float y, float z) {
    ts::Point p;
    p.P[0] = p.Ps[0] = x, p.P[1] = p.Ps[1] = y, p.P[2] = p.Ps[2] = z;
    return p;
}

TEST(Codegen, PointLight) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("pointlight"), &err)) << err;
    sh.setParam("intensity", {2});
    sh.setParam("from", {0, 0, 3});
    sh.setParam("lightcolor", {1, 0.5f, 0.25f});
    ts::Scene sc;
    auto out = sh.run({at(1, 0, 0), at(0, 2, 1)}, sc);
    ASSERT_EQ(out.size(), 2u);
    expectNear(out[0].L, {1, 0, -3}, 1e-6f, "L");
    expectNear(out[0].Cl, {0.2f, 0.1f, 0.05f}, 1e-5f, "Cl");
    expectNear(out[1].L, {0, 2, -2}, 1e-6f, "L");
    expectNear(out[1].Cl, {0.25f, 0.125f, 0.0625f}, 1e-5f, "Cl");
}

TEST(Codegen, SpotLightConeAndFalloff) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("spotlight"), &err)) << err;
    sh.setParam("from", {0, 0, 3});
    sh.setParam("to", {0, 0, 0});
    ts::Scene sc;
    auto out = sh.run({at(0, 0, 0), at(0.5f, 0, 0), at(5, 0, 0), at(1.6f, 0, 0)}, sc);
    ASSERT_EQ(out.size(), 4u);
    float cosout = std::cos(30 * M_PI / 180), cosin = std::cos(25 * M_PI / 180);
    auto want = [&](float x) {
        V3 L = {x, 0, -3};
        float cosang = -L[2] / std::sqrt(dot(L, L));
        float t = std::min(1.0f, std::max(0.0f, (cosang - cosout) / (cosin - cosout)));
        float ss = cosang < cosout ? 0 : (cosang >= cosin ? 1 : t * t * (3 - 2 * t));
        return std::pow(cosang, 2.0f) / dot(L, L) * ss;
    };
    expectNear(out[0].Cl, {want(0), want(0), want(0)}, 1e-5f, "centre");
    EXPECT_NEAR(out[0].Cl[0], 1.0f / 9, 1e-5f);
    expectNear(out[0].L, {0, 0, -3}, 1e-6f, "L");
    expectNear(out[1].Cl, {want(0.5f), want(0.5f), want(0.5f)}, 1e-5f, "inside");
    expectNear(out[2].Cl, {0, 0, 0}, 0, "outside the cone");
    float w = want(1.6f);  // 28 degrees: in the penumbra
    EXPECT_GT(w, 0);
    EXPECT_LT(w, 1.6f * 1.6f);
    expectNear(out[3].Cl, {w, w, w}, 1e-5f, "penumbra");
}

TEST(Codegen, DistantAndAmbientLights) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("distantlight"), &err)) << err;
    sh.setParam("intensity", {3});
    sh.setParam("from", {0, 0, 2});
    sh.setParam("to", {0, 1, 2});
    ts::Scene sc;
    auto out = sh.run({at(1, 2, 3)}, sc);
    ASSERT_EQ(out.size(), 1u);
    expectNear(out[0].L, {0, 1, 0}, 1e-6f, "L = to - from");
    expectNear(out[0].Cl, {3, 3, 3}, 1e-6f, "Cl");
    ASSERT_TRUE(sh.compileFile(shaderPath("ambientlight"), &err)) << err;
    sh.setParam("intensity", {0.5f});
    out = sh.run({at(1, 2, 3)}, sc);
    expectNear(out[0].Cl, {0.5f, 0.5f, 0.5f}, 1e-6f, "ambient Cl");
}

TEST(Codegen, ShadowLightsAreUnshadowed) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileFile(shaderPath("shadowpoint"), &err)) << err;
    EXPECT_EQ(err, "");  // shadow() of a parameter in a light: the shadow ray's job
    sh.setParam("from", {0, 0, 2});
    sh.setParam("shadowname", {float(rsl::stringId("raytrace"))});
    ts::Scene sc;
    auto out = sh.run({at(0, 0, 0)}, sc);
    ASSERT_EQ(out.size(), 1u);
    expectNear(out[0].Cl, {0.25f, 0.25f, 0.25f}, 1e-6f, "Cl");
}

}  // namespace

namespace {

// user functions (output parameters, loops, break, arrays, illuminance inside a
// function, extern globals) and the light mode through them
const char* kUserFunctions =
    "float accum(float n; output color c) {\n"
    "  float i;\n"
    "  for (i = 0; i < n; i += 1) { c += color(i); if (i > 2) break; }\n"
    "  return i;\n"
    "}\n"
    "color mydiffuse(normal Nn) {\n"
    "  extern point P;\n"
    "  color C = 0;\n"
    "  illuminance(P, Nn, 1.5707963) { C += Cl * (normalize(L) . Nn); }\n"
    "  return C;\n"
    "}\n"
    "surface uf(float n = 5;) {\n"
    "  color c = 0;\n"
    "  float arr[3] = {1, 2, 3};\n"
    "  float k = accum(n, c);\n"
    "  float j = 0;\n"
    "  while (j < 2) { j += 1; }\n"
    "  Ci = c + color(k, arr[1], j) + 2 * mydiffuse(normalize(N));\n"
    "  Oi = 1;\n"
    "}\n";

TEST(Codegen, UserFunctionsAndControlFlow) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kUserFunctions, "uf.sl", &err)) << err;
    EXPECT_NE(sh.shader.source.find("static float rsl_uf_accum_"), std::string::npos);
    ts::Scene sc;
    sc.lights.push_back({{0, 0, 2}, {0.5f, 0.25f, 1}});
    auto pts = ts::grid(2);
    auto base = sh.run(pts, sc);
    auto lit = sh.run(pts, sc, 0, -1);
    ASSERT_EQ(base.size(), 4u);
    ASSERT_EQ(lit.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        expectNear(base[i].Ci, {9, 8, 8}, 1e-6f, "base");
        V3 d = sub(v3(lit[i].Ci), v3(base[i].Ci));
        expectNear(d.data(), {1, 0.5f, 2}, 1e-5f, "light through a user function");
    }
    sh.setParam("n", {2});
    base = sh.run(pts, sc);
    ASSERT_EQ(base.size(), 4u);
    expectNear(base[0].Ci, {1 + 2, 1 + 2, 1 + 2}, 1e-6f, "n = 2");
}

// A nested function reaches the shader's variables and parameters it declares extern (PRMan:
// the RenderMan Repository's lensflare.sl counts its random numbers so), also through a
// function that calls it; each is passed by address. f() adds 1 to a and returns a * k:
// 2 * 3, then through g() 3 * 3, so r = 15 and a = 3 (not hoisted as the instance's 1).
TEST(Codegen, NestedFunctionsReachExternVariables) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(
        "surface x(float k = 3) {\n  uniform float a = 1;\n"
        "  float f() { extern uniform float a; extern float k; a += 1; return a * k; }\n"
        "  float g() { return f(); }\n"
        "  float r = f();\n  r += g();\n  Ci = color(r, a, 0);\n}\n",
        "x.sl", &err))
        << err;
    ts::Scene sc;
    std::vector<ts::Point> pts = ts::grid(2);
    std::vector<ts::Out> out = sh.run(pts, sc);
    ASSERT_EQ(out.size(), pts.size()) << sh.diagnostics;
    for (const ts::Out& o : out) expectNear(o.Ci, {15, 3, 0}, 1e-6f, "extern");
}

}  // namespace

namespace {

// every less common path of the generator at once: it must build on the device
const char* kKitchenSink =
    "float twice(float x) { return 2 * x; }\n"
    "surface sink(float knots[4] = {0, 1, 0.5, 1}; matrix m = 1; string space = \"shader\";\n"
    "             string map = \"\"; point pts[2] = {(0, 0, 0), (1, 1, 1)};\n"
    "             output varying color extra = 0;)\n"
    "{\n"
    "  uniform float i;\n"
    "  varying float acc = 0;\n"
    "  for (i = 0; i < 4; i += 1) { acc += knots[i]; if (acc > 10) continue; }\n"
    "  point q = transform(space, P) + transform(space, \"world\", P) + transform(m, P);\n"
    "  vector w = vtransform(\"camera\", m, vector(1, 0, 0)) + ntransform(m, N);\n"
    "  normal nn = calculatenormal(P) + bump(map, N, dPdu, dPdv);\n"
    "  color h = color \"hsl\" (0.5, 0.5, 0.5) + ctransform(map, \"rgb\", Cs);\n"
    "  float f = filterstep(0.5, s) + Deriv(s, t) + random() + depth(P) + ptlined(P, q, E);\n"
    "  f += spline(\"linear\", s, knots) + float spline(t, 0, 1, 2, 3) + pnoise(P, t, point(2, 2, 2), 3);\n"
    "  point sp = spline(s, pts[0], pts[1], pts[0], pts[1]);\n"
    "  float c = cellnoise(s, t) + float noise(s, t) + float cellnoise(P, t) + twice(f);\n"
    "  color tex = texture(map[1], s, t, \"blur\", 0.1) + color environment(map, I) + "
    "color shadow(map, P);\n"
    "  float tinfo = 0;\n"
    "  f += textureinfo(map, \"resolution\", tinfo) + attribute(\"identifier:name\", tinfo) +\n"
    "       option(\"Format\", tinfo) + lightsource(\"foo\", tinfo) + match(map, \"abc\");\n"
    "  string cc = concat(map, \"x\");\n"
    "  printf(\"%f\\n\", f);\n"
    "  setxcomp(q, 1); setcomp(m, 0, 1, 2);\n"
    "  matrix r = rotate(m, 0.5, vector(0, 0, 1)) * determinant(m) / m;\n"
    "  illuminance(\"ambient\", P) { if (comp(Cs, 0) > 2) extra += 1; extra += Cl; }\n"
    "  extra += phong(N, -I, 20) + specularbrdf(vector(0, 0, 1), N, -I, 0.2) * Cs;\n"
    "  Ci = color(c) + h + tex + color(comp(r, 0, 0)) + (cc == \"x\" ? 1 : 0) + color(sp) + "
    "color(nn) + color(w) + extra + transmission(P, E);\n"
    "  Oi = 1;\n"
    "}\n";

TEST(Codegen, KitchenSinkBuilds) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kKitchenSink, "sink.sl", &err)) << err;
    EXPECT_TRUE(sh.shader.usesDerivatives);
    EXPECT_EQ(sh.shader.paramFloats, 4 + 16 + 1 + 1 + 6 + 3);
    ts::Scene sc;
    sc.lights.push_back({{0, 0, 1}, {1, 1, 1}});
    std::string log;
    ASSERT_TRUE(sh.buildOnDevice(sc, &log)) << log;
    auto out = sh.run(ts::grid(3), sc);
    ASSERT_EQ(out.size(), 9u);
    for (const auto& o : out)
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(o.Ci[c]));
}

}  // namespace
