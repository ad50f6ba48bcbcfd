// lexer.h: turns RSL source text into tokens (used by the preprocessor, then the parser).
#pragma once
#include <string>
#include <vector>

#include "diagnostics.h"

namespace rsl {

enum class TokKind { End, Ident, Number, String, Punct };

struct Token {
    TokKind kind = TokKind::End;
    std::string text;     // identifier, punctuator, number spelling, or unescaped string
    double number = 0;    // value of a Number
    SourceLoc loc;
    bool bol = false;     // first token on its (logical) line: directives start here
    bool is(const char* p) const { return kind == TokKind::Punct && text == p; }
    bool isIdent(const char* s) const { return kind == TokKind::Ident && text == s; }
};

// Lexes a whole file. Comments and backslash-newlines are skipped; errors are reported
// and the offending character dropped. The result always ends with an End token.
std::vector<Token> lexText(const std::string& text, const std::string& file,
                           Diagnostics& diag);

// Lexes "1.5", "-3" etc.; returns false when s is not exactly one number.
bool parseNumber(const std::string& s, double& out);

}  // namespace rsl
