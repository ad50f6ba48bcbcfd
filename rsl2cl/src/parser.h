// parser.h: recursive-descent parser from preprocessed tokens to the AST.
#pragma once
#include <vector>

#include "ast.h"
#include "lexer.h"

namespace rsl {

// Parses the token stream (ending with End) into prog; reports syntax errors and
// recovers at ';' / '}' so several are reported per run. Returns false on any error.
bool parseProgram(const std::vector<Token>& toks, Program& prog, Diagnostics& diag);

}  // namespace rsl
