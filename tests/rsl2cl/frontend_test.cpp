// frontend_test.cpp: the standard shaders compile cleanly; overloads, return-type
// polymorphism, uniform/varying inference and --info metadata.
#include <gtest/gtest.h>

#include "builtins.h"
#include "test_util.h"

namespace {

using rsltest::Result;

class StandardShader : public ::testing::TestWithParam<std::string> {};

TEST_P(StandardShader, CompilesCleanly) {
    std::string path = GetParam();
    rsl::Diagnostics diag;
    rsl::Program prog;
    EXPECT_TRUE(rsl::compileFile(path, {}, prog, diag)) << diag.text();
    EXPECT_EQ(diag.text(), "");
    ASSERT_EQ(prog.shaders.size(), 1u);
    rsl::ShaderInfo info = rsl::collectInfo(*prog.shaders[0]);
    for (const rsl::ParamInfo& p : info.params) EXPECT_TRUE(p.constantDefault) << p.name;
}

INSTANTIATE_TEST_SUITE_P(
    Rsl2cl, StandardShader,
    ::testing::Values(
        RSL2CL_SHADER_DIR "/constant.sl", RSL2CL_SHADER_DIR "/matte.sl",
        RSL2CL_SHADER_DIR "/metal.sl", RSL2CL_SHADER_DIR "/shinymetal.sl",
        RSL2CL_SHADER_DIR "/plastic.sl", RSL2CL_SHADER_DIR "/paintedplastic.sl",
        RSL2CL_SHADER_DIR "/ambientlight.sl", RSL2CL_SHADER_DIR "/distantlight.sl",
        RSL2CL_SHADER_DIR "/pointlight.sl", RSL2CL_SHADER_DIR "/spotlight.sl",
        RSL2CL_SHADER_DIR "/bumpy.sl", RSL2CL_SHADER_DIR "/depthcue.sl",
        RSL2CL_SHADER_DIR "/fog.sl", RSL2CL_SHADER_DIR "/shadowspot.sl",
        RSL2CL_SHADER_DIR "/shadowpoint.sl", RSL2CL_SHADER_DIR "/shadowdistant.sl",
        RSL2CL_SHADER_DIR "/arealight.sl", RSL2CL_SHADER_DIR "/glass.sl",
        RSL2CL_SHADER_DIR "/mirror.sl", RSL2CL_TEST_DATA "/spd.sl"));

TEST(Info, PlasticMatchesGolden) {
    rsl::Diagnostics diag;
    rsl::Program prog;
    ASSERT_TRUE(rsl::compileFile(RSL2CL_SHADER_DIR "/plastic.sl", {}, prog, diag));
    EXPECT_EQ(rsl::formatInfo(rsl::collectInfo(*prog.shaders[0])),
              rsltest::readFile(RSL2CL_TEST_DATA "/plastic.info"));
}

TEST(Info, ServicesAndTextures) {
    Result r;
    rsltest::compile(
        "surface s(string env = \"sky.tex\") {\n"
        "  color c = color texture(\"wood.tex\"[1], s, t) + trace(P, N);\n"
        "  float a = area(P) + Du(s);\n"
        "  Ci = c * a + color environment(env, I);\n}\n", r);
    ASSERT_TRUE(r.ok) << r.diags;
    rsl::ShaderInfo info = rsl::collectInfo(*r.prog.shaders[0]);
    EXPECT_EQ(info.services, (std::set<std::string>{"derivatives", "environment", "texture",
                                                    "trace"}));
    EXPECT_EQ(info.textures, std::set<std::string>{"wood.tex"});
    EXPECT_EQ(info.derivatives, (std::set<std::string>{"Du", "area"}));
    EXPECT_EQ(info.globalsWritten, std::set<std::string>{"Ci"});
    EXPECT_EQ(info.params[0].value.text(), "\"sky.tex\"");
}

TEST(Info, Defaults) {
    Result r;
    rsltest::compile("light l(color c = color \"hsv\" (0.5, 1, 1); point p = (1, 2, 3) * 2;\n"
                     "  float f = -(1 + 2) / 4; output varying float o = 0;\n"
                     "  float arr[3] = {1, 2, 3}; matrix m = 1; float g = time;) { }\n", r);
    ASSERT_TRUE(r.ok) << r.diags;
    rsl::ShaderInfo info = rsl::collectInfo(*r.prog.shaders[0]);
    ASSERT_EQ(info.params.size(), 7u);
    EXPECT_EQ(info.params[0].value.text(), "\"hsv\" [0.5 1 1]");
    EXPECT_EQ(info.params[1].value.text(), "[2 4 6]");
    EXPECT_EQ(info.params[2].value.text(), "-0.75");
    EXPECT_TRUE(info.params[3].output);
    EXPECT_TRUE(info.params[3].varying);
    EXPECT_EQ(info.params[4].value.text(), "[1 2 3]");
    EXPECT_EQ(info.params[5].value.text(), "[1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]");
    EXPECT_FALSE(info.params[6].constantDefault);
    EXPECT_EQ(info.params[6].defaultText, "time");
}

// The call expression initialising variable `name` (first declaration with that name).
const rsl::Expr* initOf(const rsl::Stmt& s, const std::string& name) {
    for (const rsl::VarDecl& d : s.decls)
        if (d.name == name) return d.init.get();
    for (const auto& c : s.stmts)
        if (const rsl::Expr* e = initOf(*c, name)) return e;
    return nullptr;
}

TEST(Overload, NoiseReturnTypeFromContext) {
    Result r;
    rsltest::compile("surface s() {\n  color c = noise(P);\n  float f = noise(P);\n"
                     "  point p = noise(s, t);\n  vector v = 2 * pnoise(P, point 4);\n"
                     "  color k = cellnoise(s);\n  Ci = c + f + color p + color v + k;\n}\n", r);
    ASSERT_TRUE(r.ok) << r.diags;
    const rsl::Stmt& body = *r.prog.shaders[0]->body;
    EXPECT_EQ(initOf(body, "c")->sig->code, "cp");
    EXPECT_EQ(initOf(body, "f")->sig->code, "fp");
    EXPECT_EQ(initOf(body, "p")->sig->code, "pff");
    EXPECT_EQ(initOf(body, "v")->args[1]->sig->code, "vpp");
    EXPECT_EQ(initOf(body, "k")->sig->code, "cf");
}

TEST(Overload, CoercionsAndChannels) {
    Result r;
    rsltest::compile("surface s(string map = \"\") {\n"
                     "  vector v = normalize(N);\n  normal n = normalize(v);\n"
                     "  float x = min(1, 2, 3, u);\n  color c = mix(Cs, 1, 0.5);\n"
                     "  float ch = texture(map[2], s, t, \"blur\", 0.1);\n"
                     "  Ci = c * x * ch * (v . n) + (v ^ n) . N;\n}\n", r);
    ASSERT_TRUE(r.ok) << r.diags;
    const rsl::Stmt& body = *r.prog.shaders[0]->body;
    EXPECT_EQ(initOf(body, "v")->sig->code, "nn");
    EXPECT_EQ(initOf(body, "c")->sig->code, "cccf");
    const rsl::Expr* tex = initOf(body, "ch");
    ASSERT_TRUE(tex->channel != nullptr);
    EXPECT_EQ(tex->sig->code, "fsff*");
}

TEST(Varying, Inference) {
    Result r;
    rsltest::compile(
        "surface s(float Kd = 1; varying float vk = 0) {\n"
        "  float a = Kd * 2;\n"         // uniform: from uniform parameter
        "  float b = a + s;\n"          // varying: s is a varying global
        "  float c = 0;\n"
        "  if (u > 0.5) c = 1;\n"       // varying: assigned under varying condition
        "  float d = 0;\n"
        "  if (Kd > 0.5) d = 1;\n"      // uniform condition: stays uniform
        "  float e = vk;\n"             // varying parameter
        "  float f = 0, g = 0;\n"
        "  f = g; g = t;\n"             // loop-free chain: f stays uniform? no: g varies
        "  float h = 0; uniform float i;\n"
        "  for (i = 0; i < 3; i += 1) h += i;\n"  // uniform loop
        "  float j = length(P) * 0 + time;\n"
        "  Ci = a + b + c + d + e + f + g + h + j;\n}\n", r);
    ASSERT_TRUE(r.ok) << r.diags;
    auto varying = [&](const char* n) { return rsltest::findSymbol(r.prog, n)->varying; };
    EXPECT_FALSE(varying("a"));
    EXPECT_TRUE(varying("b"));
    EXPECT_TRUE(varying("c"));
    EXPECT_FALSE(varying("d"));
    EXPECT_TRUE(varying("e"));
    EXPECT_TRUE(varying("f"));  // f = g before g = t, but g is one variable: varying
    EXPECT_TRUE(varying("g"));
    EXPECT_FALSE(varying("h"));
    EXPECT_FALSE(varying("i"));
    EXPECT_TRUE(varying("j"));
}

TEST(Varying, FunctionsAndLightLoops) {
    Result r;
    rsltest::compile(
        "float sq(float x) { return x * x; }\n"
        "float lit() { return s; }\n"
        "surface t2(float Kd = 1) {\n"
        "  float a = sq(Kd);\n"          // uniform argument, pure function
        "  float b = sq(u);\n"           // varying argument
        "  float c = lit();\n"           // reads a varying global
        "  color acc = 0;\n"
        "  illuminance(P, N, 1.57) { acc += Cl; }\n"
        "  float k = 0;\n"
        "  illuminance(P) { k = 1; }\n"  // written in a light loop
        "  Ci = acc * a * b * c * k;\n}\n", r);
    ASSERT_TRUE(r.ok) << r.diags;
    auto varying = [&](const char* n) { return rsltest::findSymbol(r.prog, n)->varying; };
    EXPECT_TRUE(varying("b"));
    EXPECT_TRUE(varying("c"));
    EXPECT_TRUE(varying("acc"));
    EXPECT_TRUE(varying("k"));
    // sq is called with both, so its parameter is varying, and so is its result: the
    // conservative answer, a can be computed once only if sq were specialised.
    EXPECT_TRUE(varying("x"));
}

TEST(Parse, ConstructsAndNestedFunctions) {
    Result r;
    rsltest::compile(
        "surface s(float n = 3; output varying float outv = 0;) {\n"
        "  float total = 0;\n"
        "  float add(float a; float b) { extern float total; total += a; return a + b; }\n"
        "  uniform float i, j;\n"
        "  for (i = 0; i < n; i += 1) {\n"
        "    j = 0;\n"
        "    while (j < 3) { j += 1; if (j == 2) continue; if (i > 5) break 2; }\n"
        "  }\n"
        "  matrix m = matrix \"world\" (1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1);\n"
        "  point q = transform(\"object\", P) + point \"world\" (0, 0, 1);\n"
        "  float x = (n > 2) ? add(1, 2) : comp(m, 0, 0);\n"
        "  string name = \"a\\\"b\";\n"
        "  float found = surface(\"Kd\", x) + attribute(\"identifier:name\", name);\n"
        "  setcomp(Ci, 0, x);\n"
        "  outv = x + found + xcomp(q);\n"
        "  Oi = -Os;\n}\n", r);
    EXPECT_TRUE(r.ok) << r.diags;
    EXPECT_EQ(r.diags, "");
}

TEST(Builtins, TableDecodes) {
    const rsl::Builtin* tex = rsl::findBuiltin("texture");
    ASSERT_NE(tex, nullptr);
    EXPECT_TRUE(tex->flags & rsl::BF_CHANNEL);
    EXPECT_GE(rsl::builtinTable().size(), 80u);
    const rsl::Builtin* fr = rsl::findBuiltin("fresnel");
    ASSERT_NE(fr, nullptr);
    EXPECT_TRUE(fr->sigs[0].args[3].output);
    for (const rsl::Builtin& b : rsl::builtinTable())
        for (const rsl::BuiltinSig& s : b.sigs) EXPECT_FALSE(s.ret.isError()) << b.name;
}

}  // namespace

namespace {
// What old shaders write and RayDrive now takes (session 36): a variable named after a
// shader kind (`color light`), a local declared uniform assigned under a varying if (a
// warning: it is made varying), setzcomp() of a vector, N and P set in a surface, a
// nested function with a storage class (`uniform float two()`), L in a light's
// illuminate, du and dv in a volume shader's helper.
TEST(Frontend, OldShadersIdioms) {
    Result r;
    rsltest::compile("surface s() {\n  color light = 1;\n  float volume = 2;\n"
                     "  uniform float i;\n  vector v = 0;\n"
                     "  if (u > 0.5) for (i = 0; i < 2; i += 1) setzcomp(v, i);\n"
                     "  N = N + Ng;\n  P += v;\n  uniform float two() { return 2; }\n"
                     "  Ci = light * volume + zcomp(v) + two();\n}\n",
                     r);
    EXPECT_TRUE(r.ok) << r.diags;
    EXPECT_EQ(r.diags,
              "test.sl:6:23: warning: uniform variable 'i' is assigned a varying value (or "
              "under a varying condition): it is made varying\n");
    Result l;
    rsltest::compile("light l(point from = 0) {\n  illuminate(from) {\n"
                     "    L = Ps - from;\n    Cl = 1;\n  }\n}\n",
                     l);
    EXPECT_TRUE(l.ok) << l.diags;
    EXPECT_EQ(l.diags, "");
    // a volume shader's helpers (Advanced RenderMan's noises.h) declare du and dv extern
    Result v;
    rsltest::compile("float fw() { extern float du, dv; return du + dv; }\n"
                     "volume v() {\n  Ci = Ci * (1 + 0 * fw());\n}\n",
                     v);
    EXPECT_TRUE(v.ok) << v.diags;
}
}  // namespace
