// conditional.cpp: conditional RIB expressions (conditional.h), by recursive descent.
#include "conditional.h"

#include <re2/re2.h>

#include <cctype>
#include <cstdlib>
#include <vector>

namespace rib {
namespace {

class Parser {
public:
    Parser(const std::string& text, const CondLookup& lookup)
        : m_s(text), m_lookup(lookup) {}

    bool run(bool& result, std::string& error) {
        CondValue v;
        if (!orExpr(v)) {
            error = m_error;
            return false;
        }
        skip();
        if (m_i < m_s.size()) {
            error = "unexpected \"" + m_s.substr(m_i, 12) + "\" at column " +
                    std::to_string(m_i + 1);
            return false;
        }
        result = v.truth();
        return true;
    }

private:
    static CondValue boolean(bool b) {
        CondValue v;
        v.isNumber = true;
        v.number = b ? 1 : 0;
        return v;
    }
    bool fail(const std::string& what) {
        if (m_error.empty()) m_error = what + " at column " + std::to_string(m_i + 1);
        return false;
    }
    void skip() {
        while (m_i < m_s.size() && std::isspace(static_cast<unsigned char>(m_s[m_i])))
            ++m_i;
    }
    bool eat(const char* op) {
        skip();
        const size_t n = std::char_traits<char>::length(op);
        if (m_s.compare(m_i, n, op) != 0) return false;
        m_i += n;
        return true;
    }
    bool orExpr(CondValue& v) {
        if (++m_depth > kMaxDepth) return fail("nested too deeply");
        struct Leave {
            int& d;
            ~Leave() { --d; }
        } leave{m_depth};
        if (!andExpr(v)) return false;
        while (eat("||")) {
            CondValue r;
            if (!andExpr(r)) return false;
            v = boolean(v.truth() || r.truth());
        }
        return true;
    }
    bool andExpr(CondValue& v) {
        if (!notExpr(v)) return false;
        while (eat("&&")) {
            CondValue r;
            if (!notExpr(r)) return false;
            v = boolean(v.truth() && r.truth());
        }
        return true;
    }
    bool notExpr(CondValue& v) {
        bool negate = false, any = false;  // (a loop: "!!!!..." must not recurse)
        for (skip();
             m_i < m_s.size() && m_s[m_i] == '!' && m_s.compare(m_i, 2, "!=") != 0;
             skip())
            ++m_i, negate = !negate, any = true;
        if (!comparison(v)) return false;
        if (any) v = boolean(negate != v.truth());
        return true;
    }
    bool comparison(CondValue& v) {
        if (!primary(v)) return false;
        static const char* ops[] = {"==", "!=", "<=", ">=", "=~", "<", ">"};
        for (const char* op : ops) {
            if (!eat(op)) continue;
            CondValue r;
            if (!primary(r)) return false;
            const std::string o = op;
            if (o == "=~") return matches(r.text, v.text, v);
            int c;
            if (v.isNumber && r.isNumber)
                c = v.number < r.number ? -1 : v.number > r.number;
            else
                c = text(v).compare(text(r)), c = c < 0 ? -1 : c > 0;
            v = boolean(o == "=="   ? c == 0
                        : o == "!=" ? c != 0
                        : o == "<"  ? c < 0
                        : o == ">"  ? c > 0
                        : o == "<=" ? c <= 0
                                    : c >= 0);
            return true;
        }
        return true;
    }
    static std::string text(const CondValue& v) {
        if (!v.isNumber) return v.text;
        std::string s = std::to_string(v.number);
        s.erase(s.find_last_not_of('0') + 1);
        if (!s.empty() && s.back() == '.') s.pop_back();
        return s;
    }
    bool matches(const std::string& pattern, const std::string& subject, CondValue& out) {
        // RE2: time linear in the subject and memory bounded whatever the pattern
        // (std::regex backtracked without bound and recursed per character; a hostile
        // pattern could hang the reader or exhaust its stack). Its syntax is Perl's
        // without back-references.
        if (pattern.size() > kMaxRegex || subject.size() > kMaxRegex)
            return fail("a regular expression match longer than " +
                        std::to_string(kMaxRegex) + " characters");
        RE2::Options options;
        options.set_log_errors(false);
        options.set_max_mem(kRegexMemory);
        const RE2 re(pattern, options);
        if (!re.ok())
            return fail("bad regular expression '" + pattern + "': " + re.error());
        out = boolean(RE2::PartialMatch(subject, re));
        return true;
    }
    bool name(std::string& out) {
        const size_t start = m_i;
        while (m_i < m_s.size() &&
               (std::isalnum(static_cast<unsigned char>(m_s[m_i])) || m_s[m_i] == '_' ||
                m_s[m_i] == ':' || m_s[m_i] == '.'))
            ++m_i;
        out = m_s.substr(start, m_i - start);
        return !out.empty();
    }
    // $name or ${name}; sets `name` too (for defined()).
    bool variable(CondValue& v, std::string* named = nullptr) {
        ++m_i;  // '$'
        std::string n;
        if (m_i < m_s.size() && m_s[m_i] == '{') {
            const size_t close = m_s.find('}', m_i);
            if (close == std::string::npos) return fail("unterminated ${");
            n = m_s.substr(m_i + 1, close - m_i - 1);
            m_i = close + 1;
        } else if (!name(n)) {
            return fail("a variable name expected after $");
        }
        if (named) *named = n;
        v = m_lookup(n).value_or(CondValue{});
        return true;
    }
    bool primary(CondValue& v) {
        skip();
        if (m_i >= m_s.size()) return fail("a value expected");
        const char c = m_s[m_i];
        if (c == '(') {
            ++m_i;
            if (!orExpr(v)) return false;
            return eat(")") || fail("')' expected");
        }
        if (c == '\'' || c == '"') {
            const size_t close = m_s.find(c, m_i + 1);
            if (close == std::string::npos) return fail("unterminated string");
            v = CondValue{};
            v.text = m_s.substr(m_i + 1, close - m_i - 1);
            m_i = close + 1;
            return true;
        }
        if (c == '$') return variable(v);
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' ||
            c == '.') {
            char* end = nullptr;
            const double d = std::strtod(m_s.c_str() + m_i, &end);
            if (end == m_s.c_str() + m_i) return fail("a number expected");
            m_i = size_t(end - m_s.c_str());
            v = CondValue{};
            v.isNumber = true;
            v.number = d;
            return true;
        }
        std::string fn;
        if (!name(fn)) return fail("unexpected '" + std::string(1, c) + "'");
        if (!eat("(")) return fail("'(' expected after " + fn);
        if (fn == "defined") {
            skip();
            std::string n;
            if (m_i < m_s.size() && m_s[m_i] == '$') {
                CondValue ignored;
                if (!variable(ignored, &n)) return false;
            } else if (!name(n)) {
                return fail("a variable name expected in defined()");
            }
            v = boolean(m_lookup(n).has_value());
            return eat(")") || fail("')' expected");
        }
        std::vector<CondValue> args;
        skip();
        if (!eat(")")) {
            do {
                CondValue a;
                if (!orExpr(a)) return false;
                args.push_back(a);
            } while (eat(","));
            if (!eat(")")) return fail("')' expected");
        }
        if (fn == "concat") {
            v = CondValue{};
            for (const CondValue& a : args) v.text += text(a);
            return true;
        }
        if (fn == "match") {
            if (args.size() != 2) return fail("match() takes a pattern and a string");
            return matches(text(args[0]), text(args[1]), v);
        }
        return fail("unknown function " + fn + "()");
    }

    static constexpr size_t kMaxRegex = 256;
    static constexpr int64_t kRegexMemory = int64_t(1) << 20;  // bytes
    static constexpr int kMaxDepth = 200;
    const std::string& m_s;
    const CondLookup& m_lookup;
    size_t m_i = 0;
    int m_depth = 0;
    std::string m_error;
};

}  // namespace

bool evaluateCondition(const std::string& expr, const CondLookup& lookup, bool& result,
                       std::string& error) {
    Parser p(expr, lookup);
    return p.run(result, error);
}

}  // namespace rib
