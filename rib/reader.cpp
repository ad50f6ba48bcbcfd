// reader.cpp: the RIB request parser. Each request is read whole (its name, then every
// value up to the next request name) before anything is checked, so a bad request can be
// dropped without losing sync with the stream. Positional arguments are matched against
// the signatures in requests.def, parameter lists are typed from inline declarations,
// Declare, the predefined names or the values themselves. The token source is the file
// being read, an archive it reads (ReadArchive swaps the lexer and recurses), or the
// recorded tokens of an inline archive.
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include "reader_impl.h"

namespace rib {
namespace detail {

namespace {

const RequestInfo kRequests[] = {
#define RIB_REQUEST(name, sig, kind, motion) {#name, sig, Req::name, Kind::kind, motion != 0},
#include "requests.def"
#undef RIB_REQUEST
};

}  // namespace

const RequestInfo* findRequest(const std::string& name) {
    static const std::unordered_map<std::string, const RequestInfo*> table = [] {
        std::unordered_map<std::string, const RequestInfo*> t;
        for (const RequestInfo& r : kRequests) t[r.name] = &r;
        return t;
    }();
    auto it = table.find(name);
    return it == table.end() ? nullptr : it->second;
}

Reader::Reader(Lexer& lex, Target& target, Diagnostics& diag, const ReadOptions& opts)
    : m_lex(&lex), m_target(target), m_diag(diag), m_opts(opts) {
    size_t slash = lex.name().rfind('/');
    if (slash != std::string::npos) m_dir = lex.name().substr(0, slash + 1);
    m_archivePath = opts.archiveSearchPath;
}

Token Reader::nextToken() {
    if (m_havePending) {
        m_havePending = false;
        return m_pending;
    }
    if (m_replay) {
        if (m_replayPos < m_replay->size()) return (*m_replay)[m_replayPos++];
        Token eof;
        eof.line = m_lastLine;
        return eof;
    }
    Token t = m_lex->next();
    if (t.kind != TokenKind::Eof)
        m_lastLine = t.line;  // EOF errors point at the last token
    return t;
}

SourceLoc Reader::loc(int line) const {
    return m_replay ? SourceLoc{m_replayFile, line} : m_lex->loc(line);
}

void Reader::run() {
    readStream();
    finish(loc(m_lastLine));
}

void Reader::finish(const SourceLoc& end) {
    if (m_diag.tooManyErrors()) return;
    for (auto it = m_blocks.rbegin(); it != m_blocks.rend(); ++it)
        error(end, std::string(it->name) + " at " + it->loc.str() + " never closed");
    for (auto it = m_conds.rbegin(); it != m_conds.rend(); ++it)
        error(end, "IfBegin at " + it->loc.str() + " never closed");
}

// Reads requests until the current source ends.
void Reader::readStream() {
    bool strayReported = false;
    while (!m_diag.tooManyErrors()) {
        Token t = nextToken();
        if (t.kind == TokenKind::Eof) break;
        if (t.kind != TokenKind::Word) {
            // Values with no request before them: say so once per run, then resync at
            // the next request name.
            if (t.kind != TokenKind::Error && !strayReported)
                error(loc(t.line), "expected a request name, got \"" + t.text + "\"");
            strayReported = true;
            continue;
        }
        strayReported = false;
        SourceLoc here = loc(t.line);
        std::vector<Value> vals;
        if (!findRequest(t.text)) {
            // Skip its values quietly: their shape is unknown, so only the lexer speaks.
            error(here, "unknown request \"" + t.text + "\"");
            m_quiet = true;
            collectValues(vals);
            m_quiet = false;
            continue;
        }
        if (!collectValues(vals)) continue;
        request(t.text, vals, here);
    }
}

void Reader::request(const std::string& name, const std::vector<Value>& vals,
                     const SourceLoc& here) {
    const RequestInfo* info = findRequest(name);
    if (!info) {
        error(here, "unknown request \"" + name + "\"");
        return;
    }
    if (info->sig[0] == '-') return;
    if (conditional(*info, vals, here) || !branchActive()) return;
    Args args;
    if (!parseArgs(*info, vals, args, here)) return;
    if (!checkScope(*info, here)) return;
    dispatch(*info, args, here);
}

// Reads every value up to the next request name. Returns false when any of them was bad
// (already reported): the request is then dropped, but the stream stays in sync.
bool Reader::collectValues(std::vector<Value>& out) {
    bool ok = true;
    while (!m_diag.tooManyErrors()) {
        Token t = nextToken();
        if (t.kind == TokenKind::Word || t.kind == TokenKind::Eof) {
            m_pending = t;
            m_havePending = true;
            break;
        }
        Value v;
        switch (t.kind) {
            case TokenKind::Number:
                v.nums.push_back(t.number);
                v.allInt = t.isInt;
                break;
            case TokenKind::String:
                v.isString = true;
                v.strs.push_back(t.text);
                break;
            case TokenKind::LBracket:
                if (!readArray(t, v)) ok = false;
                break;
            case TokenKind::RBracket:
                if (!m_quiet) error(loc(t.line), "unexpected ']'");
                ok = false;
                continue;
            default:  // Error: already reported by the lexer
                ok = false;
                continue;
        }
        if (ok) out.push_back(std::move(v));
    }
    return ok;
}

bool Reader::readArray(const Token& open, Value& v) {
    v.array = true;
    bool ok = true, tooBig = false;
    size_t count = 0;
    while (!m_diag.tooManyErrors()) {
        Token t = nextToken();
        if (t.kind == TokenKind::RBracket) return ok;
        if (t.kind == TokenKind::Word || t.kind == TokenKind::Eof) {
            m_pending = t;
            m_havePending = true;
            if (!m_quiet) error(loc(open.line), "unterminated '['");
            return false;
        }
        if (t.kind == TokenKind::Error) {
            ok = false;
            continue;
        }
        if (t.kind == TokenKind::LBracket) {
            if (!m_quiet) error(loc(t.line), "nested '[' is not allowed");
            ok = false;
            continue;
        }
        if (++count > m_opts.maxArrayValues) {
            // Keep consuming so the stream stays in sync, but store nothing more.
            if (!tooBig && !m_quiet)
                error(loc(open.line),
                             "array too large (more than " +
                                 std::to_string(m_opts.maxArrayValues) + " values)");
            tooBig = true;
            ok = false;
            v.nums.clear();
            v.strs.clear();
            continue;
        }
        bool isStr = t.kind == TokenKind::String;
        if (count > 1 && isStr != v.isString) {
            if (ok && !m_quiet)
                error(loc(t.line), "array mixes numbers and strings");
            ok = false;
            continue;
        }
        if (!ok) continue;
        if (isStr) {
            v.isString = true;
            v.strs.push_back(t.text);
        } else {
            v.nums.push_back(t.number);
            v.allInt = v.allInt && t.isInt;
        }
    }
    return false;
}

// A bracketed numeric array, or else a run of bare numbers (`limit` at most).
void ArgCursor::numbers(size_t limit, std::vector<double>& got) {
    if (vi < vals.size() && vals[vi].array && !vals[vi].isString) {
        got = vals[vi++].nums;
        return;
    }
    while (got.size() < limit && vi < vals.size() && !vals[vi].array &&
           !vals[vi].isString)
        got.push_back(vals[vi++].nums.front());
}

bool Reader::parseArgs(const RequestInfo& info, const std::vector<Value>& vals,
                       Args& args, const SourceLoc& loc) {
    std::string sig;
    for (const char* c = info.sig; *c; ++c)
        sig += *c == 'm' ? std::string(16, 'f') : std::string(1, *c);
    auto numeric = [](char c) { return c == 'f' || c == 'i'; };
    ArgCursor at{vals, info.name, loc};
    bool takesParams = false;
    for (size_t si = 0; si < sig.size();) {
        const char c = sig[si];
        if (c == 'p') {
            takesParams = true;
            ++si;
        } else if (c == '?') {
            ++si;
            if (at.vi >= vals.size() || (!vals[at.vi].array && vals[at.vi].isString)) {
                args.optionalMissing = true;
                while (si < sig.size() && sig[si] != 'p') ++si;
            }
        } else if (numeric(c)) {
            size_t run = 0;
            while (si + run < sig.size() && numeric(sig[si + run])) ++run;
            if (!argNumbers(at, sig.substr(si, run), si, args)) return false;
            si += run;
        } else {
            const std::string argNo = std::to_string(si + 1);
            bool ok = true;  // an unknown letter: a bug in requests.def, not in the input
            if (c == 'F' || c == 'C') ok = argFloatArray(at, c, argNo, args);
            if (c == 'B') ok = argBasis(at, argNo, args);
            if (c == 's' || c == 'h') ok = argString(at, c, argNo, args);
            if (c == 'S') ok = argStringArray(at, argNo, args);
            if (c == 'I') ok = argIntArray(at, argNo, args);
            if (!ok) return false;
            ++si;
        }
    }
    if (takesParams) return parseParams(info, vals, at.vi, args.params, loc);
    if (at.vi < vals.size()) {
        error(loc, at.req + " has too many arguments");
        return false;
    }
    return true;
}

// A run of numbers ('f' and 'i' letters of `run`), the first being argument first + 1.
bool Reader::argNumbers(ArgCursor& at, const std::string& run, size_t first, Args& args) {
    std::vector<double> got;
    at.numbers(SIZE_MAX, got);  // greedy, so a surplus is reported as such
    if (got.size() != run.size()) {
        error(at.loc, at.req + " expects " + plural(run.size(), "number") + ", got " +
                          std::to_string(got.size()));
        return false;
    }
    for (size_t k = 0; k < run.size(); ++k) {
        if (run[k] == 'i' && !isIntegral(got[k])) {
            error(at.loc, at.req + " expects an integer as argument " +
                              std::to_string(first + k + 1));
            return false;
        }
        args.nums.push_back(got[k]);
    }
    return true;
}

// 'F' a numeric array; 'C' a colour, ColorSamples numbers made the target's channels.
bool Reader::argFloatArray(ArgCursor& at, char c, const std::string& argNo, Args& args) {
    std::vector<double> got;
    const size_t start = at.vi;
    at.numbers(SIZE_MAX, got);
    if (c == 'C' && got.size() != static_cast<size_t>(m_nColor)) {
        error(at.loc, at.req + " expects " + plural(m_nColor, "number") +
                          " (ColorSamples), got " + std::to_string(got.size()));
        return false;
    }
    if (c == 'F' && at.vi == start) {
        error(at.loc, at.req + " expects a numeric array as argument " + argNo);
        return false;
    }
    args.floatArrays.emplace_back(got.begin(), got.end());
    if (c == 'C') args.floatArrays.back() = targetColors(args.floatArrays.back());
    return true;
}

// 'B' a basis: its name, or 16 numbers (and "" for the name).
bool Reader::argBasis(ArgCursor& at, const std::string& argNo, Args& args) {
    const Value* v = at.next();
    if (v && !v->array && v->isString) {
        args.strs.push_back(v->strs.front());
        args.nums.insert(args.nums.end(), 16, 0.0);
        ++at.vi;
        return true;
    }
    std::vector<double> got;
    at.numbers(16, got);
    if (got.size() != 16) {
        error(at.loc,
              at.req + " expects a basis name or 16 numbers as argument " + argNo);
        return false;
    }
    args.strs.emplace_back();
    args.nums.insert(args.nums.end(), got.begin(), got.end());
    return true;
}

// 's' a string; 'h' a handle: a string or an integer (RI 3.2's light handles).
bool Reader::argString(ArgCursor& at, char c, const std::string& argNo, Args& args) {
    const Value* v = at.next();
    if (v && v->isString && v->strs.size() == 1) {
        args.strs.push_back(v->strs.front());
    } else if (v && c == 'h' && !v->isString && v->nums.size() == 1 &&
               isIntegral(v->nums.front())) {
        args.strs.push_back(std::to_string(static_cast<int>(v->nums.front())));
    } else {
        error(at.loc, at.req +
                          (c == 's' ? " expects a string as argument "
                                    : " expects a handle as argument ") +
                          argNo);
        return false;
    }
    ++at.vi;
    return true;
}

bool Reader::argStringArray(ArgCursor& at, const std::string& argNo, Args& args) {
    const Value* v = at.next();
    if (!v || !v->array || (!v->isString && !v->nums.empty())) {
        error(at.loc, at.req + " expects a string array as argument " + argNo);
        return false;
    }
    args.strArrays.push_back(v->strs);
    ++at.vi;
    return true;
}

bool Reader::argIntArray(ArgCursor& at, const std::string& argNo, Args& args) {
    const Value* v = at.next();
    if (!v || !v->array || v->isString) {
        error(at.loc, at.req + " expects an integer array as argument " + argNo);
        return false;
    }
    std::vector<int> ints;
    ints.reserve(v->nums.size());
    for (double d : v->nums) {
        if (!isIntegral(d)) {
            error(at.loc, at.req + " expects integers in argument " + argNo);
            return false;
        }
        ints.push_back(static_cast<int>(d));
    }
    args.intArrays.push_back(std::move(ints));
    ++at.vi;
    return true;
}

bool Reader::parseParams(const RequestInfo& info, const std::vector<Value>& vals,
                         size_t vi, ParamList& out, const SourceLoc& loc) {
    for (; vi < vals.size(); vi += 2) {
        const Value& nameV = vals[vi];
        if (!nameV.isString || nameV.strs.size() != 1) {
            std::string got = nameV.array ? "an array" : "a number";
            if (!nameV.array && !nameV.nums.empty() && !nameV.isString)
                got = "the number " + std::to_string(nameV.nums.front());
            error(loc, std::string(info.name) +
                                  ": expected a parameter name, got " +
                                  (nameV.isString ? "a string array" : got));
            return false;
        }
        if (vi + 1 >= vals.size()) {
            error(loc, std::string(info.name) + ": parameter \"" +
                                  nameV.strs.front() + "\" has no value");
            return false;
        }
        Param p;
        if (!buildParam(info, nameV.strs.front(), vals[vi + 1], p, loc)) return false;
        out.params.push_back(std::move(p));
    }
    return true;
}

bool Reader::buildParam(const RequestInfo& info, const std::string& token, const Value& v,
                        Param& p, const SourceLoc& loc) {
    const std::string req = info.name;
    ParamDecl decl;
    const DeclLookup found = lookUpParam(token, decl, p.name);
    if (found == DeclLookup::Bad) {
        error(loc, req +
                       (token.find_first_of(" \t[") != std::string::npos
                            ? ": bad parameter declaration \""
                            : ": bad parameter name \"") +
                       token + "\"");
        return false;
    }
    // undeclared: the values decide (numbers float, strings string)
    const bool inferred = found == DeclLookup::Undeclared;
    p.type = decl.type;
    p.storage = decl.storage;
    p.arraySize = decl.arraySize;
    const std::string what = req + ": parameter \"" + p.name + "\"";
    size_t count = 0;
    if (v.isString) {
        if (p.type != ParamType::String) {
            if (!inferred) {
                error(loc, what + " is declared " + paramTypeName(p.type) +
                                      " but has string values");
                return false;
            }
            p.type = ParamType::String;
        }
        p.strings = v.strs;
        count = p.strings.size();
    } else if (p.type == ParamType::String) {
        if (!v.nums.empty()) {
            error(loc, what + " is declared string but has numbers");
            return false;
        }
    } else if (p.type == ParamType::Integer) {
        p.ints.reserve(v.nums.size());
        for (double d : v.nums) {
            if (!isIntegral(d)) {
                error(loc,
                             what + " is declared integer but has non-integer values");
                return false;
            }
            p.ints.push_back(static_cast<int>(d));
        }
        count = p.ints.size();
    } else {
        p.floats.reserve(v.nums.size());
        for (double d : v.nums) p.floats.push_back(static_cast<float>(d));
        count = p.floats.size();
    }
    if (p.type == ParamType::Color) p.colorComponents = m_nColor;
    size_t per = static_cast<size_t>(p.components()) * static_cast<size_t>(p.arraySize);
    if (per > 1 && count % per != 0) {
        std::string type = paramTypeName(p.type);
        if (p.arraySize > 1) type += "[" + std::to_string(p.arraySize) + "]";
        error(loc, what + " (" + type + ") needs a multiple of " +
                              std::to_string(per) + " values, got " +
                              std::to_string(count));
        return false;
    }
    if (p.type == ParamType::Color && !m_nRGB.empty()) {
        const int kept = m_target.keptColorSamples();
        p.floats = targetColors(p.floats);
        p.colorComponents = m_nColor <= kept            ? std::max(3, m_nColor)
                            : m_target.wantsRgbColors() ? 3
                                                        : m_nColor;
    }
    return true;
}

Reader::DeclLookup Reader::lookUpParam(const std::string& token, ParamDecl& decl,
                                       std::string& name) const {
    if (token.find_first_of(" \t[") != std::string::npos)
        return parseParamDecl(token, true, decl, name) ? DeclLookup::Declared
                                                       : DeclLookup::Bad;
    name = token;
    // A name must survive being written back inside a declaration.
    if (token.empty() || token.find_first_of("]\n\r\f\v") != std::string::npos)
        return DeclLookup::Bad;
    auto it = m_declared.find(token);
    if (it != m_declared.end()) {
        decl = it->second;
        return DeclLookup::Declared;
    }
    return predefinedParamDecl(token, decl) ? DeclLookup::Declared
                                            : DeclLookup::Undeclared;
}

std::vector<float> Reader::targetColors(const std::vector<float>& n) const {
    if (m_nRGB.empty()) return n;
    const int kept = m_target.keptColorSamples();
    const size_t k = m_nRGB.size() / 3;
    if (int(k) <= kept && k >= 3) return n;
    if (int(k) <= kept) {  // padded to three: the last one repeated
        std::vector<float> out;
        out.reserve(n.size() / k * 3);
        for (size_t base = 0; base + k <= n.size(); base += k)
            for (size_t j = 0; j < 3; ++j) out.push_back(n[base + std::min(j, k - 1)]);
        return out;
    }
    return m_target.wantsRgbColors() ? toRgb(n) : n;
}

std::vector<float> Reader::toRgb(const std::vector<float>& n) const {
    const size_t k = m_nRGB.size() / 3;
    std::vector<float> rgb;
    rgb.reserve(n.size() / k * 3);
    for (size_t base = 0; base + k <= n.size(); base += k)
        for (size_t j = 0; j < 3; ++j) {
            float v = 0.0f;
            for (size_t i = 0; i < k; ++i) v += n[base + i] * m_nRGB[i * 3 + j];
            rgb.push_back(v);
        }
    return rgb;
}

}  // namespace detail

bool readString(const std::string& text, const std::string& name, Target& target,
                Diagnostics& diag, const ReadOptions& options) {
    int before = diag.errorCount();
    ErrorMode mode = diag.mode();
    diag.setMode(options.errorHandler);
    Lexer lex(name, diag);
    lex.setText(text);
    detail::Reader reader(lex, target, diag, options);
    reader.run();
    diag.setMode(mode);
    return diag.errorCount() == before;
}

bool readFile(const std::string& path, Target& target, Diagnostics& diag,
              const ReadOptions& options) {
    int before = diag.errorCount();
    errno = 0;
    // "-": the standard input (a program's RIB through a pipe), plain or gzip
    const bool standardInput = path == "-";
    const std::string name = standardInput ? kStandardInputName : path;
    gzFile file =
        standardInput ? gzdopen(dup(STDIN_FILENO), "rb") : gzopen(path.c_str(), "rb");
    if (!file) {
        diag.error(SourceLoc{name, 0}, std::string("cannot open RIB file: ") +
                                           std::strerror(errno ? errno : ENOMEM));
        return false;
    }
    ErrorMode mode = diag.mode();
    diag.setMode(options.errorHandler);
    Lexer lex(name, diag);
    lex.setFile(file);
    detail::Reader reader(lex, target, diag, options);
    reader.run();
    diag.setMode(mode);
    gzclose(file);
    return diag.errorCount() == before;
}

}  // namespace rib
