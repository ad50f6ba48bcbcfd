// builtins.h: the builtin function table (builtins.def) and overload resolution.
#pragma once
#include <string>
#include <vector>

#include "types.h"

namespace rsl {

enum BuiltinFlags : unsigned {
    BF_VARYING = 1u << 0,
    BF_DERIV = 1u << 1,
    BF_TRACE = 1u << 2,
    BF_TEXTURE = 1u << 3,
    BF_ENVIRONMENT = 1u << 4,
    BF_SHADOW = 1u << 5,
    BF_LIGHTING = 1u << 6,
    BF_MESSAGE = 1u << 7,
    BF_CHANNEL = 1u << 8,
};

struct BuiltinArg {
    TypeSpec type;        // Error when anyType
    bool output = false;  // must be an lvalue; written by the call
    bool anyType = false;
};

struct BuiltinSig {
    std::string code;  // as written in builtins.def, e.g. "fsff*"
    TypeSpec ret;
    std::vector<BuiltinArg> args;
    bool repeatLast = false;  // '+'
    bool paramPairs = false;  // '*'
    bool variadic = false;    // '.'
};

struct Builtin {
    std::string name;
    unsigned flags = 0;
    std::vector<BuiltinSig> sigs;
};

const std::vector<Builtin>& builtinTable();
const Builtin* findBuiltin(const std::string& name);

// Picks the cheapest overload for the argument types; among equally cheap ones the one
// returning `expected` (Error: no preference), else the first listed. Returns null
// when none accepts the arguments. argIsString[i] tells whether argument i is a
// string (needed to check "name", value pairs).
const BuiltinSig* resolveOverload(const Builtin& b, const std::vector<TypeSpec>& args,
                                  const TypeSpec& expected);
// Number of fixed arguments the overload expects and whether it accepts more.
std::string describeSignatures(const Builtin& b);  // "float texture(string, ...)" lines

}  // namespace rsl
