// emitter.cpp: ASCII and binary token encoding for RibWriter. ASCII numbers use %.9g so
// floats survive a write/read cycle bit for bit; binary integers use the fewest bytes,
// integral floats the integer form, multiples of 1/256 the fixed-point form, and the
// rest IEEE floats. Binary strings seen twice are defined once (0315) and referenced.
#include "emitter.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace rib {

void Emitter::intArray(const std::vector<int>& v) {
    open();
    for (int i : v) integer(i);
    close();
}

void Emitter::stringArray(const std::vector<std::string>& v) {
    open();
    for (const std::string& s : v) string(s);
    close();
}

// ---- ASCII

void AsciiEmitter::request(const std::string& name, int indent) {
    if (m_started) m_out << '\n';
    m_started = true;
    for (int i = 0; i < indent; ++i) m_out << "  ";
    m_out << name;
}

void AsciiEmitter::line(const std::string& text, int indent) {
    request(text, indent);  // (a line of its own, the next request starts the next)
}

void AsciiEmitter::string(const std::string& s) {
    m_out << " \"";
    for (char c : s) {
        unsigned char u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            m_out << '\\' << c;
        } else if (c == '\n') {
            m_out << "\\n";
        } else if (u < 0x20 || u == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\%03o", u);
            m_out << buf;
        } else {
            m_out << c;
        }
    }
    m_out << '"';
}

void AsciiEmitter::integer(int v) {
    m_out << ' ' << v;
}

void AsciiEmitter::number(float v) {
    char buf[32];
    if (std::isnan(v))
        std::snprintf(buf, sizeof buf, std::signbit(v) ? "-nan" : "nan");
    else if (std::isinf(v))
        std::snprintf(buf, sizeof buf, v > 0 ? "inf" : "-inf");
    else
        std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
    m_out << ' ' << buf;
}

void AsciiEmitter::floatArray(const std::vector<float>& v) {
    open();
    for (float f : v) number(f);
    close();
}

void AsciiEmitter::open() {
    m_out << " [";
}

void AsciiEmitter::close() {
    m_out << " ]";
}

void AsciiEmitter::finish() {
    if (m_started) m_out << '\n';
    m_out.flush();
}

// ---- Binary

void BinaryEmitter::bigEndian(uint64_t v, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) byte(static_cast<uint8_t>(v >> (8 * i)));
}

void BinaryEmitter::request(const std::string& name, int) {
    auto it = m_requests.find(name);
    if (it == m_requests.end()) {
        if (m_requests.size() >= 256) {  // out of codes: spell it in ASCII
            m_out << '\n' << name << ' ';
            return;
        }
        int code = static_cast<int>(m_requests.size());
        it = m_requests.emplace(name, code).first;
        byte(0314);
        byte(static_cast<uint8_t>(code));
        rawString(name);
    }
    byte(0246);
    byte(static_cast<uint8_t>(it->second));
}

void BinaryEmitter::rawString(const std::string& s) {
    size_t n = s.size();
    if (n < 16) {
        byte(static_cast<uint8_t>(0220 + n));
    } else {
        int l = n < (1u << 8) ? 0 : n < (1u << 16) ? 1 : n < (1u << 24) ? 2 : 3;
        byte(static_cast<uint8_t>(0240 + l));
        bigEndian(n, l + 1);
    }
    m_out.write(s.data(), static_cast<std::streamsize>(n));
}

void BinaryEmitter::string(const std::string& s) {
    auto it = m_strings.find(s);
    if (it == m_strings.end()) {
        if (s.size() < 2 || m_strings.size() >= 65536) {
            rawString(s);
            return;
        }
        uint32_t code = static_cast<uint32_t>(m_strings.size());
        it = m_strings.emplace(s, code).first;
        if (code < 256) {
            byte(0315);
            bigEndian(code, 1);
        } else {
            byte(0316);
            bigEndian(code, 2);
        }
        rawString(s);
    }
    if (it->second < 256) {
        byte(0317);
        bigEndian(it->second, 1);
    } else {
        byte(0320);
        bigEndian(it->second, 2);
    }
}

void BinaryEmitter::integer(int v) {
    int64_t x = v;
    int bytes = 1;
    while (bytes < 4 && (x < -(int64_t(1) << (8 * bytes - 1)) ||
                         x >= (int64_t(1) << (8 * bytes - 1))))
        ++bytes;
    byte(static_cast<uint8_t>(0200 + bytes - 1));
    bigEndian(static_cast<uint64_t>(x), bytes);
}

void BinaryEmitter::fixedPoint(double v, int bytes, int fractionBytes) {
    byte(static_cast<uint8_t>(0200 + 4 * fractionBytes + bytes - 1));
    int64_t x = static_cast<int64_t>(std::llround(v * std::ldexp(1.0, 8 * fractionBytes)));
    bigEndian(static_cast<uint64_t>(x), bytes);
}

void BinaryEmitter::ieeeFloat(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    byte(0244);
    bigEndian(bits, 4);
}

void BinaryEmitter::ieeeDouble(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    byte(0245);
    bigEndian(bits, 8);
}

void BinaryEmitter::number(float v) {
    bool negZero = v == 0 && std::signbit(v);  // only an IEEE float keeps -0
    if (std::isfinite(v) && std::fabs(v) < 8388608.f && std::floor(v) == v && !negZero) {
        integer(static_cast<int>(v));
    } else if (std::isfinite(v) && std::fabs(v) < 120.f && std::floor(v * 256) == v * 256 &&
               !negZero) {
        fixedPoint(v, 2, 1);  // 8.8 fixed point: exact for these
    } else {
        ieeeFloat(v);
    }
}

void BinaryEmitter::floatArray(const std::vector<float>& v) {
    size_t n = v.size();
    int l = n < (1u << 8) ? 0 : n < (1u << 16) ? 1 : n < (1u << 24) ? 2 : 3;
    byte(static_cast<uint8_t>(0310 + l));
    bigEndian(n, l + 1);
    for (float f : v) {
        uint32_t bits;
        std::memcpy(&bits, &f, 4);
        bigEndian(bits, 4);
    }
}

void BinaryEmitter::open() {
    m_out.put('[');
}

void BinaryEmitter::close() {
    m_out.put(']');
}

}  // namespace rib
