// compiler.cpp: front-end driver shared by the rsl2cl command, the host and tests.
#include "compiler.h"

#include "call_graph.h"
#include "parser.h"

namespace rsl {

static bool frontEnd(const std::vector<Token>& toks, Program& prog, Diagnostics& diag) {
    int before = diag.errorCount();
    if (diag.errorCount() > before) return false;
    if (!parseProgram(toks, prog, diag)) return false;
    if (prog.shaders.empty() && prog.functions.empty()) {
        diag.error(toks.back().loc, "no shader or function definition");
        return false;
    }
    return typecheckProgram(prog, diag) && checkCallGraph(prog, diag);
}

bool compileFile(const std::string& path, const PreprocessOptions& opts, Program& prog,
                 Diagnostics& diag) {
    int before = diag.errorCount();
    std::vector<Token> toks = preprocessFile(path, opts, diag);
    if (diag.errorCount() > before) return false;
    return frontEnd(toks, prog, diag);
}

bool compileSource(const std::string& text, const std::string& name,
                   const PreprocessOptions& opts, Program& prog, Diagnostics& diag) {
    int before = diag.errorCount();
    std::vector<Token> toks = preprocessText(text, name, opts, diag);
    if (diag.errorCount() > before) return false;
    return frontEnd(toks, prog, diag);
}

}  // namespace rsl
