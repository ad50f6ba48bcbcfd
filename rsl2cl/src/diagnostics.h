// diagnostics.h: source locations and the error/warning sink of rsl2cl.
// Messages read `file:line:col: error|warning: message`; the library never exits.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace rsl {

struct SourceLoc {
    std::string file;
    int line = 0;
    int col = 0;
    std::string str() const;  // "file:line:col" (parts omitted when unknown)
};

enum class Severity { Error, Warning };

struct Diagnostic {
    Severity severity;
    SourceLoc loc;
    std::string message;
    std::string str() const;
};

class Diagnostics {
public:
    // When echo is set every message is also written there as it arrives.
    explicit Diagnostics(std::ostream* echo = nullptr) : m_echo(echo) {}
    void error(const SourceLoc& loc, const std::string& msg);
    void warning(const SourceLoc& loc, const std::string& msg);
    int errorCount() const { return m_errors; }
    int warningCount() const { return m_warnings; }
    bool hasErrors() const { return m_errors > 0; }
    const std::vector<Diagnostic>& messages() const { return m_messages; }
    std::string text() const;  // every message, one per line
    // Past this many errors further ones are counted but not stored.
    void setMaxStored(size_t n) { m_maxStored = n; }

private:
    void add(Severity s, const SourceLoc& loc, const std::string& msg);
    std::ostream* m_echo;
    std::vector<Diagnostic> m_messages;
    int m_errors = 0;
    int m_warnings = 0;
    size_t m_maxStored = 1000;
};

}  // namespace rsl
