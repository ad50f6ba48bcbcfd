// hoist_test.cpp: uniform work done once per shader instance (rsl2cl/src/hoist.h): which
// declarations the compiler hoists into the prepare function, and which it must not.
#include <gtest/gtest.h>

#include <algorithm>

#include "emit_cl.h"
#include "test_util.h"

namespace {

rsl::EmittedShader emit(const std::string& src) {
    rsltest::Result r;
    rsltest::compile(src, r);
    EXPECT_TRUE(r.ok) << r.diags;
    rsl::Diagnostics diag;
    rsl::EmittedShader out = rsl::emitOpenCL(*r.prog.shaders.at(0), r.prog, diag);
    EXPECT_TRUE(out.ok) << diag.text();
    return out;
}

bool hoisted(const rsl::EmittedShader& sh, const std::string& name) {
    return std::find(sh.hoisted.begin(), sh.hoisted.end(), name) != sh.hoisted.end();
}

}  // namespace

TEST(Hoist, UniformWorkOnParametersIsDoneOncePerInstance) {
    rsl::EmittedShader sh = emit(
        "surface s(float Kd = 0.5; float rough = 0.1; color tint = 1;) {\n"
        "    uniform float k = pow(Kd, 2) + sqrt(rough);\n"  // params only: hoisted
        "    color c = tint * k;\n"                          // inferred uniform, uses k
        "    matrix m = rotate(matrix 1, radians(90), vector(0, 0, 1));\n"
        "    float copy = Kd;\n"                             // no work: left alone
        "    float atP = k * xcomp(P);\n"                    // reads a varying global
        "    uniform float later = pow(Kd, 3);\n"
        "    later = 2;\n"                                   // assigned again: not hoisted
        "    uniform float e = length(E);\n"                 // a global: not hoisted
        "    Ci = c * atP * later * e * comp(m, 0, 0) + copy; Oi = 1;\n}\n");
    EXPECT_TRUE(hoisted(sh, "k"));
    EXPECT_TRUE(hoisted(sh, "c"));
    EXPECT_TRUE(hoisted(sh, "m"));
    EXPECT_FALSE(hoisted(sh, "copy"));
    EXPECT_FALSE(hoisted(sh, "atP"));
    EXPECT_FALSE(hoisted(sh, "later"));
    EXPECT_FALSE(hoisted(sh, "e"));
    EXPECT_EQ(sh.prepFunction, "rsl_prep_surface_s");
    EXPECT_EQ(sh.prepFloats, 1 + 3 + 16);
    EXPECT_EQ(sh.prepOffset, sh.spaceOffset + rsl::kSpaceFloats);
    // the body reads the slot; the prepare function computes it
    EXPECT_NE(sh.source.find("float v_k = params[" + std::to_string(sh.prepOffset) + "]"),
              std::string::npos)
        << sh.source;
    EXPECT_NE(sh.source.find("void rsl_prep_surface_s(__global float* params, "
                             "__global const float* scene)"),
              std::string::npos);
}

TEST(Hoist, NothingThatDependsOnTheShadingPointOrTheRenderer) {
    rsl::EmittedShader sh = emit(
        "float twice(float x) { return 2 * x; }\n"
        "surface s(float Kd = 0.5; color c = Cs;) {\n"
        "    uniform float a = twice(Kd);\n"             // a user function: left alone
        "    uniform color b = c * 2;\n"                 // c's default is computed per point
        "    uniform float n = noise(Kd);\n"             // pure builtin: hoisted
        "    float r = random();\n"                      // varying
        "    float f = 0; if (Kd > 0.25) { uniform float inner = pow(Kd, 2); f = inner; }\n"
        "    Ci = a * b * n * r * f; Oi = 1;\n}\n");
    EXPECT_FALSE(hoisted(sh, "a"));
    EXPECT_FALSE(hoisted(sh, "b"));
    EXPECT_TRUE(hoisted(sh, "n"));
    EXPECT_FALSE(hoisted(sh, "r"));
    EXPECT_FALSE(hoisted(sh, "inner")) << "only top-level declarations";
}

// A light's parameters are data in a block as a surface's are (RayDrive: a light edited
// between renders keeps the program), so its uniform work is prepared the same way.
TEST(Hoist, LightShadersPrepareTheirUniformWork) {
    rsl::EmittedShader sh = emit(
        "light l(float intensity = 1;) {\n"
        "    uniform float k = pow(intensity, 2);\n"
        "    illuminate(point(0, 0, 0)) { Cl = k; }\n}\n");
    EXPECT_EQ(sh.prepFunction, "rsl_prep_light_l");
    EXPECT_EQ(sh.prepFloats, 1);
    EXPECT_TRUE(hoisted(sh, "k"));
}

// A cone's cosine (illuminate, illuminance) is prepared once per instance when its angle
// is the instance's (a parameter, here inside a condition), folded by rsl2cl for a
// literal, and computed once per loop for an angle that varies: never per light.
TEST(Hoist, ConeCosinesArePreparedOnceOrFolded) {
    rsl::EmittedShader spot = emit(
        "light l(float coneangle = 0.5; point from = 0; vector axis = vector(0, 0, 1);) {\n"
        "    if (coneangle > 0) illuminate(from, axis, coneangle) { Cl = 1; }\n}\n");
    EXPECT_EQ(spot.prepFloats, 1);
    EXPECT_NE(spot.source.find("= rsl_cone_cos(p_coneangle);"), std::string::npos) << spot.source;
    EXPECT_EQ(spot.source.find("cos(p_coneangle)"), spot.source.find("rsl_cone_cos(p_coneangle)") + 9)
        << "only in the prepare function";
    rsl::EmittedShader literal = emit(
        "light l(point from = 0;) {\n"
        "    illuminate(from, vector(0, 0, 1), 0.5) { Cl = 1; }\n}\n");
    EXPECT_EQ(literal.prepFloats, 0);
    EXPECT_EQ(literal.source.find("cos("), std::string::npos) << literal.source;
    EXPECT_NE(literal.source.find("0.877581"), std::string::npos) << "cos(0.5) - 1e-6, folded";
    rsl::EmittedShader varying = emit(
        "surface s() {\n    float a = s * 1.5;\n"
        "    illuminance(P, N, a) { Ci += Cl; }\n    Oi = 1;\n}\n");
    EXPECT_EQ(varying.prepFloats, 0);
    const size_t c = varying.source.find("rsl_cone_cos(");
    ASSERT_NE(c, std::string::npos) << varying.source;
    EXPECT_LT(c, varying.source.find("for (int _l")) << "before the light loop";
}

// A parameter the body assigns is no longer the instance's value: nothing computed from
// it is hoisted.
TEST(Hoist, AssignedParametersAreNotTheInstancesValue) {
    rsl::EmittedShader sh = emit(
        "surface s(float Kd = 0.5; matrix m = 1;) {\n"
        "    setcomp(m, 0, 1, 2);\n"
        "    Kd = Kd * 2;\n"
        "    uniform float k = pow(Kd, 2);\n"
        "    matrix r = m * determinant(m);\n"
        "    Ci = k * comp(r, 0, 1); Oi = 1;\n}\n");
    EXPECT_FALSE(hoisted(sh, "k"));
    EXPECT_FALSE(hoisted(sh, "r"));
}

// Parameters a primitive gives per point (rsl_abi.h, PER-POINT PARAMETERS): only where
// the renderer defines RSL_MAX_PARAM_PRIMVARS, the surface takes g->pv_value for the
// parameter at that block offset (floats and triples; arrays and strings never), and
// its hoisted work is computed at the point while pv_count > 0. The render tests are in
// tests/host/point_params_test.cpp.
TEST(Hoist, PerPointParametersReplaceTheBlockValueAndTheHoistedWork) {
    rsl::EmittedShader sh = emit(
        "surface s(float Kd = 0.5; color tint = 1; string map = \"\"; float w[2] = {1, 2};) {\n"
        "    uniform float k = pow(Kd, 2);\n"
        "    Ci = tint * k * w[0]; Oi = 1;\n}\n");
    ASSERT_TRUE(hoisted(sh, "k"));
    auto offset = [&](const std::string& name) {
        for (const rsl::ParamSlot& p : sh.params)
            if (p.name == name) return std::to_string(p.offset);
        return std::string("?");
    };
    EXPECT_NE(sh.source.find("#ifdef RSL_MAX_PARAM_PRIMVARS"), std::string::npos) << sh.source;
    EXPECT_NE(sh.source.find("case " + offset("Kd") + ": p_Kd = g->pv_value[_k].x;"),
              std::string::npos) << sh.source;
    EXPECT_NE(sh.source.find("case " + offset("tint") +
                             ": p_tint = rsl_pv_color(g->pv_value, _k);"),
              std::string::npos)
        << sh.source;
    EXPECT_EQ(sh.source.find("p_map = g->pv_value"), std::string::npos);
    EXPECT_EQ(sh.source.find("p_w = g->pv_value"), std::string::npos);
    EXPECT_NE(sh.source.find("float v_k = g->pv_count > 0 ?"), std::string::npos) << sh.source;
    // the prepare function and light shaders have no per-point values
    const std::string prep = sh.source.substr(sh.source.find("void " + sh.prepFunction));
    EXPECT_EQ(prep.find("pv_"), std::string::npos) << prep;
    rsl::EmittedShader light = emit("light l(float intensity = 1;) {\n"
                                    "    illuminate(point(0, 0, 0)) { Cl = intensity; }\n}\n");
    EXPECT_EQ(light.source.find("pv_"), std::string::npos) << light.source;
    // a displacement takes them by its own slots, where the renderer says some does
    rsl::EmittedShader disp = emit(
        "displacement d(float h = 0.5;) {\n"
        "    uniform float k = pow(h, 2);\n"
        "    P += k * normalize(N);\n}\n");
    ASSERT_TRUE(hoisted(disp, "k"));
    const std::string both =
        "#if defined(RSL_MAX_PARAM_PRIMVARS) && defined(RSL_DISPLACEMENT_PRIMVARS)";
    EXPECT_NE(
        disp.source.find(both + "\n  for (int _k = 0; _k < g->pv_count; ++_k) switch "
                                "(g->pv_dslot[_k]) { case 0: p_h = g->pv_value[_k].x;"),
        std::string::npos)
        << disp.source;
    EXPECT_NE(disp.source.find(both + "\n  float v_k = g->pv_count > 0 ?"),
              std::string::npos)
        << disp.source;
    EXPECT_EQ(disp.source.find("pv_slot"), std::string::npos) << disp.source;
}
