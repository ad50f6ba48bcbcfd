// ri_params.h: the variable-argument forms of the Ri calls (RiSphere(..., "Kd", &kd,
// RI_NULL)) collected into the token and value arrays of their V forms.
#pragma once
#include <cstdarg>
#include <vector>

#include "ri.h"

namespace rd::ri {

struct VarParams {
    std::vector<RtToken> tokens;
    std::vector<RtPointer> values;
    RtInt n() const { return RtInt(tokens.size()); }
    RtToken* t() { return tokens.data(); }
    RtPointer* v() { return values.data(); }
};

// (token, value) pairs up to RI_NULL.
inline VarParams collectParams(va_list ap) {
    VarParams p;
    for (;;) {
        RtToken token = va_arg(ap, RtToken);
        if (!token) break;
        p.tokens.push_back(token);
        p.values.push_back(va_arg(ap, RtPointer));
    }
    return p;
}

}  // namespace rd::ri

// The body of RiFoo(..., last, ...): its pairs collected, then `call` (which names them
// vp.n(), vp.t(), vp.v()).
#define RI_VARARGS(last, call)                        \
    va_list ap;                                       \
    va_start(ap, last);                               \
    rd::ri::VarParams vp = rd::ri::collectParams(ap); \
    va_end(ap);                                       \
    return call
