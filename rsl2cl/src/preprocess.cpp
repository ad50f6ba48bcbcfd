// preprocess.cpp: include handling, macro expansion and conditional compilation.
#include "preprocess.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace rsl {
namespace {

struct Macro {
    bool functionLike = false;
    std::vector<std::string> params;
    std::vector<Token> body;
};

bool readFile(const std::string& path, std::string& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream ss;
    ss << in.rdbuf();
    out = ss.str();
    return true;
}

std::string dirName(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

class Preprocessor {
public:
    Preprocessor(const PreprocessOptions& opts, Diagnostics& diag)
        : m_opts(opts), m_diag(diag) {
        for (const auto& d : opts.defines) {
            Macro m;
            Diagnostics quiet;
            m.body = lexText(d.second, "<command line>", quiet);
            m.body.pop_back();
            m_macros[d.first] = m;
        }
    }

    std::vector<Token> run(const std::string& text, const std::string& name) {
        processText(text, name, 0);
        Token end;
        end.loc = m_mainEnd.file.empty() ? SourceLoc{name, 0, 0} : m_mainEnd;
        m_out.push_back(end);
        return std::move(m_out);
    }

private:
    struct Cond {
        bool active;       // this branch is being emitted
        bool taken;        // some branch of this #if was taken
        bool sawElse;
        bool parentActive;
        SourceLoc loc;
    };

    void processText(const std::string& text, const std::string& name, int depth) {
        std::vector<Token> toks = lexText(text, name, m_diag);
        if (depth == 0) m_mainEnd = toks.back().loc;
        std::vector<Cond> conds;
        size_t i = 0;
        while (toks[i].kind != TokKind::End) {
            bool active = conds.empty() || conds.back().active;
            if (toks[i].bol && toks[i].is("#")) {
                SourceLoc hashLoc = toks[i].loc;
                std::vector<Token> line;
                for (++i; toks[i].kind != TokKind::End && !toks[i].bol; ++i)
                    line.push_back(toks[i]);
                directive(hashLoc, line, conds, name, depth);
                continue;
            }
            if (!active) {
                ++i;
                continue;
            }
            if (toks[i].kind == TokKind::Ident && m_macros.count(toks[i].text)) {
                std::vector<Token> expanded;
                i = expandAt(toks, i, {}, expanded, 0);
                for (Token& t : expanded) t.bol = false;
                m_out.insert(m_out.end(), expanded.begin(), expanded.end());
                continue;
            }
            m_out.push_back(toks[i]);
            m_out.back().bol = false;
            ++i;
        }
        for (const Cond& c : conds) m_diag.error(c.loc, "unterminated conditional directive");
    }

    // Expands the macro use at toks[i]; returns the index after the use.
    size_t expandAt(const std::vector<Token>& toks, size_t i, std::set<std::string> off,
                    std::vector<Token>& out, int level) {
        const Token& nameTok = toks[i];
        const Macro& m = m_macros[nameTok.text];
        if (level > 100 || m_expansions > 100000) {
            if (m_expansions++ == 100001 || level == 101)
                m_diag.error(nameTok.loc, "macro expansion too deep");
            out.push_back(nameTok);
            return i + 1;
        }
        ++m_expansions;
        std::vector<std::vector<Token>> args;
        size_t next = i + 1;
        if (m.functionLike) {
            if (next >= toks.size() || !toks[next].is("(")) {
                out.push_back(nameTok);  // a function-like name without ( is left alone
                return i + 1;
            }
            int nest = 0;
            args.emplace_back();
            for (++next;; ++next) {
                if (next >= toks.size() || toks[next].kind == TokKind::End) {
                    m_diag.error(nameTok.loc, "unterminated call of macro '" +
                                                  nameTok.text + "'");
                    return next;
                }
                const Token& t = toks[next];
                if (t.is("(")) ++nest;
                if (t.is(")") && nest-- == 0) break;
                if (t.is(",") && nest == 0) {
                    args.emplace_back();
                    continue;
                }
                args.back().push_back(t);
            }
            ++next;
            if (args.size() == 1 && args[0].empty() && m.params.empty()) args.clear();
            if (args.size() != m.params.size()) {
                m_diag.error(nameTok.loc, "macro '" + nameTok.text + "' takes " +
                                              std::to_string(m.params.size()) +
                                              " argument(s), " +
                                              std::to_string(args.size()) + " given");
                return next;
            }
        }
        // Substitute parameters (arguments fully expanded first), # and ##.
        std::vector<Token> body;
        for (size_t b = 0; b < m.body.size(); ++b) {
            const Token& t = m.body[b];
            int p = paramIndex(m, t);
            if (t.is("#") && b + 1 < m.body.size() && paramIndex(m, m.body[b + 1]) >= 0) {
                Token s;
                s.kind = TokKind::String;
                s.text = tokensToText(args[paramIndex(m, m.body[++b])]);
                body.push_back(s);
            } else if (p >= 0) {
                std::vector<Token> e = expandList(args[p], off, level + 1);
                body.insert(body.end(), e.begin(), e.end());
            } else {
                body.push_back(t);
            }
        }
        body = paste(body);
        for (Token& t : body) t.loc = nameTok.loc;
        off.insert(nameTok.text);
        std::vector<Token> result = expandList(body, off, level + 1);
        out.insert(out.end(), result.begin(), result.end());
        return next;
    }

    static int paramIndex(const Macro& m, const Token& t) {
        if (t.kind != TokKind::Ident) return -1;
        for (size_t k = 0; k < m.params.size(); ++k)
            if (m.params[k] == t.text) return static_cast<int>(k);
        return -1;
    }

    std::vector<Token> paste(const std::vector<Token>& in) {
        std::vector<Token> out;
        for (size_t k = 0; k < in.size(); ++k) {
            if (in[k].is("##") && !out.empty() && k + 1 < in.size()) {
                std::string joined = out.back().text + in[k + 1].text;
                Diagnostics quiet;
                std::vector<Token> re = lexText(joined, in[k].loc.file, quiet);
                out.pop_back();
                out.insert(out.end(), re.begin(), re.end() - 1);
                ++k;
            } else {
                out.push_back(in[k]);
            }
        }
        return out;
    }

    std::vector<Token> expandList(const std::vector<Token>& in,
                                  const std::set<std::string>& off, int level) {
        std::vector<Token> out;
        for (size_t k = 0; k < in.size();) {
            if (in[k].kind == TokKind::Ident && m_macros.count(in[k].text) &&
                !off.count(in[k].text)) {
                k = expandAt(in, k, off, out, level);
            } else {
                out.push_back(in[k++]);
            }
        }
        return out;
    }

    void directive(const SourceLoc& hashLoc, std::vector<Token>& line,
                   std::vector<Cond>& conds, const std::string& file, int depth) {
        bool active = conds.empty() || conds.back().active;
        if (line.empty()) return;  // null directive
        const Token& d = line[0];
        std::string name = d.text;
        if (name == "if" || name == "ifdef" || name == "ifndef") {
            bool value = false;
            if (active) {
                if (name == "if") {
                    value = evalCondition(line, d.loc);
                } else if (line.size() < 2 || line[1].kind != TokKind::Ident) {
                    m_diag.error(d.loc, "#" + name + " needs a macro name");
                } else {
                    value = m_macros.count(line[1].text) == (name == "ifdef" ? 1u : 0u);
                }
            }
            conds.push_back({active && value, value, false, active, d.loc});
            return;
        }
        if (name == "elif" || name == "else" || name == "endif") {
            if (conds.empty()) {
                m_diag.error(d.loc, "#" + name + " without #if");
                return;
            }
            Cond& c = conds.back();
            if (name == "endif") {
                conds.pop_back();
                return;
            }
            if (c.sawElse) {
                m_diag.error(d.loc, "#" + name + " after #else");
                return;
            }
            bool value = false;
            if (name == "else") {
                c.sawElse = true;
                value = !c.taken;
            } else if (c.parentActive && !c.taken) {
                value = evalCondition(line, d.loc);
            }
            c.active = c.parentActive && value;
            c.taken = c.taken || value;
            return;
        }
        if (!active) return;
        if (name == "define") return define(line);
        if (name == "undef") {
            if (line.size() < 2 || line[1].kind != TokKind::Ident)
                m_diag.error(d.loc, "#undef needs a macro name");
            else
                m_macros.erase(line[1].text);
            return;
        }
        if (name == "include") return include(line, file, depth);
        if (name == "error") {
            std::vector<Token> rest(line.begin() + 1, line.end());
            m_diag.error(d.loc, "#error " + tokensToText(rest));
            return;
        }
        if (name == "warning") {
            std::vector<Token> rest(line.begin() + 1, line.end());
            m_diag.warning(d.loc, "#warning " + tokensToText(rest));
            return;
        }
        if (name == "pragma" || name == "line" || name == "ident") return;
        m_diag.error(d.loc, "unknown preprocessor directive '#" + name + "'");
        (void)hashLoc;
    }

    void define(const std::vector<Token>& line) {
        if (line.size() < 2 || line[1].kind != TokKind::Ident) {
            m_diag.error(line[0].loc, "#define needs a macro name");
            return;
        }
        const Token& n = line[1];
        Macro m;
        size_t k = 2;
        if (k < line.size() && line[k].is("(") && line[k].loc.line == n.loc.line &&
            line[k].loc.col == n.loc.col + static_cast<int>(n.text.size())) {
            m.functionLike = true;
            ++k;
            bool ok = true;
            if (k < line.size() && line[k].is(")")) {
                ++k;
            } else {
                for (;;) {
                    if (k >= line.size() || line[k].kind != TokKind::Ident) {
                        ok = false;
                        break;
                    }
                    m.params.push_back(line[k++].text);
                    if (k < line.size() && line[k].is(")")) {
                        ++k;
                        break;
                    }
                    if (k >= line.size() || !line[k].is(",")) {
                        ok = false;
                        break;
                    }
                    ++k;
                }
            }
            if (!ok) {
                m_diag.error(n.loc, "malformed parameter list of macro '" + n.text + "'");
                return;
            }
        }
        m.body.assign(line.begin() + static_cast<long>(k), line.end());
        m_macros[n.text] = m;
    }

    void include(const std::vector<Token>& line, const std::string& file, int depth) {
        const SourceLoc& loc = line[0].loc;
        std::string target;
        bool quoted = false;
        if (line.size() >= 2 && line[1].kind == TokKind::String) {
            target = line[1].text;
            quoted = true;
        } else if (line.size() >= 3 && line[1].is("<") && line.back().is(">")) {
            for (size_t k = 2; k + 1 < line.size(); ++k) target += line[k].text;
        } else {
            m_diag.error(loc, "#include expects \"file\" or <file>");
            return;
        }
        if (depth >= m_opts.maxIncludeDepth) {
            m_diag.error(loc, "#include nested too deeply");
            return;
        }
        std::vector<std::string> candidates;
        if (!target.empty() && target[0] == '/') {
            candidates.push_back(target);
        } else {
            if (quoted) candidates.push_back(dirName(file) + target);
            for (const std::string& dir : m_opts.includeDirs)
                candidates.push_back(dir.empty() || dir.back() == '/' ? dir + target
                                                                      : dir + "/" + target);
        }
        std::string text;
        for (const std::string& c : candidates) {
            if (readFile(c, text)) {
                processText(text, c, depth + 1);
                return;
            }
        }
        m_diag.error(loc, "cannot find include file '" + target + "'");
    }

    bool evalCondition(const std::vector<Token>& line, const SourceLoc& loc) {
        std::vector<Token> toks;
        for (size_t k = 1; k < line.size(); ++k) {
            if (line[k].isIdent("defined")) {
                bool paren = k + 1 < line.size() && line[k + 1].is("(");
                size_t n = k + (paren ? 2 : 1);
                if (n >= line.size() || line[n].kind != TokKind::Ident ||
                    (paren && (n + 1 >= line.size() || !line[n + 1].is(")")))) {
                    m_diag.error(line[k].loc, "malformed defined()");
                    return false;
                }
                Token v;
                v.kind = TokKind::Number;
                v.number = m_macros.count(line[n].text) ? 1 : 0;
                v.loc = line[k].loc;
                toks.push_back(v);
                k = n + (paren ? 1 : 0);
            } else {
                toks.push_back(line[k]);
            }
        }
        toks = expandList(toks, {}, 0);
        Token end;
        end.loc = loc;
        toks.push_back(end);
        CondEval e{toks, 0, m_diag, false, 0};
        long long v = e.ternary();
        if (!e.failed && toks[e.pos].kind != TokKind::End) e.fail(toks[e.pos]);
        return !e.failed && v != 0;
    }

    // Integer expression evaluator for #if (identifiers left after expansion are 0).
    // Arithmetic wraps (two's complement, as unsigned), so no input is undefined
    // behaviour or a trap (LLONG_MIN / -1); nesting is bounded, so no input overflows the
    // stack.
    struct CondEval {
        const std::vector<Token>& t;
        size_t pos;
        Diagnostics& diag;
        bool failed;
        int depth;
        static constexpr int kMaxDepth = 200;
        void fail(const Token& at) {
            if (!failed)
                diag.error(at.loc, at.kind == TokKind::End
                                       ? "missing expression in #if"
                                       : "unexpected '" + at.text + "' in #if");
            failed = true;
        }
        bool accept(const char* p) {
            if (!t[pos].is(p)) return false;
            ++pos;
            return true;
        }
        static long long wrap(unsigned long long v) { return static_cast<long long>(v); }
        static unsigned long long bits(long long v) { return static_cast<unsigned long long>(v); }
        // One level deeper (a parenthesis, a unary operator); false past kMaxDepth.
        bool enter() {
            if (depth < kMaxDepth) return ++depth, true;
            if (!failed) diag.error(t[pos].loc, "#if expression nested too deeply");
            failed = true;
            return false;
        }
        long long ternary() {
            if (!enter()) return 0;
            long long v = conditional();
            --depth;
            return v;
        }
        long long conditional() {
            long long c = binary(0);
            if (!accept("?")) return c;
            long long a = ternary();
            if (!accept(":")) fail(t[pos]);
            long long b = ternary();
            return c ? a : b;
        }
        // A unary operator's operand, counted in the nesting as a parenthesis is.
        long long operand() {
            if (!enter()) return 0;
            long long v = unary();
            --depth;
            return v;
        }
        long long binary(int prec) {
            static const std::vector<std::vector<std::string>> levels = {
                {"||"}, {"&&"}, {"|"}, {"^"}, {"&"}, {"==", "!="},
                {"<", ">", "<=", ">="}, {"+", "-"}, {"*", "/", "%"}};
            if (prec == static_cast<int>(levels.size())) return unary();
            long long v = binary(prec + 1);
            for (;;) {
                std::string op;
                for (const std::string& o : levels[prec])
                    if (t[pos].is(o.c_str())) op = o;
                if (op.empty() || failed) return v;
                const Token& at = t[pos++];
                long long r = binary(prec + 1);
                if ((op == "/" || op == "%") && r == 0) {
                    if (!failed) diag.error(at.loc, "division by zero in #if");
                    failed = true;
                    return 0;
                }
                if ((op == "/" || op == "%") && r == -1) {  // LLONG_MIN / -1 traps
                    v = op == "/" ? wrap(0ull - bits(v)) : 0;
                    continue;
                }
                if (op == "||") v = v || r;
                else if (op == "&&") v = v && r;
                else if (op == "|") v |= r;
                else if (op == "^") v ^= r;
                else if (op == "&") v &= r;
                else if (op == "==") v = v == r;
                else if (op == "!=") v = v != r;
                else if (op == "<") v = v < r;
                else if (op == ">") v = v > r;
                else if (op == "<=") v = v <= r;
                else if (op == ">=") v = v >= r;
                else if (op == "+") v = wrap(bits(v) + bits(r));
                else if (op == "-") v = wrap(bits(v) - bits(r));
                else if (op == "*") v = wrap(bits(v) * bits(r));
                else if (op == "/") v /= r;
                else v %= r;
            }
        }
        long long unary() {
            if (t[pos].is("!") || t[pos].is("-") || t[pos].is("+") || t[pos].is("~")) {
                const std::string op = t[pos++].text;
                long long v = operand();
                return op == "!" ? !v : op == "-" ? wrap(0ull - bits(v)) : op == "~" ? ~v : v;
            }
            if (accept("(")) {
                long long v = ternary();
                if (!accept(")")) fail(t[pos]);
                return v;
            }
            const Token& tok = t[pos];
            if (tok.kind == TokKind::Number) {
                ++pos;
                // the range of long long, exactly: 2^63 itself is out of it
                if (!(std::fabs(tok.number) < 9223372036854775808.0)) {
                    if (!failed) diag.error(tok.loc, "number out of range in #if");
                    failed = true;
                    return 0;
                }
                return static_cast<long long>(tok.number);
            }
            if (tok.kind == TokKind::Ident) {
                ++pos;
                return 0;
            }
            fail(tok);
            return 0;
        }
    };

    const PreprocessOptions& m_opts;
    Diagnostics& m_diag;
    std::map<std::string, Macro> m_macros;
    std::vector<Token> m_out;
    long m_expansions = 0;
    SourceLoc m_mainEnd;
};

}  // namespace

std::vector<Token> preprocessText(const std::string& text, const std::string& name,
                                  const PreprocessOptions& opts, Diagnostics& diag) {
    return Preprocessor(opts, diag).run(text, name);
}

std::vector<Token> preprocessFile(const std::string& path, const PreprocessOptions& opts,
                                  Diagnostics& diag) {
    std::string text;
    if (!readFile(path, text)) {
        diag.error(SourceLoc{path, 0, 0}, "cannot open file");
        std::vector<Token> end(1);
        end[0].loc = SourceLoc{path, 0, 0};
        return end;
    }
    return preprocessText(text, path, opts, diag);
}

std::string tokensToText(const std::vector<Token>& toks) {
    std::string out;
    for (const Token& t : toks) {
        if (t.kind == TokKind::End) break;
        if (!out.empty()) out += ' ';
        if (t.kind == TokKind::String) {
            out += '"';
            for (char c : t.text) {
                if (c == '"' || c == '\\') out += '\\';
                out += c;
            }
            out += '"';
        } else {
            out += t.text;
        }
    }
    return out;
}

}  // namespace rsl
