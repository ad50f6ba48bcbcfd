// lexer.cpp: ASCII RIB tokenization (binary tokens are in lexer_binary.cpp). Input is buffered in chunks so large (possibly
// gzip-compressed) files stream instead of being loaded whole. Numbers are checked
// against a strict grammar before conversion so typos like "1.2.3" or "3e" are errors
// rather than silently truncated values.
#include "lexer.h"

#include <zlib.h>

#include <cerrno>
#include <cfloat>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rib {

namespace {

constexpr size_t kChunk = 1 << 16;

bool isDigit(int c) {
    return c >= '0' && c <= '9';
}
bool isAlpha(int c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool isSpace(int c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

std::string lower(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
}

bool isNanOrInf(const std::string& word) {
    std::string w = lower(word);
    return w == "nan" || w == "inf" || w == "infinity";
}

// [+-]? (digits [. digits*] | . digits) ([eE] [+-]? digits)?, or a signed nan/inf.
bool validNumber(const std::string& s, bool& isInteger) {
    size_t i = 0, n = s.size();
    isInteger = true;
    if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
    if (i < n && isAlpha(static_cast<unsigned char>(s[i]))) {
        isInteger = false;
        return isNanOrInf(s.substr(i));
    }
    size_t intDigits = 0, fracDigits = 0;
    while (i < n && isDigit(s[i])) ++i, ++intDigits;
    if (i < n && s[i] == '.') {
        isInteger = false;
        ++i;
        while (i < n && isDigit(s[i])) ++i, ++fracDigits;
    }
    if (intDigits + fracDigits == 0) return false;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        isInteger = false;
        ++i;
        if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
        size_t expDigits = 0;
        while (i < n && isDigit(s[i])) ++i, ++expDigits;
        if (expDigits == 0) return false;
    }
    return i == n;
}

}  // namespace

Lexer::Lexer(std::string name, Diagnostics& diag)
    : m_name(std::move(name)), m_diag(diag) {}

void Lexer::setText(std::string text) {
    m_buf.assign(text.begin(), text.end());
    m_pos = 0;
    m_len = m_buf.size();
    m_file = nullptr;
    m_eof = false;
    m_line = 1;
}

void Lexer::setFile(gzFile_s* file) {
    m_file = file;
    m_buf.assign(kChunk, 0);
    m_pos = m_len = 0;
    m_eof = false;
    m_line = 1;
}

bool Lexer::refill() {
    if (m_eof || !m_file) {
        m_eof = true;
        return false;
    }
    int n = gzread(m_file, m_buf.data(), static_cast<unsigned>(m_buf.size()));
    if (n <= 0) {
        if (n < 0) {
            int err = 0;
            const char* msg = gzerror(m_file, &err);
            std::string why = err == Z_ERRNO ? std::strerror(errno) : (msg ? msg : "");
            m_diag.error(loc(m_line), "cannot read RIB file: " + why);
        }
        m_eof = true;
        return false;
    }
    m_pos = 0;
    m_len = static_cast<size_t>(n);
    return true;
}

int Lexer::peek() {
    if (m_pos >= m_len && !refill()) return -1;
    return static_cast<unsigned char>(m_buf[m_pos]);
}

int Lexer::get() {
    int c = peek();
    if (c < 0) return c;
    ++m_pos;
    if (c == '\n') ++m_line;
    return c;
}

int Lexer::peekFirstByte() {
    return peek();
}

bool Lexer::isDelimiter(int c) {
    return c < 0 || isSpace(c) || c == '[' || c == ']' || c == '"' || c == '#' ||
           c >= 0x80;  // a binary token may follow ASCII with no space between
}

std::string Lexer::readRun(int first) {
    std::string s(1, static_cast<char>(first));
    // (a run holds no newline: whole stretches of the buffer at a time, not a call a byte)
    for (;;) {
        if (m_pos >= m_len && !refill()) return s;
        size_t end = m_pos;
        while (end < m_len && !isDelimiter(static_cast<unsigned char>(m_buf[end]))) ++end;
        s.append(m_buf.data() + m_pos, end - m_pos);
        const bool more = end == m_len;
        m_pos = end;
        if (!more) return s;
    }
}

Token Lexer::error(int line, const std::string& msg) {
    m_diag.error(loc(line), msg);
    Token t;
    t.kind = TokenKind::Error;
    t.line = line;
    return t;
}

Token Lexer::next() {
    if (m_inBinArray) return nextBinaryArrayElement();
    for (;;) {
        int c = get();
        if (c < 0) {
            Token t;
            t.line = m_line;
            return t;
        }
        if (isSpace(c)) continue;
        int line = m_line;
        if (c >= 0x80) {
            Token b;
            if (lexBinary(c, line, b)) return b;
            continue;
        }
        if (c == '#') {
            // Comments and "##" structural comments alike carry nothing the reader needs.
            while (peek() >= 0 && peek() != '\n') get();
            continue;
        }
        Token t;
        t.line = line;
        if (c == '[' || c == ']') {
            t.kind = c == '[' ? TokenKind::LBracket : TokenKind::RBracket;
            t.text = std::string(1, static_cast<char>(c));
            return t;
        }
        if (c == '"') return lexString(line);
        if (isDigit(c) || c == '+' || c == '-' || c == '.')
            return lexNumber(readRun(c), line);
        if (isAlpha(c)) {
            t.text = readRun(c);
            if (isNanOrInf(t.text)) return lexNumber(t.text, line);
            t.kind = TokenKind::Word;
            return t;
        }
        readRun(c);  // skip the whole run: one message per bad token, not per byte
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%02x", c);
        return error(line, std::string("unexpected character ") + hex);
    }
}

Token Lexer::lexString(int startLine) {
    Token t;
    t.kind = TokenKind::String;
    t.line = startLine;
    for (;;) {
        int c = get();
        if (c < 0) return error(startLine, "unterminated string");
        if (c == '"') return t;
        if (c != '\\') {
            t.text += static_cast<char>(c);
            continue;
        }
        int e = get();
        switch (e) {
            case 'n':
                t.text += '\n';
                break;
            case 't':
                t.text += '\t';
                break;
            case 'r':
                t.text += '\r';
                break;
            case 'b':
                t.text += '\b';
                break;
            case 'f':
                t.text += '\f';
                break;
            case '\n':
                break;  // a backslash-newline continues the string on the next line
            case -1:
                return error(startLine, "unterminated string");
            default:
                if (e >= '0' && e <= '7') {
                    int v = e - '0';
                    for (int k = 0; k < 2 && peek() >= '0' && peek() <= '7'; ++k)
                        v = v * 8 + (get() - '0');
                    t.text += static_cast<char>(v & 0xff);
                } else {
                    t.text += static_cast<char>(e);  // \\, \", and any other escaped char
                }
        }
    }
}

Token Lexer::lexNumber(std::string text, int line) {
    bool isInteger = false;
    if (!validNumber(text, isInteger))
        return error(line, "malformed number \"" + text + "\"");
    Token t;
    t.kind = TokenKind::Number;
    t.line = line;
    // The digits read in place after the sign (a 300k-triangle RIB reads a million
    // numbers; each one's text was copied four times).
    const bool neg = text[0] == '-';
    const char* digits = text.c_str() + (text[0] == '+' || text[0] == '-' ? 1 : 0);
    const char* end = text.c_str() + text.size();
    if (isAlpha(static_cast<unsigned char>(*digits))) {  // validNumber took nan or inf
        t.number = lower(digits) == "nan" ? (neg ? -NAN : NAN) : (neg ? -HUGE_VAL : HUGE_VAL);
        t.text = std::move(text);
        return t;
    }
    double v = 0.0;
    auto res = std::from_chars(digits, end, v);
    if (res.ec == std::errc::result_out_of_range) {
        // from_chars reports underflow and overflow alike; strtod tells them apart.
        errno = 0;
        v = std::strtod(digits, nullptr);
        if (std::isinf(v) || std::fabs(v) > DBL_MAX)
            return error(line, "number out of range \"" + text + "\"");
        v = 0.0;
    } else if (res.ec != std::errc() || res.ptr != end) {
        return error(line, "malformed number \"" + text + "\"");
    }
    // Out of range only if it does not round to a float: the nine digits the writer gives
    // -FLT_MAX ("-3.40282347e+38") lie a little beyond it, and must read back.
    if (std::isinf(static_cast<float>(v)))
        return error(line, "number out of range \"" + text + "\"");
    t.number = neg ? -v : v;
    t.isInt = isInteger && t.number >= INT_MIN && t.number <= INT_MAX;
    t.text = std::move(text);
    return t;
}

}  // namespace rib
