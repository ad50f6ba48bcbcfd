// reader_impl.h: internals of the RIB reader shared by reader.cpp (tokens to values to
// arguments) and reader_dispatch.cpp (checks, block nesting, Target calls). Not part of
// the library's API; only the reader's own sources include it.
#pragma once
#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

#include "lexer.h"
#include "param_decl.h"
#include "reader.h"

namespace rib {
namespace detail {

enum class Req {
#define RIB_REQUEST(name, sig) name,
#include "requests.def"
#undef RIB_REQUEST
};

struct RequestInfo {
    const char* name;
    const char* sig;
    Req req;
};

const RequestInfo* findRequest(const std::string& name);

// One value after a request name: a number, a string, or a bracketed array of either.
// An empty array is neither numeric nor string and matches both.
struct Value {
    bool array = false;
    bool isString = false;
    bool allInt = true;
    std::vector<double> nums;
    std::vector<std::string> strs;
};

struct Args {
    std::vector<double> nums;
    std::vector<std::string> strs;
    std::vector<std::vector<int>> intArrays;
    ParamList params;
};

struct OpenBlock {
    Req begin;
    const char* name;
    SourceLoc loc;
};

inline bool isIntegral(double v) {
    return std::isfinite(v) && std::floor(v) == v && v >= -2147483648.0 &&
           v <= 2147483647.0;
}

inline std::string plural(size_t n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

class Reader {
public:
    Reader(Lexer& lex, Target& target, Diagnostics& diag, const ReadOptions& opts)
        : m_lex(lex), m_target(target), m_diag(diag), m_opts(opts) {}
    void run();

private:
    Token nextToken();
    bool collectValues(std::vector<Value>& out);
    bool readArray(const Token& open, Value& v);
    bool parseArgs(const RequestInfo& info, const std::vector<Value>& vals, Args& args,
                   const SourceLoc& loc);
    bool parseParams(const RequestInfo& info, const std::vector<Value>& vals, size_t vi,
                     ParamList& out, const SourceLoc& loc);
    bool buildParam(const RequestInfo& info, const std::string& token, const Value& v,
                    Param& out, const SourceLoc& loc);
    long long countPoints(const char* req, const ParamList& params, const SourceLoc& loc);
    bool checkPointsPolygons(const Args& a, const SourceLoc& loc);
    void dispatch(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    void beginBlock(Req begin, const char* name, const SourceLoc& loc);
    bool endBlock(Req begin, const char* beginName, const char* endName,
                  const SourceLoc& loc);

    Lexer& m_lex;
    Target& m_target;
    Diagnostics& m_diag;
    const ReadOptions& m_opts;
    bool m_havePending = false;
    bool m_quiet = false;  // skipping an unknown request's values: no shape errors
    Token m_pending;
    int m_lastLine = 1;
    std::unordered_map<std::string, ParamDecl> m_declared;
    std::vector<OpenBlock> m_blocks;
};

}  // namespace detail
}  // namespace rib
