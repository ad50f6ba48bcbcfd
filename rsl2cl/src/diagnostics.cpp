// diagnostics.cpp: formatting and collection of compiler messages.
#include "diagnostics.h"

namespace rsl {

std::string SourceLoc::str() const {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) {
        s += ":" + std::to_string(line);
        if (col > 0) s += ":" + std::to_string(col);
    }
    return s;
}

std::string Diagnostic::str() const {
    return loc.str() + (severity == Severity::Error ? ": error: " : ": warning: ") +
           message;
}

void Diagnostics::error(const SourceLoc& loc, const std::string& msg) {
    ++m_errors;
    add(Severity::Error, loc, msg);
}

void Diagnostics::warning(const SourceLoc& loc, const std::string& msg) {
    ++m_warnings;
    add(Severity::Warning, loc, msg);
}

void Diagnostics::add(Severity s, const SourceLoc& loc, const std::string& msg) {
    if (m_messages.size() >= m_maxStored) return;
    m_messages.push_back({s, loc, msg});
    if (m_echo) *m_echo << m_messages.back().str() << "\n";
}

std::string Diagnostics::text() const {
    std::string out;
    for (const Diagnostic& d : m_messages) out += d.str() + "\n";
    return out;
}

}  // namespace rsl
