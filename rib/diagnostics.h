// diagnostics.h: source locations and the error/warning collector used by the RIB reader and
// the scene builder. Messages print as `file:line: error: message` (the compiler convention
// editors understand); callers recover and go on, and only main() decides the exit code.
#pragma once
#include <iosfwd>
#include <string>

namespace rib {

struct SourceLoc {
    std::string file;
    int line = 0;
    std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

class Diagnostics {
public:
    explicit Diagnostics(std::ostream* out = nullptr, int maxErrors = 100)
        : m_out(out), m_maxErrors(maxErrors) {}
    void error(const SourceLoc& loc, const std::string& msg);
    void warning(const SourceLoc& loc, const std::string& msg);
    int errorCount() const { return m_errors; }
    int warningCount() const { return m_warnings; }
    // After this many errors a reader stops: a corrupt or binary file read as text
    // would otherwise print one message per token.
    bool tooManyErrors() const { return m_errors >= m_maxErrors; }
    const std::string& lastMessage() const { return m_last; }

private:
    void emit(const SourceLoc& loc, const char* kind, const std::string& msg);
    std::ostream* m_out;
    int m_maxErrors;
    int m_errors = 0;
    int m_warnings = 0;
    std::string m_last;
};

} // namespace rib
