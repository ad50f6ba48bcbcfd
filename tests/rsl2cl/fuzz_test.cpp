// fuzz_test.cpp: truncated, token-shuffled and byte-mutated versions of the standard
// shaders must never crash the front end (errors are fine; a crash fails the test).
#include <gtest/gtest.h>

#include <random>

#include "coef_shader.h"
#include "emit_cl.h"
#include "test_util.h"

namespace {

const char* const kShaders[] = {"plastic", "spotlight", "glass", "bumpy", "shadowspot",
                                "depthcue", "shinymetal", "arealight"};

std::string load(const char* name) {
    return rsltest::readFile(std::string(RSL2CL_SHADER_DIR "/") + name + ".sl");
}

void run(const std::string& src) {
    rsltest::Result r;
    rsltest::compile(src, r);
    if (r.ok) rsl::dumpAst(r.prog);
    for (const auto& sh : r.prog.shaders) rsl::formatInfo(rsl::collectInfo(*sh));
    if (!r.ok) return;
    for (const auto& sh : r.prog.shaders) {  // the code generator too (light coefficients...)
        rsl::Diagnostics d;
        rsl::emitOpenCL(*sh, r.prog, d, 1 + int(src.size() % 15));  // and colour channels
    }
}

TEST(Fuzz, Truncation) {
    for (const char* n : kShaders) {
        std::string src = load(n);
        for (size_t len = 0; len < src.size(); len += 3) run(src.substr(0, len));
    }
}

TEST(Fuzz, ShuffledTokens) {
    std::mt19937 rng(1234);
    for (const char* n : kShaders) {
        rsl::Diagnostics d;
        std::vector<rsl::Token> toks = rsl::lexText(load(n), "x.sl", d);
        toks.pop_back();
        for (int iter = 0; iter < 150; ++iter) {
            std::vector<rsl::Token> t = toks;
            int swaps = 1 + static_cast<int>(rng() % 6);
            for (int k = 0; k < swaps; ++k) {
                size_t a = rng() % t.size(), b = rng() % t.size();
                switch (rng() % 3) {
                case 0: std::swap(t[a], t[b]); break;
                case 1: t.erase(t.begin() + static_cast<long>(a)); break;
                default: t.insert(t.begin() + static_cast<long>(a), t[b]); break;
                }
            }
            run(rsl::tokensToText(t));
        }
    }
}

TEST(Fuzz, ByteMutations) {
    std::mt19937 rng(99);
    const std::string alphabet = "(){}[];,.^#\"=+-*/<>!?:\n\\ 0aZ_";
    for (const char* n : kShaders) {
        std::string src = load(n);
        for (int iter = 0; iter < 150; ++iter) {
            std::string s = src;
            for (int k = 0; k < 4; ++k) s[rng() % s.size()] = alphabet[rng() % alphabet.size()];
            run(s);
        }
    }
}

// Light coefficients (emit_coefs.cpp, coef_shader.h): token swaps and drops that still
// compile must generate code without a crash (or give errors).
TEST(Fuzz, LightCoefficientShaders) {
    const char* src = rsltest::coefShader();
    std::mt19937 rng(4321);
    rsl::Diagnostics d;
    std::vector<rsl::Token> toks = rsl::lexText(src, "f.sl", d);
    toks.pop_back();
    {  // the unmutated shader compiles, with coefficients
        rsltest::Result r;
        rsltest::compile(src, r);
        ASSERT_TRUE(r.ok) << r.diags;
        rsl::Diagnostics diag;
        EXPECT_TRUE(rsl::emitOpenCL(*r.prog.shaders[0], r.prog, diag).lightCoefs) << diag.text();
    }
    for (int iter = 0; iter < 3000; ++iter) {
        std::vector<rsl::Token> t = toks;
        size_t a = rng() % t.size(), b = rng() % t.size();
        if (rng() % 2) std::swap(t[a], t[b]);
        else t.erase(t.begin() + static_cast<long>(a));
        run(rsl::tokensToText(t));
    }
}

TEST(Fuzz, DeepNestingAndMacroBombs) {
    run("surface s() { Ci = " + std::string(5000, '(') + "1" + std::string(5000, ')') + "; }");
    run("surface s() " + std::string(3000, '{') + std::string(3000, '}'));
    run("surface s() { Ci = " + std::string(4000, '-') + "1; }");
    run("#define A B B\n#define B C C\n#define C D D\n#define D E E\n#define E F F\n"
        "#define F G G\n#define G H H\n#define H 1\nsurface s() { float x = A; }\n");
    run("#define R(x) R(x)\nsurface s() { float x = R(1); }\n");
    run(std::string(2000, '#') + "\n#if\n#elif\n#else\n#else\n#endif\n#endif");
}

}  // namespace
