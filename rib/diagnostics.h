// diagnostics.h: source locations and the error/warning collector used by the RIB reader and
// the scene builder. Messages print as `file:line: error: message` (the compiler convention
// editors understand); callers recover and go on, and only main() decides the exit code.
#pragma once
#include <functional>
#include <iosfwd>
#include <map>
#include <string>

namespace rib {

// RiErrorHandler semantics: print each error (the default), ignore errors (neither
// printed nor counted; ignoredCount() says how many), or abort: the first error is
// printed and tooManyErrors() turns true, so readers stop there.
enum class ErrorMode { Print, Ignore, Abort };

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
    bool tooManyErrors() const { return m_errors >= m_maxErrors || m_aborted; }
    const std::string& lastMessage() const { return m_last; }
    void setMode(ErrorMode mode) { m_mode = mode; }
    ErrorMode mode() const { return m_mode; }
    int ignoredCount() const { return m_ignored; }
    bool aborted() const { return m_aborted; }
    // A warning repeated with only its numbers changed (one per mesh of a large file) is
    // printed kMaxRepeats times, the last saying so; the rest are counted, and this
    // prints how many of each were not shown (main, at the end).
    static constexpr int kMaxRepeats = 5;
    void printSuppressed();
    // Where messages go: the stream (nullptr: nowhere), and a listener also called with
    // each message shown (the Ri API's RiErrorHandler).
    void setOutput(std::ostream* out) { m_out = out; }
    using Listener = std::function<void(bool isError, const std::string& message)>;
    void setListener(Listener listener) { m_listener = std::move(listener); }

private:
    void emit(const SourceLoc& loc, const char* kind, const std::string& msg);
    std::ostream* m_out;
    Listener m_listener;
    int m_maxErrors;
    int m_errors = 0;
    int m_warnings = 0;
    int m_ignored = 0;
    bool m_aborted = false;
    ErrorMode m_mode = ErrorMode::Print;
    std::string m_last;
    struct Repeats {
        int seen = 0;
        std::string first;  // the first such message, for the summary
    };
    std::map<std::string, Repeats> m_repeats;  // by the message without its digits
};

} // namespace rib
