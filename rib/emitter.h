// emitter.h: the token encoders behind RibWriter: ASCII RIB text, or binary-encoded RIB
// (RI 3.2 appendix C: encoded requests, defined strings, compact integers, fixed-point
// and IEEE numbers, float arrays). Separate from the writer so either encoding writes
// every request the same way; tests also use BinaryEmitter to build binary input.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>
#include <unordered_map>
#include <vector>

namespace rib {

class Emitter {
public:
    explicit Emitter(std::ostream& out) : m_out(out) {}
    virtual ~Emitter() = default;
    virtual void request(const std::string& name, int indent) = 0;
    virtual void string(const std::string& s) = 0;
    virtual void integer(int v) = 0;
    virtual void number(float v) = 0;
    virtual void floatArray(const std::vector<float>& v) = 0;
    virtual void intArray(const std::vector<int>& v);
    virtual void stringArray(const std::vector<std::string>& v);
    virtual void finish() {}
    // A line of its own, as it is (a comment "# ...", a structure comment "## ...", or
    // verbatim RIB); it must hold no newline.
    virtual void line(const std::string& text, int indent) = 0;

protected:
    virtual void open() = 0;   // '['
    virtual void close() = 0;  // ']'
    std::ostream& m_out;
};

class AsciiEmitter : public Emitter {
public:
    using Emitter::Emitter;
    void request(const std::string& name, int indent) override;
    void line(const std::string& text, int indent) override;
    void string(const std::string& s) override;
    void integer(int v) override;
    void number(float v) override;
    void floatArray(const std::vector<float>& v) override;
    void finish() override;

private:
    void open() override;
    void close() override;
    bool m_started = false;
};

class BinaryEmitter : public Emitter {
public:
    using Emitter::Emitter;
    void request(const std::string& name, int indent) override;
    void line(const std::string& text, int) override { m_out << '\n' << text << '\n'; }
    void string(const std::string& s) override;
    void integer(int v) override;
    void number(float v) override;
    void floatArray(const std::vector<float>& v) override;
    // Lower-level encodings, for tests that build binary RIB by hand.
    void rawString(const std::string& s);  // 0220+n or 0240+l, never a definition
    void fixedPoint(double v, int bytes, int fractionBytes);
    void ieeeFloat(float v);
    void ieeeDouble(double v);
    void byte(uint8_t b) { m_out.put(static_cast<char>(b)); }

private:
    void open() override;
    void close() override;
    void bigEndian(uint64_t v, int bytes);
    std::unordered_map<std::string, int> m_requests;
    std::unordered_map<std::string, uint32_t> m_strings;
};

}  // namespace rib
