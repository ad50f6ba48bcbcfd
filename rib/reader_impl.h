// reader_impl.h: internals of the RIB reader shared by its sources: reader.cpp (tokens to
// values to arguments), reader_dispatch.cpp (options, attributes, transforms),
// reader_geometry.cpp (primitives and their array-length checks), reader_scope.cpp
// (blocks, valid scopes, motion blocks) and reader_archive.cpp (ReadArchive, inline
// archives). Not part of the library's API; only the reader's own sources include it.
#pragma once
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "conditional.h"
#include "lexer.h"
#include "param_decl.h"
#include "reader.h"
#include "request_feed.h"

namespace rib {
namespace detail {

enum class Req {
#define RIB_REQUEST(name, sig, kind, motion) name,
#include "requests.def"
#undef RIB_REQUEST
};
constexpr size_t kRequestCount = 0
#define RIB_REQUEST(name, sig, kind, motion) +1
#include "requests.def"
#undef RIB_REQUEST
    ;

// Where a request may appear (the third column of requests.def).
enum class Kind { Any, Opt, Attr, Xform, Geom, Light, Tex, Block };

struct RequestInfo {
    const char* name;
    const char* sig;
    Req req;
    Kind kind;
    bool motion;  // may appear inside MotionBegin/MotionEnd
};

const RequestInfo* findRequest(const std::string& name);

// One value after a request name (request_feed.h).
using Value = RequestValue;

// A request's positional arguments by kind, in signature order within each kind.
struct Args {
    std::vector<double> nums;                    // f, i, m, and a B's sixteen numbers
    std::vector<std::string> strs;               // s, h, and a B's name ("" for numbers)
    std::vector<std::vector<int>> intArrays;     // I
    std::vector<std::vector<float>> floatArrays; // F, C
    std::vector<std::vector<std::string>> strArrays;  // S
    bool optionalMissing = false;                // the '?' group was left out
    ParamList params;
};

// A request's values being read as its positional arguments (Reader::parseArgs).
struct ArgCursor {
    const std::vector<Value>& vals;
    const std::string req;  // the request's name, for messages
    const SourceLoc& loc;
    size_t vi = 0;  // the next value
    const Value* next() const { return vi < vals.size() ? &vals[vi] : nullptr; }
    void numbers(size_t limit, std::vector<double>& got);
};

// A request's positional arguments by index. parseArgs guarantees their counts; these
// check anyway (0 or empty past the end), so that a table typo never reads out of range.
struct ArgAt {
    const Args& a;
    float f(size_t i) const {
        return i < a.nums.size() ? static_cast<float>(a.nums[i]) : 0.f;
    }
    int n(size_t i) const { return i < a.nums.size() ? static_cast<int>(a.nums[i]) : 0; }
    std::string s(size_t i) const {
        return i < a.strs.size() ? a.strs[i] : std::string();
    }
    std::vector<float> fa(size_t i) const {
        return i < a.floatArrays.size() ? a.floatArrays[i] : std::vector<float>();
    }
};

// Attribute and Option values by "group:name" (their first value), for conditional RIB.
using CondValues = std::unordered_map<std::string, CondValue>;

struct OpenBlock {
    Req begin = Req::version;
    const char* name = "";
    SourceLoc loc;
    int ustep = 3, vstep = 3;  // Basis steps to restore when an attribute block ends
    std::string solidOp;       // SolidBegin's operation
    size_t motionTimes = 0;    // MotionBegin: number of times
    size_t motionCount = 0;    // MotionBegin: requests seen so far
    const char* motionReq = nullptr;  // MotionBegin: the request being sampled
    std::shared_ptr<const CondValues>
        condAttributes;  // restored when an attribute block ends
};

// What the reader keeps of the attributes (the Basis steps, the values conditions read),
// saved by Resource "attributes" under a name.
struct ReaderAttributes {
    int ustep = 3, vstep = 3;
    std::shared_ptr<const CondValues> condAttributes;
};

// An IfBegin ... IfEnd being read: whether the branch being read is taken.
struct CondFrame {
    SourceLoc loc;
    bool parentActive = true;  // the IfBegin itself is in a taken branch
    bool taken = false;        // some branch so far was taken
    bool active = false;       // the branch being read is
    bool sawElse = false;
};

// An inline archive (ArchiveBegin "name" ... ArchiveEnd) kept as tokens for ReadArchive.
struct InlineArchive {
    std::string file;
    std::vector<Token> tokens;
};

inline bool isIntegral(double v) {
    return std::isfinite(v) && std::floor(v) == v && v >= -2147483648.0 &&
           v <= 2147483647.0;
}

inline std::string plural(size_t n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

// Shared by the geometry checks (reader_geometry.cpp).
long long sum(const std::vector<int>& v);

class Reader {
public:
    Reader(Lexer& lex, Target& target, Diagnostics& diag, const ReadOptions& opts);
    // Reads the lexer's stream to its end, then finish().
    void run();
    // One request with its values, as read from a stream or given by an API
    // (RequestFeed): checked, typed and dispatched.
    void request(const std::string& name, const std::vector<Value>& vals,
                 const SourceLoc& loc);
    // Reports the blocks still open at `end`.
    void finish(const SourceLoc& end);
    // How a parameter token ("Kd", "uniform float Kd") is declared: inline, by Declare or
    // predefined (Declared, `decl` and `name` set), not at all, or badly.
    enum class DeclLookup { Declared, Undeclared, Bad };
    DeclLookup lookUpParam(const std::string& token, ParamDecl& decl,
                           std::string& name) const;
    int colorSamples() const { return m_nColor; }
    int ustep() const { return m_ustep; }
    int vstep() const { return m_vstep; }

private:
    // reader.cpp
    void readStream();
    Token nextToken();
    SourceLoc loc(int line) const;
    bool collectValues(std::vector<Value>& out);
    bool readArray(const Token& open, Value& v);
    bool parseArgs(const RequestInfo& info, const std::vector<Value>& vals, Args& args,
                   const SourceLoc& loc);
    bool argNumbers(ArgCursor& at, const std::string& run, size_t first, Args& args);
    bool argFloatArray(ArgCursor& at, char c, const std::string& argNo, Args& args);
    bool argBasis(ArgCursor& at, const std::string& argNo, Args& args);
    bool argString(ArgCursor& at, char c, const std::string& argNo, Args& args);
    bool argStringArray(ArgCursor& at, const std::string& argNo, Args& args);
    bool argIntArray(ArgCursor& at, const std::string& argNo, Args& args);
    bool parseParams(const RequestInfo& info, const std::vector<Value>& vals, size_t vi,
                     ParamList& out, const SourceLoc& loc);
    bool buildParam(const RequestInfo& info, const std::string& token, const Value& v,
                    Param& out, const SourceLoc& loc);
    void error(const SourceLoc& loc, const std::string& msg) { m_diag.error(loc, msg); }

    // reader_dispatch.cpp
    void dispatch(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    // Each returns false for a request not of its family.
    bool dispatchOption(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchShading(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchAttribute(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchTransformOrTexture(const RequestInfo& info, const Args& a,
                                    const SourceLoc& loc);
    bool basisMatrix(const std::string& name, const double* nums, float m[16],
                     const SourceLoc& loc);

    // reader_geometry.cpp
    bool dispatchGeometry(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchPolygonsOrPatches(const RequestInfo& info, const Args& a,
                                   const SourceLoc& loc);
    bool dispatchQuadric(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchOtherGeometry(const RequestInfo& info, const Args& a,
                               const SourceLoc& loc);
    void dispatchProcedural(const Args& a, const SourceLoc& loc);
    bool checkGeneralPolygon(const Args& a, const SourceLoc& loc);
    bool checkPatch(const Args& a, const SourceLoc& loc);
    bool checkPointwise(const char* req, const ParamList& P, const SourceLoc& loc);
    long long countPoints(const char* req, const ParamList& params, const SourceLoc& loc);
    bool checkVaryingCounts(const char* req, const ParamList& params, long long uniform,
                            long long varying, long long vertex, long long faceVarying,
                            const SourceLoc& loc);
    bool checkPointsPolygons(const Args& a, const SourceLoc& loc);
    bool checkPointsGeneralPolygons(const Args& a, const SourceLoc& loc);
    bool checkPatchMesh(const Args& a, const SourceLoc& loc);
    bool checkNuPatch(const Args& a, const SourceLoc& loc);
    bool checkTrimCurve(const Args& a, const SourceLoc& loc);
    bool checkSubdivisionMesh(const Args& a, const SourceLoc& loc);
    bool checkCurves(const Args& a, const SourceLoc& loc);
    bool checkBlobby(const Args& a, const SourceLoc& loc);
    bool checkIndices(const char* req, const std::vector<int>& idx, long long n,
                      const char* what, const SourceLoc& loc);

    // reader_scope.cpp
    bool checkScope(const RequestInfo& info, const SourceLoc& loc);
    bool dispatchBlock(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchBegin(const RequestInfo& info, const Args& a, const SourceLoc& loc);
    bool dispatchEnd(const RequestInfo& info, const SourceLoc& loc);
    void motionBegin(const std::vector<float>& times, const SourceLoc& loc);
    void solidBegin(const std::string& op, const SourceLoc& loc);
    void motionEnd(const SourceLoc& loc);
    bool has(Req begin) const;
    void beginBlock(Req begin, const char* name, const SourceLoc& loc);
    bool endBlock(Req begin, const char* beginName, const char* endName,
                  const SourceLoc& loc);

    // reader_conditional.cpp
    // IfBegin, ElseIf, Else, IfEnd; true when `info` is one of them (handled).
    bool conditional(const RequestInfo& info, const std::vector<Value>& vals,
                     const SourceLoc& loc);
    bool branchActive() const { return m_conds.empty() || m_conds.back().active; }
    bool evaluate(const std::string& expr, const SourceLoc& loc);
    std::optional<CondValue> condVariable(const std::string& name) const;
    // Notes an Attribute's or an Option's values for $group:name.
    void noteCondValues(bool attribute, const std::string& group,
                        const ParamList& params);

    // Resource: checked, mirrored in the reader's own attributes, forwarded.
    void resource(const Args& a, const SourceLoc& loc);

    // reader_archive.cpp
    // DelayedReadArchive and RunProgram, expanded at once inside an attribute block (the
    // renderer does not yet defer them until a ray reaches their bound).
    void expandProcedural(const std::string& name, const std::vector<std::string>& args,
                          const SourceLoc& loc);
    void readArchive(const std::string& name, const ParamList& params,
                     const SourceLoc& loc);
    void recordInlineArchive(const std::string& name, const SourceLoc& loc);
    std::string resolveArchive(const std::string& name) const;
    std::string resolveDynamicObject(const std::string& name) const;
    void noteOption(const std::string& name, const ParamList& params);

    Lexer* m_lex;
    Target& m_target;
    Diagnostics& m_diag;
    const ReadOptions& m_opts;
    bool m_havePending = false;
    bool m_quiet = false;  // skipping an unknown request's values: no shape errors
    Token m_pending;
    int m_lastLine = 1;
    std::unordered_map<std::string, ParamDecl> m_declared;
    std::vector<OpenBlock> m_blocks;
    // How many blocks of each Begin request are open, so that has() does not walk
    // m_blocks: a request inside n nested blocks cost O(n), a file of them O(n^2) (300k
    // nested AttributeBegin: minutes).
    std::array<int, kRequestCount> m_open{};

    int m_nColor = 3;               // ColorSamples
    std::vector<float> m_nRGB;      // its n x 3 matrix, row i: channel i's RGB
    // n colour values -> RGB through m_nRGB, for targets that want RGB (wantsRgbColors)
    std::vector<float> toRgb(const std::vector<float>& n) const;
    // A colour's values as the target takes them (Target::keptColorSamples,
    // wantsRgbColors)
    std::vector<float> targetColors(const std::vector<float>& n) const;
    int m_ustep = 3, m_vstep = 3;   // Basis steps (bezier by default)
    int m_archiveDepth = 0;
    std::string m_dir;              // the directory of the file being read ("" or ".../")
    std::string m_archivePath;      // Option "searchpath" "archive", ':'-separated
    std::unordered_map<std::string, std::shared_ptr<const InlineArchive>> m_inlineArchives;
    std::shared_ptr<const InlineArchive> m_replayHold;  // keeps a replayed archive alive
    const std::vector<Token>* m_replay = nullptr;       // replaying an inline archive
    size_t m_replayPos = 0;
    std::string m_replayFile;
    std::unordered_set<std::string> m_objects;  // ObjectBegin handles seen
    std::vector<CondFrame> m_conds;             // open IfBegin blocks
    std::shared_ptr<CondValues> m_condAttributes = std::make_shared<CondValues>();
    CondValues m_condOptions;
    std::optional<int> m_frame;  // FrameBegin's number, for $Frame
    // Resource "attributes" saves by name, one map per ResourceBegin block open
    std::vector<std::unordered_map<std::string, ReaderAttributes>> m_resources{1};
};

}  // namespace detail
}  // namespace rib
