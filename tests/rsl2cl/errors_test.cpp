// errors_test.cpp: bad programs and their exact diagnostics (OSL testsuite style: the
// expected stderr text lives beside the source).
#include <gtest/gtest.h>

#include "test_util.h"

namespace {

struct ErrorCase {
    const char* name;
    const char* source;
    const char* expected;
};

const ErrorCase kCases[] = {
    {"unknown_identifier", "surface s() {\n  Ci = Cx;\n}\n",
     "test.sl:2:8: error: unknown identifier 'Cx'\n"},
    {"unknown_function", "surface s() {\n  Ci = frob(1);\n}\n",
     "test.sl:2:8: error: unknown function 'frob'\n"},
    {"type_mismatch_init", "surface s() {\n  float f = Cs;\n  Ci = f;\n}\n",
     "test.sl:2:13: error: cannot initialise 'float f' with a value of type 'color'\n"},
    {"type_mismatch_assign", "surface s() {\n  point p;\n  p = Cs;\n}\n",
     "test.sl:3:5: error: cannot assign a value of type 'color' to 'point' 'p'\n"},
    {"bad_operator", "surface s() {\n  Ci = Cs . P;\n}\n",
     "test.sl:2:11: error: operator '.' cannot be applied to 'color' and 'point'\n"},
    {"wrong_arg_count", "surface s() {\n  float x = sin(1, 2);\n}\n",
     "test.sl:2:13: error: wrong number of arguments to 'sin': 2 given\n"},
    {"no_overload", "surface s() {\n  float x = length(\"abc\");\n}\n",
     "test.sl:2:13: error: no matching function for call to 'length(string)'\n"},
    {"readonly_global", "surface s() {\n  Ng = N;\n  Cs = 1;\n  Ci = Cs;\n}\n",
     "test.sl:2:3: error: cannot assign to 'Ng': it is read-only in surface shaders\n"
     "test.sl:3:3: error: cannot assign to 'Cs': it is read-only in surface shaders\n"},
    {"light_writes_ci", "light l() {\n  Ci = 1;\n}\n",
     "test.sl:2:3: error: unknown identifier 'Ci'\n"},
    {"uniform_gets_varying", "surface s(float Kd = 1) {\n  uniform float k = s;\n"
                             "  Kd = t;\n}\n",
     "test.sl:2:21: warning: uniform variable 'k' is assigned a varying value (or under a "
     "varying condition): it is made varying\n"
     "test.sl:3:6: error: cannot assign a varying value to uniform variable 'Kd'\n"},
    {"syntax_missing_semicolon", "surface s() {\n  float a = 1\n  Ci = a;\n  Oi = ;\n}\n",
     "test.sl:3:3: error: expected ';' but found 'Ci'\n"
     "test.sl:4:8: error: expected an expression but found ';'\n"},
    {"syntax_bad_toplevel", "surface s( {\n}\nsurface t() { Ci = 1; }\n",
     "test.sl:1:12: error: expected a type name but found '{'\n"},
    {"illuminance_in_light", "light l() {\n  illuminance(P) { Cl = 1; }\n}\n",
     "test.sl:2:3: error: illuminance is only allowed in surface and volume shaders\n"},
    {"illuminate_in_surface", "surface s() {\n  illuminate(P) { Ci = 1; }\n}\n",
     "test.sl:2:3: error: illuminate is only allowed in light shaders\n"},
    {"break_outside_loop", "surface s() {\n  break;\n  while (1) { continue 2; }\n}\n",
     "test.sl:2:3: error: break outside a loop\n"
     "test.sl:3:15: error: loop level 2 exceeds the 1 enclosing loop(s)\n"},
    {"return_value_in_void", "void f() { return 1; }\nsurface s() { f(); }\n",
     "test.sl:1:12: error: return with a value in a void function\n"},
    {"redeclaration", "surface s() {\n  float a;\n  color a;\n}\n",
     "test.sl:3:9: error: redeclaration of 'a'\n"},
    {"condition_not_float", "surface s() {\n  if (Cs) Ci = 1;\n}\n",
     "test.sl:2:7: error: condition of if must be a float or relation, not 'color'\n"},
    {"index_non_array", "surface s() {\n  float a = 1;\n  Ci = a[0];\n}\n",
     "test.sl:3:9: error: indexing into non-array type 'float'\n"},
    {"bad_cast", "surface s() {\n  float f = float Cs;\n}\n",
     "test.sl:2:13: error: cannot cast 'color' to 'float'\n"},
    {"tuple_size", "surface s() {\n  Ci = color (1, 2);\n}\n",
     "test.sl:2:14: error: a tuple needs 3 or 16 components, not 2\n"},
    {"output_arg_not_lvalue", "surface s() {\n  float kr, kt;\n"
                              "  fresnel(I, N, 1.5, kr + 1, kt);\n}\n",
     "test.sl:3:25: error: output argument 4 of 'fresnel' must be a variable\n"},
    {"user_fn_args", "float f(float a) { return a; }\nsurface s() {\n  Ci = f(1, 2);\n}\n",
     "test.sl:3:8: error: wrong number of arguments to 'f': 2 given\n"},
    {"extern_missing", "surface s() {\n  void g() { extern float zz; }\n  g();\n}\n",
     "test.sl:2:27: error: extern variable 'zz' is not declared in an enclosing scope\n"},
    {"lexer_bad_char", "surface s() {\n  Ci = $;\n}\n",
     "test.sl:2:8: error: unexpected character '$'\n"},
    {"unterminated_string", "surface s() {\n  string a = \"abc;\n}\n",
     "test.sl:2:14: error: unterminated string literal\n"},
    {"several_errors", "surface s() {\n  float a = b;\n  color c = d;\n  Ci = e;\n}\n",
     "test.sl:2:13: error: unknown identifier 'b'\n"
     "test.sl:3:13: error: unknown identifier 'd'\n"
     "test.sl:4:8: error: unknown identifier 'e'\n"},
    {"empty_file", "/* nothing */\n", "test.sl:2:1: error: no shader or function definition\n"},
    // OpenCL C has no recursion (PoCL's compiler overflowed its stack on one: the
    // renderer crashed); functions are inlined, so a call cycle is an error
    {"recursive_call", "float f(float x) { return f(x) + 1; }\nsurface s() {\n  Ci = f(1);\n}\n",
     "test.sl:1:27: error: recursive call of 'f': shading language functions are inlined, "
     "so they cannot call themselves\n"},
    {"mutual_recursion_through_nested_function",
     "float f(float x) {\n  float h(float y) { return f(y) * 2; }\n  return h(x);\n}\n"
     "surface s() {\n  Ci = f(1);\n}\n",
     "test.sl:2:29: error: recursive call of 'f': shading language functions are inlined, "
     "so they cannot call themselves\n"},
};

void PrintTo(const ErrorCase& c, std::ostream* os) { *os << c.name; }

class ErrorDiagnostics : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(ErrorDiagnostics, MatchExpectedText) {
    const ErrorCase& c = GetParam();
    rsltest::Result r;
    rsltest::compile(c.source, r);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.diags, c.expected);
}

// A chain of calls deeper than 200 is an error, not a stack overflow in a later stage
// (the affinity check and the code generator walk inlined calls recursively: 100k
// functions each calling the last crashed rsl2cl); 150 deep compiles.
static std::string callChain(int n) {
    std::string src = "float f0(float x) { return x; }\n";
    for (int i = 1; i < n; ++i)
        src += "float f" + std::to_string(i) + "(float x) { return f" + std::to_string(i - 1) +
               "(x) + 1; }\n";
    return src + "surface s() {\n  Ci = f" + std::to_string(n - 1) + "(1);\n}\n";
}

TEST(ErrorDiagnostics, DeepCallChainIsAnErrorNotACrash) {
    rsltest::Result r;
    rsltest::compile(callChain(100000), r);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.diags, "test.sl:201:7: error: 'f200' calls functions nested more than 200 deep "
                       "(shading language functions are inlined)\n");
    rsltest::Result ok;
    rsltest::compile(callChain(150), ok);
    EXPECT_TRUE(ok.ok) << ok.diags;
}

INSTANTIATE_TEST_SUITE_P(Rsl2cl, ErrorDiagnostics, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& i) {
                             return std::string(i.param.name);
                         });

}  // namespace
