// lexer.h: the tokenizer for RIB. It turns a byte stream (a string, or a file read
// through zlib so gzip-compressed and plain RIB both work) into words, strings, numbers
// and brackets, with line numbers. Bytes 0200-0377 are binary-encoded tokens (RI 3.2
// appendix C), decoded into the same kinds of tokens, so ASCII and binary may mix. Malformed tokens are reported to Diagnostics at their
// own line and come back as TokenKind::Error so the reader can drop just that request.
#pragma once
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "diagnostics.h"

struct gzFile_s;  // zlib's handle; zlib.h stays out of this header

namespace rib {

enum class TokenKind { Eof, Word, String, Number, LBracket, RBracket, Error };

struct Token {
    TokenKind kind = TokenKind::Eof;
    std::string text;  // the word, the decoded string, or a number's spelling
    double number = 0.0;
    bool isInt = false;  // an integer literal that fits in an int
    int line = 0;
};

class Lexer {
public:
    // `name` is the file name used in messages.
    Lexer(std::string name, Diagnostics& diag);
    // Reads from an in-memory text.
    void setText(std::string text);
    // Reads from an open zlib stream; the caller keeps ownership and closes it.
    void setFile(gzFile_s* file);

    Token next();
    // The first byte of the stream without consuming it, or -1 when it is empty: the
    // reader uses it to recognise binary RIB before tokenizing.
    int peekFirstByte();
    int line() const { return m_line; }
    const std::string& name() const { return m_name; }
    SourceLoc loc(int line) const { return SourceLoc{m_name, line}; }

private:
    int peek();
    int get();
    bool refill();
    static bool isDelimiter(int c);
    std::string readRun(int first);
    Token lexString(int startLine);
    Token lexNumber(std::string text, int line);
    Token error(int line, const std::string& msg);
    // lexer_binary.cpp
    bool lexBinary(int c, int line, Token& out);  // false: a definition, no token
    bool rawBytes(size_t n, uint8_t* out);        // no line counting
    bool rawUint(size_t n, uint32_t& out);
    Token binaryNumber(double v, bool isInt, int line);
    Token binaryString(size_t length, int line);
    Token nextBinaryArrayElement();
    Token binaryFixed(int c, int line);
    Token binaryLongString(int c, int line);
    Token binaryIeee(int c, int line);
    Token binaryRequestReference(int line);
    Token binaryArrayStart(int c, int line);
    bool binaryDefinition(int c, int line, Token& out);
    Token binaryStringReference(int c, int line);

    std::string m_name;
    Diagnostics& m_diag;
    gzFile_s* m_file = nullptr;
    std::vector<char> m_buf;
    size_t m_pos = 0;
    size_t m_len = 0;
    bool m_eof = false;
    int m_line = 1;
    // Binary RIB state: encoded request and string tables, and a float array being read.
    std::string m_binRequests[256];
    std::unordered_map<uint32_t, std::string> m_binStrings;
    bool m_inBinArray = false;
    uint32_t m_binArrayLeft = 0;
};

}  // namespace rib
