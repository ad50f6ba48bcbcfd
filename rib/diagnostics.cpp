// diagnostics.cpp: formatting and counting of RIB diagnostics.
#include "diagnostics.h"

#include <algorithm>
#include <iostream>

namespace rib {

void Diagnostics::emit(const SourceLoc& loc, const char* kind, const std::string& msg) {
    m_last = loc.str() + ": " + kind + ": " + msg;
    if (m_out) *m_out << m_last << "\n";
    if (m_listener) m_listener(kind[0] == 'e', m_last);
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
    std::string key;
    for (char c : msg)
        if (c < '0' || c > '9') key += c;
    Repeats& r = m_repeats[key];
    if (++r.seen == 1) r.first = loc.str() + ": warning: " + msg;
    if (r.seen < kMaxRepeats) {
        emit(loc, "warning", msg);
    } else if (r.seen == kMaxRepeats) {
        emit(loc, "warning", msg + " (further warnings like this are not shown)");
    } else {
        m_last = loc.str() + ": warning: " + msg;
    }
}

void Diagnostics::printSuppressed() {
    for (auto& [key, r] : m_repeats) {
        if (r.seen > kMaxRepeats && m_out)
            *m_out << "note: " << r.seen - kMaxRepeats << " more warning(s) like \"" << r.first
                   << "\" were not shown\n";
        r.seen = std::min(r.seen, kMaxRepeats);  // (said once)
    }
}

} // namespace rib
