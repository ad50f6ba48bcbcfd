// diagnostics.cpp: formatting and counting of RIB diagnostics.
#include "diagnostics.h"

#include <iostream>

namespace rib {

void Diagnostics::emit(const SourceLoc& loc, const char* kind, const std::string& msg) {
    m_last = loc.str() + ": " + kind + ": " + msg;
    if (m_out) *m_out << m_last << "\n";
}

void Diagnostics::error(const SourceLoc& loc, const std::string& msg) {
    if (m_mode == ErrorMode::Ignore) {
        ++m_ignored;
        return;
    }
    ++m_errors;
    emit(loc, "error", msg);
    if (m_mode == ErrorMode::Abort) m_aborted = true;
}

void Diagnostics::warning(const SourceLoc& loc, const std::string& msg) {
    if (m_mode == ErrorMode::Ignore) return;
    ++m_warnings;
    emit(loc, "warning", msg);
}

} // namespace rib
