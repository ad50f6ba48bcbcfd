// preprocess_test.cpp: macros, conditionals, includes and line tracking.
#include <gtest/gtest.h>

#include "preprocess.h"
#include "test_util.h"

namespace {

std::string pp(const std::string& src, std::string* diags = nullptr,
               const rsl::PreprocessOptions& opts = {}) {
    rsl::Diagnostics d;
    std::string out = rsl::tokensToText(rsl::preprocessText(src, "pp.sl", opts, d));
    if (diags) *diags = d.text();
    return out;
}

TEST(Preprocess, ObjectMacro) { EXPECT_EQ(pp("#define K 1.5\nfloat x = K;"), "float x = 1.5 ;"); }

TEST(Preprocess, FunctionMacroAndNesting) {
    EXPECT_EQ(pp("#define SQ(a) ((a)*(a))\n#define F(a,b) SQ(a)+b\nF(x, 2)"),
              "( ( x ) * ( x ) ) + 2");
}

TEST(Preprocess, FunctionMacroNameWithoutParens) {
    EXPECT_EQ(pp("#define F(a) a\nF + 1"), "F + 1");
}

TEST(Preprocess, SelfReferenceStops) { EXPECT_EQ(pp("#define A A + 1\nA"), "A + 1"); }

TEST(Preprocess, Stringize) { EXPECT_EQ(pp("#define S(x) #x\nS(abc)"), "\"abc\""); }

TEST(Preprocess, Undef) { EXPECT_EQ(pp("#define A 1\n#undef A\nA"), "A"); }

TEST(Preprocess, IfElifElse) {
    const char* src = "#define V 2\n#if V == 1\none\n#elif V == 2 && defined(V)\ntwo\n"
                      "#else\nthree\n#endif\n";
    EXPECT_EQ(pp(src), "two");
    EXPECT_EQ(pp("#if 0\na\n#if 1\nb\n#endif\n#else\nc\n#endif"), "c");
    EXPECT_EQ(pp("#ifdef X\na\n#endif\n#ifndef X\nb\n#endif"), "b");
    EXPECT_EQ(pp("#if (3 + 4) * 2 > 13 ? !defined X : 0\nyes\n#endif"), "yes");
}

TEST(Preprocess, CommandLineDefines) {
    rsl::PreprocessOptions o;
    o.defines = {{"DEBUG", "1"}, {"KD", "0.25"}};
    EXPECT_EQ(pp("#if DEBUG\nKD\n#endif", nullptr, o), "0.25");
}

TEST(Preprocess, ConditionalErrors) {
    std::string d;
    pp("#if 1\nx\n", &d);
    EXPECT_EQ(d, "pp.sl:1:2: error: unterminated conditional directive\n");
    pp("#endif\n", &d);
    EXPECT_EQ(d, "pp.sl:1:2: error: #endif without #if\n");
    pp("#if 1 +\n#endif\n#frobnicate\n", &d);
    EXPECT_EQ(d, "pp.sl:1:2: error: missing expression in #if\n"
                 "pp.sl:3:2: error: unknown preprocessor directive '#frobnicate'\n");
    pp("#define F(a) a\nF(1, 2)\n", &d);
    EXPECT_EQ(d, "pp.sl:2:1: error: macro 'F' takes 1 argument(s), 2 given\n");
}

// Found by a libFuzzer run of the front end under ASan and UBSan (session 20): #if
// arithmetic that overflowed (undefined behaviour), LLONG_MIN / -1 (a trap on x86), a
// number beyond the integers, and nesting that overflowed the stack (a crash, rc 139).
TEST(Preprocess, IfArithmeticIsDefinedForEveryInput) {
    std::string d;
    // -2^63 (an exact double), then divided and taken modulo by -1: wraps, no trap
    const std::string min = "(-9223372036854774784 - 1024)";
    EXPECT_EQ(pp("#if " + min + " / -1 == " + min + "\nwraps\n#endif", &d), "wraps");
    EXPECT_EQ(d, "");
    EXPECT_EQ(pp("#if " + min + " % -1 == 0\nzero\n#endif", &d), "zero");
    EXPECT_EQ(pp("#if -" + min + " == " + min + "\nneg\n#endif", &d), "neg");
    EXPECT_EQ(pp("#if " + min + " - 1 > 0 && 4611686018427387904 * 4 == 0\nwrap\n#endif", &d),
              "wrap");
    EXPECT_EQ(d, "");
    pp("#if 1e93 > 0\nx\n#endif\n", &d);
    EXPECT_EQ(d, "pp.sl:1:5: error: number out of range in #if\n");
}

TEST(Preprocess, DeepIfNestingIsAnErrorNotACrash) {
    std::string d;
    const std::string deep(100000, '(');
    pp("#if " + deep + "1\n#endif\n", &d);
    EXPECT_EQ(d, "pp.sl:1:205: error: #if expression nested too deeply\n");
    pp("#if " + std::string(100000, '-') + "1\n#endif\n", &d);
    EXPECT_EQ(d, "pp.sl:1:205: error: #if expression nested too deeply\n");
    // 150 levels are fine
    EXPECT_EQ(pp("#if " + std::string(150, '(') + "1" + std::string(150, ')') + "\nok\n#endif"),
              "ok");
}

TEST(Preprocess, IncludeSearchPathAndGuards) {
    rsl::PreprocessOptions o;
    o.includeDirs = {RSL2CL_TEST_DATA "/inc"};
    EXPECT_EQ(pp("#include <clean.h>\n#include \"clean.h\"\nKD_DEFAULT", nullptr, o), "0.75");
    std::string d;
    pp("#include \"nosuch.h\"\n", &d, o);
    EXPECT_EQ(d, "pp.sl:1:2: error: cannot find include file 'nosuch.h'\n");
}

TEST(Preprocess, DiagnosticsNameIncludedFileAndLine) {
    rsl::PreprocessOptions o;
    o.includeDirs = {RSL2CL_TEST_DATA "/inc"};
    rsltest::Result r;
    rsltest::compile("#include \"common.h\"\nsurface s() { Ci = TWICE(Cs); }\n", r,
                     "main.sl", o);
    EXPECT_EQ(r.diags, RSL2CL_TEST_DATA "/inc/common.h:4:25: error: unknown identifier "
                                        "'undefined_here'\n");
}

TEST(Preprocess, LineTrackingAfterComments) {
    rsltest::Result r;
    rsltest::compile("/* a\n b\n c */\n#define X \\\n  1\nsurface s() {\n  Ci = y;\n}\n", r);
    EXPECT_EQ(r.diags, "test.sl:7:8: error: unknown identifier 'y'\n");
}

}  // namespace
