// abi_test.cpp: the parts of the rsl_abi.h contract beyond shading itself, run on the
// device with testshade: per-instance "shader"/"object" matrices after the parameter
// block, output parameters written back to RslEval::outputs, and message passing
// (lightsource() in illuminance, attribute(), option(), surface() from a light).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>

#include "emit_cl.h"
#include "testshade.h"

namespace {

#define REQUIRE_DEVICE() \
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device"

const rsl::ParamSlot* slot(const rsl::EmittedShader& sh, const std::string& name) {
    for (const rsl::ParamSlot& p : sh.params)
        if (p.name == name) return &p;
    return nullptr;
}

void expectCi(const std::vector<ts::Out>& out, const std::vector<ts::Point>& pts,
              const std::function<std::array<float, 3>(const ts::Point&)>& want, const char* what) {
    ASSERT_EQ(out.size(), pts.size()) << what;
    for (size_t i = 0; i < pts.size(); ++i) {
        std::array<float, 3> w = want(pts[i]);
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(out[i].Ci[c], w[c], 1e-4f) << what << ": point " << i << " channel " << c;
    }
}

// ---- 1. spaces ------------------------------------------------------------------------
const char* kSpaces =
    "point toShader(point q) { return transform(\"shader\", q); }\n"
    "surface spaces(float which = 0;)\n{\n"
    "  if (which == 0) Ci = color(transform(\"shader\", P));\n"
    "  else if (which == 1) Ci = color(point \"shader\" (1, 1, 1));\n"
    "  else if (which == 2) Ci = color(vtransform(\"shader\", vector(2, 4, 6)));\n"
    "  else if (which == 3) Ci = color(transform(\"object\", P));\n"
    "  else if (which == 4) Ci = color(transform(\"shader\", \"object\", P));\n"
    "  else if (which == 5) Ci = color(toShader(P));\n"
    "  else Ci = color(vector \"object\" (1, 2, 3));\n"
    "}\n";

TEST(Abi, ShaderAndObjectSpacesFromTheBlock) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kSpaces, "spaces.sl", &err)) << err;
    EXPECT_EQ(sh.shader.spaceOffset, sh.shader.paramFloats);
    // the host's count of the floats after a block is the runtime's, defined once
    const std::string runtime = rsl::runtimeSource();
    const std::string define = "#define RSL_SPACE_FLOATS ";
    const size_t at = runtime.find(define);
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(std::stoi(runtime.substr(at + define.size())), rsl::kSpaceFloats);
    EXPECT_EQ(runtime.find(define, at + 1), std::string::npos);
    EXPECT_NE(sh.shader.source.find("_sp.spaces = params + 1;"), std::string::npos)
        << sh.shader.source;
    ts::Scene sc;
    // shader: scale 2 then translate (1, 2, 3); object: translate (5, 0, 0)
    float S[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
    float O[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
    std::copy(S, S + 16, sc.shaderMatrix);
    std::copy(O, O + 16, sc.objectMatrix);
    auto pts = ts::grid(3);
    using A = std::array<float, 3>;
    std::vector<std::pair<const char*, std::function<A(const ts::Point&)>>> cases = {
        {"transform(shader, P)",
         [](const ts::Point& p) { return A{(p.P[0] - 1) / 2, (p.P[1] - 2) / 2, (p.P[2] - 3) / 2}; }},
        {"point shader (1,1,1)", [](const ts::Point&) { return A{3, 4, 5}; }},
        {"vtransform(shader)", [](const ts::Point&) { return A{1, 2, 3}; }},
        {"transform(object, P)", [](const ts::Point& p) { return A{p.P[0] - 5, p.P[1], p.P[2]}; }},
        {"transform(shader, object, P)",
         [](const ts::Point& p) { return A{2 * p.P[0] + 1 - 5, 2 * p.P[1] + 2, 2 * p.P[2] + 3}; }},
        {"user function",
         [](const ts::Point& p) { return A{(p.P[0] - 1) / 2, (p.P[1] - 2) / 2, (p.P[2] - 3) / 2}; }},
        {"vector object (1,2,3)", [](const ts::Point&) { return A{1, 2, 3}; }},
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        sh.setParam("which", {float(i)});
        expectCi(sh.run(pts, sc), pts, cases[i].second, cases[i].first);
    }
}

TEST(Abi, SpacesAreNotReadWhenUnused) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface flat(float Kd = 1;) { Ci = Kd * Cs; }", "flat.sl", &err)) << err;
    EXPECT_EQ(sh.shader.spaceOffset, 1);
    EXPECT_EQ(sh.shader.source.find("_sp.spaces"), std::string::npos) << sh.shader.source;
}

// ---- 2. output parameters -------------------------------------------------------------
const char* kOutputs =
    "surface outs(float Kd = 0.5; output varying float f = 1; output varying color oc = 0;\n"
    "             output varying point op = 0; output float arr[2] = {7, 8};\n"
    "             output varying string tag = \"none\";)\n{\n"
    "  Ci = Cs;\n"
    "  f = Kd * 4; oc = color(s, t, 1); op = P; arr[1] = 9;\n"
    "  if (s > 0.75) { f = -2; return; }\n"
    "  tag = \"done\";\n"
    "}\n";

TEST(Abi, OutputParametersWrittenBack) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kOutputs, "outs.sl", &err)) << err;
    ASSERT_TRUE(slot(sh.shader, "Kd") && slot(sh.shader, "tag"));
    EXPECT_EQ(slot(sh.shader, "Kd")->outputOffset, -1);
    EXPECT_EQ(slot(sh.shader, "f")->outputOffset, 0);
    EXPECT_EQ(slot(sh.shader, "oc")->outputOffset, 1);
    EXPECT_EQ(slot(sh.shader, "op")->outputOffset, 4);
    EXPECT_EQ(slot(sh.shader, "arr")->outputOffset, 7);
    EXPECT_EQ(slot(sh.shader, "tag")->outputOffset, 9);
    EXPECT_EQ(sh.shader.outputFloats, 10);
    sh.setParam("Kd", {0.25f});
    ts::Scene sc;
    auto pts = ts::grid(5);
    auto out = sh.run(pts, sc);
    ASSERT_EQ(out.size(), pts.size());
    for (size_t i = 0; i < pts.size(); ++i) {
        const float* o = out[i].outputs;
        const ts::Point& p = pts[i];
        bool early = p.s > 0.75f;
        EXPECT_FLOAT_EQ(o[0], early ? -2.0f : 1.0f) << i;
        EXPECT_FLOAT_EQ(o[1], p.s);
        EXPECT_FLOAT_EQ(o[2], p.t);
        EXPECT_FLOAT_EQ(o[3], 1.0f);
        for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(o[4 + c], p.P[c]);
        EXPECT_FLOAT_EQ(o[7], 7.0f);
        EXPECT_FLOAT_EQ(o[8], 9.0f);
        EXPECT_FLOAT_EQ(o[9], float(rsl::stringId(early ? "none" : "done")));
        EXPECT_FLOAT_EQ(o[10], -12345.0f);  // untouched past the outputs
    }
}

TEST(Abi, OutputsThatDoNotFitWarn) {
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface big(output matrix a = 1; output matrix b = 1;\n"
                                 "            output float c = 0;) { Ci = Cs; }",
                                 "big.sl", &err))
        << err;
    EXPECT_EQ(slot(sh.shader, "a")->outputOffset, 0);
    EXPECT_EQ(slot(sh.shader, "b")->outputOffset, 16);
    EXPECT_EQ(slot(sh.shader, "c")->outputOffset, -1);
    EXPECT_NE(err.find("does not fit"), std::string::npos) << err;
}

// ---- 3. message passing ----------------------------------------------------------------
const char* kMessages =
    "surface msg(float which = 0;)\n{\n"
    "  color acc = 0;\n"
    "  illuminance(P) {\n"
    "    float intensity = -1; color lc = color(-1);\n"
    "    float got = lightsource(\"intensity\", intensity);\n"
    "    lightsource(\"lightcolor\", lc);\n"
    "    acc += color(got, intensity, comp(lc, 1));\n"
    "  }\n"
    "  string id = \"\"; float fmt[3] = {0, 0, 0}; float x = -1;\n"
    "  if (which == 0) Ci = acc;\n"
    "  else if (which == 1) { float ga = attribute(\"identifier:name\", id);\n"
    "                         Ci = color(ga, id == \"mesh1\" ? 1 : 0, id == \"other\" ? 1 : 0); }\n"
    "  else if (which == 2) { float go = option(\"Format\", fmt); Ci = color(fmt[0], fmt[1], fmt[2] + go); }\n"
    "  else if (which == 3) Ci = color(option(\"Format\", x), x, attribute(\"nope\", x));\n"
    "  else Ci = color(lightsource(\"intensity\", x), x, 0);\n"
    "}\n";

TEST(Abi, MessagePassingServices) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kMessages, "msg.sl", &err)) << err;
    ts::Scene sc;
    sc.lights.push_back({{0, 0, 1}, {1, 1, 1}});
    sc.lights.push_back({{0, 1, 0}, {1, 1, 1}});
    sc.lightParams.push_back({0, "intensity", {3}});
    sc.lightParams.push_back({0, "lightcolor", {0.1f, 0.2f, 0.3f}});
    sc.lightParams.push_back({1, "lightcolor", {0.5f, 0.75f, 1}});
    sc.attributes.push_back({-1, "identifier:name", {float(rsl::stringId("mesh1"))}});
    sc.options.push_back({-1, "Format", {640, 480, 1}});
    auto pts = ts::grid(2);
    using A = std::array<float, 3>;
    // light 0: found, 3, 0.2; light 1: not found, -1, 0.75
    std::vector<A> want = {{1, 2, 0.95f}, {1, 1, 0}, {640, 480, 2}, {0, -1, 0}, {0, -1, 0}};
    for (size_t i = 0; i < want.size(); ++i) {
        sh.setParam("which", {float(i)});
        expectCi(sh.run(pts, sc), pts, [&](const ts::Point&) { return want[i]; },
                 ("case " + std::to_string(i)).c_str());
    }
}

TEST(Abi, SurfaceFromALightIsNotFound) {
    REQUIRE_DEVICE();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("light lt(float intensity = 2;)\n{\n  float y = -1;\n"
                                 "  float got = surface(\"Kd\", y);\n"
                                 "  illuminate(P) Cl = color(got, y, intensity);\n}\n",
                                 "lt.sl", &err))
        << err;
    ts::Scene sc;
    auto pts = ts::grid(2);
    auto out = sh.run(pts, sc);
    ASSERT_EQ(out.size(), pts.size());
    for (const ts::Out& o : out) {
        EXPECT_FLOAT_EQ(o.Cl[0], 0.0f);
        EXPECT_FLOAT_EQ(o.Cl[1], -1.0f);
        EXPECT_FLOAT_EQ(o.Cl[2], 2.0f);
    }
}

}  // namespace
