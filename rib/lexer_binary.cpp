// lexer_binary.cpp: binary-encoded RIB (RI 3.2 appendix C). Each byte 0200-0377 starts a
// token: integers and fixed-point numbers of 1-4 bytes (read as signed, big-endian),
// IEEE floats and doubles, short and long strings, float arrays (streamed one element at
// a time as '[' numbers ']', so a lying length cannot make us allocate), encoded request
// and string definitions (0314, 0315-0316) and references to them (0246, 0317-0320).
// Payload bytes never count as newlines; messages use the line of the last ASCII text.
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

#include "lexer.h"

namespace rib {

namespace {

std::string hexByte(int c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "0%03o", c & 0xff);
    return buf;
}

// A token of `kind` whose text is `text`
Token textToken(TokenKind kind, std::string text, int line) {
    Token t;
    t.kind = kind;
    t.text = std::move(text);
    t.line = line;
    return t;
}

std::string spell(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

}  // namespace

bool Lexer::rawBytes(size_t n, uint8_t* out) {
    for (size_t i = 0; i < n; ++i) {
        int c = peek();
        if (c < 0) return false;
        ++m_pos;
        out[i] = static_cast<uint8_t>(c);
    }
    return true;
}

bool Lexer::rawUint(size_t n, uint32_t& out) {
    uint8_t b[4] = {0, 0, 0, 0};
    if (n > 4 || !rawBytes(n, b)) return false;
    out = 0;
    for (size_t i = 0; i < n; ++i) out = (out << 8) | b[i];
    return true;
}

Token Lexer::binaryNumber(double v, bool isInt, int line) {
    Token t;
    t.kind = TokenKind::Number;
    t.number = v;
    t.isInt = isInt;
    t.text = spell(v);
    t.line = line;
    return t;
}

Token Lexer::binaryString(size_t length, int line) {
    Token t;
    t.kind = TokenKind::String;
    t.line = line;
    // Grows with the bytes actually present, so a huge declared length on a short
    // stream costs nothing.
    for (size_t i = 0; i < length; ++i) {
        int c = peek();
        if (c < 0) return error(line, "truncated binary string");
        ++m_pos;
        t.text += static_cast<char>(c);
    }
    return t;
}

Token Lexer::nextBinaryArrayElement() {
    int line = m_line;
    if (m_binArrayLeft == 0) {
        m_inBinArray = false;
        return textToken(TokenKind::RBracket, "]", line);
    }
    --m_binArrayLeft;
    uint32_t bits = 0;
    if (!rawUint(4, bits)) {
        m_inBinArray = false;
        return error(line, "truncated binary float array");
    }
    float f;
    std::memcpy(&f, &bits, 4);
    return binaryNumber(f, false, line);
}

bool Lexer::lexBinary(int c, int line, Token& out) {
    if (c == 0314 || c == 0315 || c == 0316) return binaryDefinition(c, line, out);
    out = c <= 0217                ? binaryFixed(c, line)
          : c <= 0237              ? binaryString(static_cast<size_t>(c - 0220), line)
          : c <= 0243              ? binaryLongString(c, line)
          : c <= 0245              ? binaryIeee(c, line)
          : c == 0246              ? binaryRequestReference(line)
          : c >= 0310 && c <= 0313 ? binaryArrayStart(c, line)
          : c == 0317 || c == 0320
              ? binaryStringReference(c, line)
              : error(line, "reserved binary RIB byte " + hexByte(c));
    return true;
}

// 0200 + 4d + w: w+1 bytes, d of them after the binary point
Token Lexer::binaryFixed(int c, int line) {
    size_t bytes = static_cast<size_t>(c & 3) + 1;
    int d = (c >> 2) & 3;
    uint32_t u = 0;
    if (!rawUint(bytes, u)) return error(line, "truncated binary number");
    // Sign-extend from `bytes` bytes.
    int64_t v = u;
    if (u & (1u << (8 * bytes - 1))) v -= int64_t(1) << (8 * bytes);
    return binaryNumber(static_cast<double>(v) / std::ldexp(1.0, 8 * d), d == 0, line);
}

// 0240-0243: a 1-4 byte length, then the bytes
Token Lexer::binaryLongString(int c, int line) {
    uint32_t n = 0;
    if (!rawUint(static_cast<size_t>(c - 0240) + 1, n))
        return error(line, "truncated binary string");
    return binaryString(n, line);
}

// 0244 an IEEE float, 0245 a double (within float's range), big-endian
Token Lexer::binaryIeee(int c, int line) {
    uint8_t b[8];
    size_t n = c == 0244 ? 4 : 8;
    if (!rawBytes(n, b)) return error(line, "truncated binary number");
    uint64_t bits = 0;
    for (size_t i = 0; i < n; ++i) bits = (bits << 8) | b[i];
    double v;
    if (n == 4) {
        uint32_t b32 = static_cast<uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, 4);
        v = f;
    } else {
        std::memcpy(&v, &bits, 8);
        if (std::isfinite(v) && std::fabs(v) > FLT_MAX)
            return error(line, "binary double out of range");
    }
    return binaryNumber(v, false, line);
}

Token Lexer::binaryRequestReference(int line) {
    uint8_t code = 0;
    if (!rawBytes(1, &code)) return error(line, "truncated encoded request");
    if (m_binRequests[code].empty())
        return error(line,
                     "encoded request " + std::to_string(code) + " was not defined");
    return textToken(TokenKind::Word, m_binRequests[code], line);
}

// 0310-0313: a 1-4 byte count; the floats follow as tokens (nextBinaryArrayElement)
Token Lexer::binaryArrayStart(int c, int line) {
    uint32_t n = 0;
    if (!rawUint(static_cast<size_t>(c - 0310) + 1, n))
        return error(line, "truncated binary float array");
    m_inBinArray = true;
    m_binArrayLeft = n;
    return textToken(TokenKind::LBracket, "[", line);
}

// 0314 defines an encoded request, 0315-0316 an encoded string: no token, unless an error
bool Lexer::binaryDefinition(int c, int line, Token& out) {
    uint32_t code = 0;
    if (!rawUint(c == 0316 ? 2 : 1, code)) {
        out = error(line, "truncated binary definition");
        return true;
    }
    Token name = next();
    if (name.kind == TokenKind::Error) {
        out = name;
        return true;
    }
    if (name.kind != TokenKind::String || (c == 0314 && name.text.empty())) {
        out = error(line, std::string(c == 0314 ? "encoded request" : "encoded string") +
                              " definition without a string");
        return true;
    }
    if (c == 0314)
        m_binRequests[code] = name.text;
    else
        m_binStrings[code] = name.text;
    return false;
}

Token Lexer::binaryStringReference(int c, int line) {
    uint32_t code = 0;
    if (!rawUint(c == 0320 ? 2 : 1, code)) return error(line, "truncated encoded string");
    auto it = m_binStrings.find(code);
    if (it == m_binStrings.end())
        return error(line, "encoded string " + std::to_string(code) + " was not defined");
    return textToken(TokenKind::String, it->second, line);
}

}  // namespace rib
