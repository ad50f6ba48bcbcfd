// affine_test.cpp: the static check that Ci is affine in trace() results and light Cl:
// non-affine shaders are rejected with exact diagnostics; affine ones evaluate to the
// expected coefficients in each mode on the device.
#include <gtest/gtest.h>

#include "emit_cl.h"
#include "test_util.h"
#include "testshade.h"

namespace {

// What a shader not affine in Cl alone is told (a warning: it is shaded light by light)
#define kLightByLight                                                                  \
    "; each light is shaded on its own and its shadow scales its part (exact for one " \
    "light or lights whose parts add)"

// Diagnostics of compiling and generating code for src (named name).
std::string codegenDiags(const std::string& src, const std::string& name) {
    rsltest::Result r;
    rsltest::compile(src, r, name);
    if (!r.ok) return "front end: " + r.diags;
    rsl::Diagnostics diag;
    rsl::EmittedShader em = rsl::emitOpenCL(*r.prog.shaders[0], r.prog, diag);
    EXPECT_EQ(em.ok, !diag.hasErrors());
    return diag.text();
}

TEST(Affine, ProductOfTwoTraces) {
    EXPECT_EQ(codegenDiags("surface a1(float Kr = 1;)\n"
                           "{\n"
                           "    vector R = reflect(I, N);\n"
                           "    color c = trace(P, R);\n"
                           "    Ci = Kr * c * trace(P, -R);\n"
                           "}\n",
                           "glass.sl"),
              "glass.sl:5:17: error: Ci is not affine in trace(): product of two trace() "
              "results in '((Kr * c) * trace(P, -R))'\n");
}

// gather() (gather.cpp): Ci stays affine in what its rays bring back only while a
// variable declared outside the loop changes in it by += and -=; an output gather()
// cannot give is refused; a sum is accepted.
TEST(Affine, GatherLoopsAreSums) {
    auto diags = [](const std::string& body) {
        return codegenDiags(
            "surface s()\n{\n    color c = 0, hitc = 0;\n" + body + "    Ci = c;\n}\n",
            "s.sl");
    };
    EXPECT_EQ(
        diags("    gather(\"\", P, N, 0.5, 4, \"surface:Ci\", hitc) { c = hitc; }\n"),
        "s.sl:4:54: error: Ci is not affine in trace(): 'c' (declared outside the gather "
        "loop) changed by '=' in it; only += and -= keep it a sum over the rays in "
        "'c = hitc'\n");
    EXPECT_EQ(
        diags("    float l = 0;\n    gather(\"\", P, N, 0.5, 4, \"primitive:N\", l) "
              "{ c += 1; }\n"),
        "front end: s.sl:5:30: error: gather(): \"primitive:N\" is not supported "
        "(outputs: \"surface:Ci\", \"ray:length\", \"primitive:P\", \"ray:direction\", "
        "\"ray:origin\"; inputs: \"maxdist\", \"distribution\")\n");
    // "primitive:P" (origin + direction x length) is a sum's term, its components too
    EXPECT_EQ(
        diags("    point q = 0;\n    gather(\"\", P, N, 0.5, 4, \"primitive:P\", q) "
              "{ c += zcomp(q); }\n"),
        "");
    // a traced colour made a point is not (its channels would be mixed by zcomp())
    EXPECT_EQ(
        codegenDiags("surface t()\n{\n    color c = trace(P, N);\n"
                     "    Ci = zcomp(point(c));\n}\n",
                     "t.sl"),
        "t.sl:4:16: error: Ci is not affine in trace(): a trace() result made a point, "
        "vector or normal in 'point c'\n");
    // the distance is a ray's result too: a sum of it, not a product
    EXPECT_EQ(
        diags(
            "    float l = 0, s = 0;\n    gather(\"\", P, N, 0.5, 4, \"ray:length\", l) "
            "{ s += l * l; }\n"),
        "s.sl:5:56: error: Ci is not affine in trace(): product of two trace() results "
        "in '(l * l)'\n");
    EXPECT_EQ(
        diags("    gather(\"\", P, N, 0.5, 4, \"surface:Ci\", hitc) { c += hitc; }\n"),
        "");
}

TEST(Affine, TraceInCondition) {
    EXPECT_EQ(codegenDiags("surface a2()\n{\n    color c = trace(P, N);\n"
                           "    if (c == color 1)\n        Ci = 1;\n}\n",
                           "a2.sl"),
              "a2.sl:4:11: error: Ci is not affine in trace(): a trace() result used in a "
              "comparison in '(c == color 1)'\n");
    EXPECT_EQ(codegenDiags("surface a2()\n{\n    color c = trace(P, N);\n"
                           "    Ci = (comp(c, 0) > 0.5) ? 1 : 0;\n}\n",
                           "a2.sl"),
              "a2.sl:4:11: error: Ci is not affine in trace(): a trace() result passed to comp() "
              "in 'comp(c, 0)'\n");
}

TEST(Affine, ClProductAndDivisionByTrace) {
    EXPECT_EQ(
        codegenDiags("surface a3()\n{\n    color c = 0;\n    illuminance(P) {\n"
                     "        c += Cl * Cl;\n    }\n    Ci = Cs / trace(P, N);\n}\n",
                     "a3.sl"),
        "a3.sl:7:13: error: Ci is not affine in trace(): division by a trace() result in "
        "'(Cs / trace(P, N))'\n");
    // Cl alone: a warning, and the shader compiles (light by light: no coefficients)
    EXPECT_EQ(codegenDiags("surface a3()\n{\n    color c = 0;\n    illuminance(P) {\n"
                           "        c += Cl * Cl;\n    }\n    Ci = c;\n}\n",
                           "a3.sl"),
              "a3.sl:5:17: warning: Ci is not affine in Cl: product of two Cl values in "
              "'(Cl * Cl)'" kLightByLight "\n");
}

TEST(Affine, TaintFlowsThroughVariablesAndFunctions) {
    // the product only appears through a loop-carried variable and a user function
    EXPECT_EQ(codegenDiags("color tr() { return trace(P, N); }\n"
                           "surface a5()\n{\n    color t = tr();\n    color u = 1;\n"
                           "    for (u = 1; 1 > 0; u = t) { Ci = u * t; break; }\n}\n",
                           "a5.sl"),
              "a5.sl:6:40: error: Ci is not affine in trace(): product of two trace() results "
              "in '(u * t)'\n");
}

TEST(Affine, BuiltinsUserFunctionsMixWeightAndOi) {
    EXPECT_EQ(
        codegenDiags("color refl(color x) { return x * x; }\n"
                     "surface a4()\n{\n    color t = trace(P, N);\n"
                     "    Ci = refl(t) + mix(Cs, Os, comp(diffuse(N), 1));\n"
                     "    Ci += mix(Cs, t, 0.5) + clamp(t, color 0, color 1);\n"
                     "    Oi = t;\n}\n",
                     "a4.sl"),
        "a4.sl:1:32: error: Ci is not affine in trace(): product of two trace() "
        "results in '(x * x)'\n"
        "a4.sl:6:29: error: Ci is not affine in trace(): a trace() result passed to "
        "clamp() "
        "in 'clamp(t, color 0, color 1)'\n"
        "a4.sl:7:8: error: Oi must not depend on trace() (opacity is needed before any "
        "ray is cast)\n");
    EXPECT_EQ(codegenDiags("surface a6()\n{\n    color t = trace(P, N);\n"
                           "    Ci = (t . Cs) * Cs;\n}\n", "a6.sl"),
              "a6.sl:4:13: error: Ci is not affine in trace(): a trace() result used in a dot "
              "or cross product in '(t . Cs)'\n");
}

TEST(Affine, StandardShadersAreAffine) {
    for (const char* n : {"glass", "mirror", "plastic", "matte", "metal", "shinymetal",
                          "paintedplastic", "constant", "fog", "depthcue"}) {
        std::string src = rsltest::readFile(std::string(RSL2CL_SHADER_DIR) + "/" + n + ".sl");
        std::string d = codegenDiags(src, n);
        EXPECT_EQ(d.find("error"), std::string::npos) << n << ": " << d;
    }
}

const char* kAffineOk =
    "surface ok(float Kr = .5;)\n"
    "{\n"
    "    color t = trace(P, N);\n"
    "    color c = 0;\n"
    "    illuminance(P, N, 1.5708) { c += Cl * Cs / 2; }\n"
    "    Ci = -(Kr * t) / 2 + mix(t, c, Kr) + ((Kr > 0) ? t : c) + color(0.25);\n"
    "    Ci *= Os;\n"
    "}\n";

TEST(Affine, AllowedOperationsEvaluatePerMode) {
    EXPECT_EQ(codegenDiags(kAffineOk, "ok.sl"), "");
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kAffineOk, "ok.sl", &err)) << err;
    ts::Scene sc;
    sc.lights.push_back({{0, 0, 1}, {0.8f, 0.4f, 0.2f}});
    auto pts = ts::grid(2);
    for (auto& p : pts) p.Os[0] = 0.5f, p.Os[1] = 1.0f, p.Os[2] = 0.25f;
    auto base = sh.run(pts, sc, -1, -1);
    auto tr = sh.run(pts, sc, -1, 0);
    auto li = sh.run(pts, sc, 0, -1);
    ASSERT_EQ(base.size(), 4u);
    ASSERT_EQ(tr.size(), 4u);
    ASSERT_EQ(li.size(), 4u);
    const float Kr = 0.5f, Cl[3] = {0.8f, 0.4f, 0.2f};
    for (size_t i = 0; i < base.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            float os = pts[i].Os[c];
            EXPECT_NEAR(base[i].Ci[c], 0.25f * os, 1e-6f);
            EXPECT_NEAR(tr[i].Ci[c] - base[i].Ci[c], (-Kr / 2 + (1 - Kr) + 1) * os, 1e-6f);
            EXPECT_NEAR(li[i].Ci[c] - base[i].Ci[c], Kr * Cl[c] / 2 * os, 1e-6f);
        }
}

}  // namespace

// Taint follows the code: a variable assigned an untainted value is clean from there on
// (the RenderMan Companion's txtplastic: Ci holds the texture colour, then is multiplied by
// diffuse()), while branches join and loops (light loops too) carry it round. Before,
// taint was per variable: Ci's final value made its first use a product of two Cl values.
TEST(Affine, TaintFollowsTheCode) {
    auto diags = [](const std::string& body) {
        return codegenDiags("surface f(float Ka = 1, Kd = 0.5;)\n{\n"
                            "    normal Nf = faceforward(normalize(N), I);\n" +
                                body + "}\n",
                            "f.sl");
    };
    EXPECT_EQ(diags("    Ci = Cs;\n"
                    "    Ci = Os * (Ci * (Ka * ambient() + Kd * diffuse(Nf)));\n"),
              "");
    EXPECT_EQ(diags("    Ci = Cs;\n    Ci *= Ka * ambient() + Kd * diffuse(Nf);\n"), "");
    EXPECT_EQ(diags("    color x = diffuse(Nf);\n    Ci = x;\n    x = Cs;\n"
                    "    Ci += x * diffuse(Nf);\n"),
              "");
    // one branch may leave x tainted: the product after the if is refused
    EXPECT_EQ(diags("    color x = diffuse(Nf);\n    if (u > 0.5) x = Cs;\n"
                    "    Ci = x * diffuse(Nf);\n"),
              "f.sl:6:12: warning: Ci is not affine in Cl: product of two Cl values in "
              "'(x * diffuse(Nf))'" kLightByLight "\n");
    // a light loop's next light sees what the last one left
    EXPECT_EQ(diags("    color x = Cs, c = 0;\n"
                    "    illuminance(P) {\n        c += x * Cl;\n        x = Cl;\n    }\n"
                    "    Ci = c;\n"),
              "f.sl:6:16: warning: Ci is not affine in Cl: product of two Cl values in "
              "'(x * Cl)'" kLightByLight "\n");
}
