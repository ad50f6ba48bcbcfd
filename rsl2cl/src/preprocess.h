// preprocess.h: the C-style preprocessor of RSL (#include, #define, #if...) on tokens.
// Tokens keep the file and line they came from, so diagnostics name included files;
// tokens produced by a macro carry the location of the macro's use.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "diagnostics.h"
#include "lexer.h"

namespace rsl {

struct PreprocessOptions {
    std::vector<std::string> includeDirs;                       // -I, in order
    std::vector<std::pair<std::string, std::string>> defines;   // -D NAME=VALUE
    int maxIncludeDepth = 64;
};

// Preprocesses the file at path; the result ends with an End token.
std::vector<Token> preprocessFile(const std::string& path, const PreprocessOptions& opts,
                                  Diagnostics& diag);
// Same for text already in memory, named `name` in diagnostics; #include "x" is
// searched relative to name's directory, then the include dirs.
std::vector<Token> preprocessText(const std::string& text, const std::string& name,
                                  const PreprocessOptions& opts, Diagnostics& diag);
// Spells tokens back as text separated by single spaces (strings re-quoted).
std::string tokensToText(const std::vector<Token>& toks);

}  // namespace rsl
