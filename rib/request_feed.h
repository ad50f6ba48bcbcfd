// request_feed.h: requests given one at a time by a program instead of read from RIB text
// (the Ri API, host/ri/ri.h, is its client). Each request goes through the same checks,
// typing and Target calls as the RIB reader's, as soon as it is given, with its call
// number as the "line" of its messages; what a RIB file may do (ReadArchive, Declare,
// ErrorHandler) it may do too.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "diagnostics.h"
#include "param_decl.h"
#include "reader.h"
#include "target.h"

namespace rib {

// One value after a request name: a number, a string, or a bracketed array of either.
// An empty array is neither numeric nor string and matches both.
struct RequestValue {
    bool array = false;
    bool isString = false;
    bool allInt = true;
    std::vector<double> nums;
    std::vector<std::string> strs;
};

// Patches along one direction of a patch mesh (or segments of a curve) and the number of
// varying values along it (RI 3.2 section 5.3: cubic spans by the basis step). Returns
// false with `why` set when n does not fit the rules.
bool spanCount(bool cubic, bool periodic, long long n, int step, long long& patches,
               long long& varying, std::string& why);
// "periodic" or "nonperiodic"; false for anything else.
bool wrapMode(const std::string& w, bool& periodic);

namespace detail {
class Reader;
}

class RequestFeed {
public:
    // `name` names the source in messages ("Ri:12: error: ..." for the 12th call).
    RequestFeed(Target& target, Diagnostics& diag, const std::string& name,
                const ReadOptions& options = ReadOptions());
    ~RequestFeed();
    RequestFeed(const RequestFeed&) = delete;
    RequestFeed& operator=(const RequestFeed&) = delete;

    // A request by its RIB name ("Sphere") with its positional values and then its
    // parameters as (token, value) pairs, as they would follow the name in RIB; `line` is
    // the "line" its messages give (the caller's call number).
    void request(const std::string& name, const std::vector<RequestValue>& values,
                 int line);
    // Reports the blocks still open, at `line`.
    void finish(int line);
    // A parameter token's declaration (inline, Declare'd or predefined): false when it
    // has none (or a bad one); `name` gets the bare name.
    bool declaration(const std::string& token, ParamDecl& decl, std::string& name) const;
    // Floats a colour takes now (ColorSamples) and the Basis steps in force.
    int colorSamples() const;
    int ustep() const;
    int vstep() const;
    SourceLoc at(int line) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace rib
