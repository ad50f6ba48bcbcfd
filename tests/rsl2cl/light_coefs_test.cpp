// light_coefs_test.cpp: light coefficients (rsl_abi.h, LIGHT COEFFICIENTS; rsl2cl
// emit_coefs.cpp). One base evaluation with ev->coefs set must give, for every light l,
// what the evaluation in light mode l adds to Ci: checked on the device over a grid of
// points and three coloured lights for the standard shaders, spd.sl and shaders that use
// every construct the code generator carries; shaders it cannot carry are compiled
// without (and evaluated per light, as before).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "coef_shader.h"
#include "emit_cl.h"
#include "info.h"
#include "lexer.h"
#include "test_util.h"
#include "testshade.h"

namespace {

rsl::EmittedShader generate(const std::string& src, const std::string& name) {
    rsltest::Result r;
    rsltest::compile(src, r, name);
    EXPECT_TRUE(r.ok) << r.diags;
    rsl::Diagnostics diag;
    if (!r.ok) return {};
    rsl::EmittedShader em = rsl::emitOpenCL(*r.prog.shaders[0], r.prog, diag);
    EXPECT_FALSE(diag.hasErrors()) << diag.text();
    return em;
}

ts::Scene threeLights() {
    ts::Scene sc;
    sc.lights.push_back({{0.0f, 0.0f, 1.0f}, {0.8f, 0.4f, 0.2f}});
    sc.lights.push_back({{1.0f, 0.5f, 0.7f}, {0.1f, 0.9f, 0.3f}});
    sc.lights.push_back({{-0.6f, 0.2f, 0.4f}, {2.0f, 2.0f, 2.5f}});
    sc.ambient[0] = sc.ambient[1] = sc.ambient[2] = 0.3f;
    return sc;
}

// For every point and light: base + coefficient = Ci of that light's mode.
void expectCoefsMatchModes(ts::Shade& sh, const std::string& what) {
    ts::Scene sc = threeLights();
    std::vector<ts::Point> pts = ts::grid(4);
    for (size_t i = 0; i < pts.size(); ++i) {  // varied normals and colours
        ts::Point& p = pts[i];
        p.N[0] = 0.3f * std::sin(float(i)), p.N[1] = 0.2f * std::cos(float(i)), p.N[2] = 1.0f;
        p.Cs[0] = 0.9f, p.Cs[1] = 0.5f + 0.02f * float(i), p.Cs[2] = 0.2f;
        p.Os[0] = 1.0f, p.Os[1] = 0.75f, p.Os[2] = 0.5f;
    }
    std::vector<ts::Out> coefs = sh.run(pts, sc, ts::kCoefficients);
    std::vector<ts::Out> base = sh.run(pts, sc);
    ASSERT_EQ(coefs.size(), pts.size()) << what << sh.diagnostics;
    ASSERT_EQ(base.size(), pts.size()) << what;
    float largest = 0.0f;
    for (int l = 0; l < int(sc.lights.size()); ++l) {
        std::vector<ts::Out> mode = sh.run(pts, sc, l);
        ASSERT_EQ(mode.size(), pts.size()) << what;
        for (size_t i = 0; i < pts.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                float want = mode[i].Ci[c] - base[i].Ci[c];
                largest = std::max(largest, std::fabs(want));
                // the per-mode difference cancels E (ambient): a few ulp of Ci
                EXPECT_NEAR(coefs[i].CiLight[l][c], want, 1e-5f + 1e-5f * std::fabs(mode[i].Ci[c]))
                    << what << " light " << l << " point " << i << " channel " << c;
            }
    }
    EXPECT_GT(largest, 0.01f) << what << ": the lights must contribute for the test to mean anything";
    for (size_t i = 0; i < pts.size(); ++i)  // the value is still the base evaluation's
        for (int c = 0; c < 3; ++c) EXPECT_EQ(coefs[i].Ci[c], base[i].Ci[c]) << what;
}

// Compiles src into sh, which must carry light coefficients.
void compileWithCoefs(ts::Shade& sh, const char* src, const char* name) {
    std::string err;
    ASSERT_TRUE(sh.compileSource(src, name, &err)) << err;
    ASSERT_TRUE(sh.shader.lightCoefs) << sh.shader.source;
}

TEST(LightCoefs, StandardShadersMatchTheirLightModes) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    for (const char* n : {"plastic", "matte", "metal", "shinymetal", "paintedplastic"}) {
        ts::Shade sh;
        std::string err;
        ASSERT_TRUE(sh.compileFile(std::string(RSL2CL_SHADER_DIR) + "/" + n + ".sl", &err)) << err;
        EXPECT_TRUE(sh.shader.lightCoefs) << n;
        expectCoefsMatchModes(sh, n);
    }
    ts::Shade spd;
    std::string err;
    ASSERT_TRUE(spd.compileFile(std::string(RSL2CL_TEST_DATA) + "/spd.sl", &err)) << err;
    EXPECT_TRUE(spd.shader.lightCoefs);
    spd.setParam("Ks", {0.5f});
    spd.setParam("reflected", {0.3f});
    expectCoefsMatchModes(spd, "spd");
}

// Every construct the coefficients are carried through: illuminance loops (a term of
// the loop's light, and a whole-array update), declarations, = += -= *= /=, unary
// minus, division, ?:, mix(), casts, a product with a trace() result's neighbour, and
// a variable reset to an independent value.
const char* kEveryConstruct =
    "surface every(float Kd = .7, k = .25;)\n"
    "{\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    color c = 0, d = Cs * diffuse(Nf);\n"
    "    color unused = diffuse(Nf);\n"
    "    unused = color(0.5);\n"
    "    illuminance(P, Nf, PI / 2) {\n"
    "        c += Cl * (normalize(L) . Nf) * Kd;\n"
    "        c -= k * Cl / 4;\n"
    "        d = d + Cl * Cs;\n"
    "    }\n"
    "    color t = trace(P, Nf);\n"
    "    d *= 0.5;\n"
    "    d += c * 0.5;\n"
    "    d -= c * 0.25;\n"
    "    d /= 2;\n"
    "    color m = mix(c, -d, k) + (k > 0.5 ? c : d / 3) + color(specular(Nf, -I, .2));\n"
    "    Oi = Os;\n"
    "    Ci = Os * (0.1 + t - Cs * m - unused) ;\n"
    "    Ci *= 2;\n"
    "}\n";

TEST(LightCoefs, EveryCarriedConstructMatchesLightModes) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    ASSERT_NO_FATAL_FAILURE(compileWithCoefs(sh, kEveryConstruct, "every.sl"));
    expectCoefsMatchModes(sh, "every");
}

// Illumination models written as user functions (as Advanced RenderMan's material.h
// does): a function's light-dependent result carries its parts per light back to the
// caller, through nested calls, several returns, a ternary, and a void function that
// adds to Ci itself.
const char* kFunctions =
    "surface fns(float Ka = 1, Kd = .6, Ks = .4, roughness = .2;)\n"
    "{\n"
    "    color plasticish(normal Nf; vector V; float Kd, Ks, roughness) {\n"
    "        color C = 0;\n"
    "        illuminance(P, Nf, PI / 2) {\n"
    "            C += Cl * Kd * (normalize(L) . Nf);\n"
    "        }\n"
    "        if (Ks <= 0) return C;\n"
    "        return C + Ks * specular(Nf, V, roughness);\n"
    "    }\n"
    "    color twice(normal Nf; vector V; float Kd, Ks, roughness) {\n"
    "        return 2 * plasticish(Nf, V, Kd, Ks, roughness) - diffuse(Nf);\n"
    "    }\n"
    "    void addto(normal Nf; color k) { Ci += k * diffuse(Nf); }\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    vector V = -normalize(I);\n"
    "    Oi = Os;\n"
    "    Ci = Os * (Cs * Ka * ambient() + (Kd > 0.5 ? twice(Nf, V, Kd, Ks, roughness)\n"
    "                                               : plasticish(Nf, V, 0.3, 0, 0.1)));\n"
    "    addto(Nf, Cs * 0.25);\n"
    "    Ci += plasticish(Nf, V, 0.2, 0.3, 0.3);\n"
    "}\n";

TEST(LightCoefs, UserFunctionsCarryTheirResultsParts) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    ASSERT_NO_FATAL_FAILURE(compileWithCoefs(sh, kFunctions, "fns.sl"));
    expectCoefsMatchModes(sh, "functions, Kd .6");
    sh.setParam("Kd", {0.4f});  // the ternary's other branch
    expectCoefsMatchModes(sh, "functions, Kd .4");
}

// Operands with side effects in light-dependent expressions: random() (a site per
// call), a derivative, a texture lookup, a user function. Each is computed once, before
// the statement, for the value and the parts alike; evaluated again per light, random()
// would draw from another site (this test then fails).
const char* kImpureOperands =
    "surface impure(float Kd = .8;)\n"
    "{\n"
    "    float k(float x) { return 2 * x; }\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    color c = random() * diffuse(Nf);\n"
    "    c += (0.5 + area(P)) * k(Kd) * specular(Nf, -I, .3);\n"
    "    c *= 0.5 + random();\n"
    "    Oi = Os;\n"
    "    Ci = Os * color texture(\"map.tx\", \"fill\", 0.75) * (c + diffuse(normalize(N + random())));\n"
    "}\n";

TEST(LightCoefs, ImpureOperandsAreEvaluatedOnce) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    ASSERT_NO_FATAL_FAILURE(compileWithCoefs(sh, kImpureOperands, "impure.sl"));
    expectCoefsMatchModes(sh, "impure");
}

// A light just below the horizon: the hemisphere test lets it in (its tolerance is
// 1e-6), and diffuse() must add nothing rather than a negative amount (which the
// renderer counts as a bad shader result and leaves out), in its mode and as a part.
TEST(LightCoefs, DiffuseAtTheHorizonIsNotNegative) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface d() { Oi = 1; Ci = diffuse(N); }\n", "d.sl", &err)) << err;
    ts::Scene sc;
    sc.lights.push_back({{1.0f, 0.0f, -4e-7f}, {1.0f, 1.0f, 1.0f}});
    std::vector<ts::Point> pts = ts::grid(1);
    std::vector<ts::Out> mode = sh.run(pts, sc, 0), coefs = sh.run(pts, sc, ts::kCoefficients);
    ASSERT_EQ(mode.size(), 1u);
    ASSERT_EQ(coefs.size(), 1u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GE(mode[0].Ci[c], 0.0f);
        EXPECT_GE(coefs[0].CiLight[0][c], 0.0f);
    }
}

// Differential: mutants of coef_shader.h (token swaps and drops) that still compile with
// light coefficients build on the device, and their coefficients match their per-light
// evaluation modes (within 1e-4 + 1e-4 |Ci|: mutants may sum large terms).
TEST(LightCoefs, MutantsMatchTheirLightModes) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    rsl::Diagnostics d;
    std::vector<rsl::Token> toks = rsl::lexText(rsltest::coefShader(), "f.sl", d);
    toks.pop_back();
    std::mt19937 rng(777);
    const ts::Scene sc = threeLights();
    const std::vector<ts::Point> pts = ts::grid(2);
    int checked = 0;
    for (int iter = 0; iter < 2000 && checked < 12; ++iter) {
        std::vector<rsl::Token> t = toks;
        size_t a = rng() % t.size(), b = rng() % t.size();
        if (rng() % 2) std::swap(t[a], t[b]);
        else t.erase(t.begin() + static_cast<long>(a));
        const std::string src = rsl::tokensToText(t);
        ts::Shade sh;
        std::string err;
        if (!sh.compileSource(src, "m.sl", &err) || !sh.shader.lightCoefs) continue;
        std::string log;
        ASSERT_TRUE(sh.buildOnDevice(sc, &log)) << src << log;
        ++checked;
        std::vector<ts::Out> coefs = sh.run(pts, sc, ts::kCoefficients), base = sh.run(pts, sc);
        ASSERT_EQ(coefs.size(), pts.size());
        for (int l = 0; l < int(sc.lights.size()); ++l) {
            std::vector<ts::Out> mode = sh.run(pts, sc, l);
            ASSERT_EQ(mode.size(), pts.size());
            for (size_t i = 0; i < pts.size(); ++i)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(coefs[i].CiLight[l][c], mode[i].Ci[c] - base[i].Ci[c],
                                1e-4f + 1e-4f * std::fabs(mode[i].Ci[c]))
                        << src << "light " << l << " point " << i;
        }
    }
    EXPECT_EQ(checked, 12);
}

// Shaders whose light-dependent values go where the coefficients are not carried are
// compiled without them (the renderer evaluates them per light); their code has none.
// The base evaluation and each light's mode of two shaders agree at a grid of points;
// returns the largest |Ci| of `b`'s (the lights must reach the points to mean anything).
float expectSameModes(ts::Shade& a, ts::Shade& b) {
    ts::Scene sc = threeLights();
    std::vector<ts::Point> pts = ts::grid(4);
    float largest = 0.0f;
    for (int l = -1; l < int(sc.lights.size()); ++l) {
        std::vector<ts::Out> x = l < 0 ? a.run(pts, sc) : a.run(pts, sc, l);
        std::vector<ts::Out> y = l < 0 ? b.run(pts, sc) : b.run(pts, sc, l);
        EXPECT_EQ(x.size(), pts.size()) << a.diagnostics;
        EXPECT_EQ(y.size(), pts.size()) << b.diagnostics;
        for (size_t i = 0; i < pts.size() && i < x.size() && i < y.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                largest = std::max(largest, std::fabs(y[i].Ci[c]));
                EXPECT_NEAR(x[i].Ci[c], y[i].Ci[c], 1e-6f + 1e-6f * std::fabs(y[i].Ci[c]))
                    << "mode " << l << " point " << i << " channel " << c;
            }
    }
    return largest;
}

// Ci as a temporary for the base colour (the RenderMan Companion's txtplastic): affine
// where it is used (affine.cpp follows the code), evaluated per light (the coefficients
// see Ci depend on the lights somewhere, and do not carry it), and each light's mode gives
// what the same shader written without the temporary gives.
TEST(LightCoefs, CiAsATemporaryMatchesTheDirectForm) {
    ts::Shade temp, direct;
    std::string err;
    ASSERT_TRUE(temp.compileSource(
        "surface temp(float Ka = 1, Kd = 0.5, Ks = 0.5;) {\n"
        "  normal Nf = faceforward(normalize(N), I);\n  Ci = Cs * 0.5;\n"
        "  Ci = Os * (Ci * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, -normalize(I), 0.1));\n}\n",
        "temp.sl", &err))
        << err;
    ASSERT_TRUE(direct.compileSource(
        "surface direct(float Ka = 1, Kd = 0.5, Ks = 0.5;) {\n"
        "  normal Nf = faceforward(normalize(N), I);\n"
        "  Ci = Os * (Cs * 0.5 * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, -normalize(I), 0.1));\n}\n",
        "direct.sl", &err))
        << err;
    EXPECT_FALSE(temp.shader.lightCoefs);
    EXPECT_TRUE(direct.shader.lightCoefs);
    EXPECT_GT(expectSameModes(temp, direct), 0.01f);
}

// Cl passed to a user function affine in it (SIGGRAPH 2000's fur shader: its own diffuse
// of (Cl, L, N)): the affine check walks the function with the argument's taint, and each
// light's mode gives what the same model written inline gives.
TEST(LightCoefs, ClPassedToAnAffineFunction) {
    ts::Shade fn, inl;
    std::string err;
    ASSERT_TRUE(fn.compileSource(
        "color mydiffuse(color cl; vector l; normal n) {\n"
        "  return cl * max(0, normalize(l) . n);\n}\n"
        "surface fn() {\n  normal Nf = faceforward(normalize(N), I);\n  Ci = 0;\n"
        "  illuminance(P, Nf, PI / 2) { Ci += Cs * mydiffuse(Cl, L, Nf); }\n}\n",
        "fn.sl", &err))
        << err;
    ASSERT_TRUE(inl.compileSource(
        "surface inl() {\n  normal Nf = faceforward(normalize(N), I);\n  Ci = 0;\n"
        "  illuminance(P, Nf, PI / 2) { Ci += Cs * Cl * max(0, normalize(L) . Nf); }\n}\n",
        "inl.sl", &err))
        << err;
    EXPECT_GT(expectSameModes(fn, inl), 0.01f);
}

TEST(LightCoefs, UnsupportedShadersCompileWithout) {
    const char* cases[][2] = {
        {"surface out() { void f(output color c) { c = diffuse(N); } color x = 0; f(x); Ci = x; }",
         "output"},
        {"surface arr() { color a[2]; a[0] = diffuse(N); Ci = a[0]; }", "array"},
        {"surface par(varying color x = 0;) { x = diffuse(N); Ci = x; }", "parameter"},
        {"surface nested() { color a = 0, b = 0; a = (b = diffuse(N)) * 2; Ci = a; }", "nested"},
        // an impure operand in a ?: branch would run whichever branch is taken
        {"surface br() { Ci = u > 0.5 ? random() * diffuse(N) : diffuse(N); }", "branch"},
        {"surface asg() { float k = 0; Ci = (k = 2) * diffuse(N); }", "assignment"},
    };
    for (const auto& c : cases) {
        rsl::EmittedShader em = generate(c[0], std::string(c[1]) + ".sl");
        EXPECT_FALSE(em.lightCoefs) << c[1];
        EXPECT_EQ(em.source.find("Ci_light"), std::string::npos) << c[1];
    }
    {  // rsl2cl --info says why
        rsltest::Result r;
        rsltest::compile("surface arr() {\n  color a[2];\n  a[0] = diffuse(N);\n  Ci = a[0];\n}\n",
                         r, "arr.sl");
        ASSERT_TRUE(r.ok) << r.diags;
        EXPECT_EQ(rsl::collectInfo(*r.prog.shaders[0]).lightCoefficients,
                  "no (arr.sl:2:9: 'a' depends on the lights and is an array)");
    }
    rsl::EmittedShader plain = generate("surface p() { Ci = Cs * diffuse(N); }", "p.sl");
    EXPECT_TRUE(plain.lightCoefs);
    EXPECT_NE(plain.source.find("rsl_diffuse_light(g, _k"), std::string::npos) << plain.source;
}

}  // namespace
