// test_util.h: helpers shared by the rsl2cl front-end tests.
#pragma once
#include <fstream>
#include <sstream>
#include <string>

#include "compiler.h"

namespace rsltest {

struct Result {
    bool ok;
    std::string diags;  // every diagnostic, one per line
    rsl::Program prog;
};

inline void compile(const std::string& src, Result& r, const std::string& name = "test.sl",
                    const rsl::PreprocessOptions& opts = {}) {
    rsl::Diagnostics diag;
    r.ok = rsl::compileSource(src, name, opts, r.prog, diag);
    r.diags = diag.text();
}

// Diagnostics text of compiling src (empty when clean).
inline std::string diagsOf(const std::string& src) {
    Result r;
    compile(src, r);
    return r.diags;
}

inline std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Finds a symbol declared with this name (first match) in the program.
inline const rsl::Symbol* findSymbol(const rsl::Program& p, const std::string& name) {
    for (const auto& s : p.symbols)
        if (s->name == name && s->kind != rsl::SymbolKind::Global) return s.get();
    return nullptr;
}

}  // namespace rsltest
