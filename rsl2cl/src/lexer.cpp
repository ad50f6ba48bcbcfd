// lexer.cpp: hand-written scanner for RSL tokens with line/column tracking.
#include "lexer.h"

#include <cctype>
#include <cstdlib>

namespace rsl {
namespace {

class Lexer {
public:
    Lexer(const std::string& text, const std::string& file, Diagnostics& diag)
        : m_text(text), m_file(file), m_diag(diag) {}

    std::vector<Token> run() {
        std::vector<Token> out;
        bool bol = true;
        for (;;) {
            bol = skipSpace(bol);
            Token t;
            t.loc = here();
            t.bol = bol;
            if (m_pos >= m_text.size()) {
                t.kind = TokKind::End;
                out.push_back(t);
                return out;
            }
            if (!lexOne(t)) continue;
            bol = false;
            out.push_back(std::move(t));
        }
    }

private:
    SourceLoc here() const { return SourceLoc{m_file, m_line, m_col}; }
    char peek(size_t k = 0) const {
        return m_pos + k < m_text.size() ? m_text[m_pos + k] : '\0';
    }
    void advance() {
        if (m_text[m_pos] == '\n') {
            ++m_line;
            m_col = 1;
        } else {
            ++m_col;
        }
        ++m_pos;
    }

    // Skips blanks and comments; returns whether the next token starts a line.
    bool skipSpace(bool bol) {
        while (m_pos < m_text.size()) {
            char c = peek();
            if (c == '\n') {
                bol = true;
                advance();
            } else if (c == '\\' && peek(1) == '\n') {
                advance();
                advance();
            } else if (c == '\\' && peek(1) == '\r' && peek(2) == '\n') {
                advance();
                advance();
                advance();
            } else if (isspace(static_cast<unsigned char>(c))) {
                advance();
            } else if (c == '/' && peek(1) == '/') {
                while (m_pos < m_text.size() && peek() != '\n') advance();
            } else if (c == '/' && peek(1) == '*') {
                SourceLoc start = here();
                advance();
                advance();
                while (m_pos < m_text.size() && !(peek() == '*' && peek(1) == '/')) {
                    if (peek() == '\n') bol = true;
                    advance();
                }
                if (m_pos >= m_text.size()) {
                    m_diag.error(start, "unterminated comment");
                } else {
                    advance();
                    advance();
                }
            } else {
                break;
            }
        }
        return bol;
    }

    bool lexOne(Token& t) {
        char c = peek();
        unsigned char uc = static_cast<unsigned char>(c);
        if (isalpha(uc) || c == '_') {
            t.kind = TokKind::Ident;
            while (isalnum(static_cast<unsigned char>(peek())) || peek() == '_') {
                t.text += peek();
                advance();
            }
            return true;
        }
        if (isdigit(uc) || (c == '.' && isdigit(static_cast<unsigned char>(peek(1))))) {
            return lexNumber(t);
        }
        if (c == '"') return lexString(t);
        static const char* const two[] = {"+=", "-=", "*=", "/=", "==", "!=", "<=",
                                          ">=", "&&", "||", "##", "^="};
        for (const char* p : two) {
            if (c == p[0] && peek(1) == p[1]) {
                t.kind = TokKind::Punct;
                t.text = p;
                advance();
                advance();
                return true;
            }
        }
        if (std::string("+-*/^.?:;,(){}[]=<>!#%&|~").find(c) != std::string::npos) {
            t.kind = TokKind::Punct;
            t.text = std::string(1, c);
            advance();
            return true;
        }
        std::string shown = isprint(uc) ? std::string(1, c) : "\\x" + hex(uc);
        m_diag.error(t.loc, "unexpected character '" + shown + "'");
        advance();
        return false;
    }

    static std::string hex(unsigned char c) {
        const char* d = "0123456789abcdef";
        return std::string{d[c >> 4], d[c & 15]};
    }

    bool lexNumber(Token& t) {
        t.kind = TokKind::Number;
        while (isdigit(static_cast<unsigned char>(peek()))) addChar(t);
        if (peek() == '.') {
            addChar(t);
            while (isdigit(static_cast<unsigned char>(peek()))) addChar(t);
        }
        if ((peek() == 'e' || peek() == 'E') &&
            (isdigit(static_cast<unsigned char>(peek(1))) ||
             ((peek(1) == '+' || peek(1) == '-') &&
              isdigit(static_cast<unsigned char>(peek(2)))))) {
            addChar(t);
            addChar(t);
            while (isdigit(static_cast<unsigned char>(peek()))) addChar(t);
        }
        if (peek() == 'f' || peek() == 'F') advance();  // tolerate C-style 1.0f
        t.number = std::strtod(t.text.c_str(), nullptr);
        return true;
    }
    void addChar(Token& t) {
        t.text += peek();
        advance();
    }

    bool lexString(Token& t) {
        t.kind = TokKind::String;
        advance();
        for (;;) {
            char c = peek();
            if (m_pos >= m_text.size() || c == '\n') {
                m_diag.error(t.loc, "unterminated string literal");
                return true;
            }
            advance();
            if (c == '"') return true;
            if (c == '\\' && m_pos < m_text.size()) {
                char e = peek();
                advance();
                switch (e) {
                case 'n': t.text += '\n'; break;
                case 't': t.text += '\t'; break;
                case 'r': t.text += '\r'; break;
                case '\\': t.text += '\\'; break;
                case '"': t.text += '"'; break;
                case '\n': break;
                default: t.text += '\\'; t.text += e; break;
                }
                continue;
            }
            t.text += c;
        }
    }

    const std::string& m_text;
    std::string m_file;
    Diagnostics& m_diag;
    size_t m_pos = 0;
    int m_line = 1;
    int m_col = 1;
};

}  // namespace

std::vector<Token> lexText(const std::string& text, const std::string& file,
                           Diagnostics& diag) {
    return Lexer(text, file, diag).run();
}

bool parseNumber(const std::string& s, double& out) {
    if (s.empty()) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end && *end == '\0';
}

}  // namespace rsl
