// builtins.cpp: decodes the signature strings of builtins.def and resolves overloads.
#include "builtins.h"

#include <climits>
#include <sstream>

namespace rsl {
namespace {

BuiltinSig decodeSig(const std::string& code) {
    BuiltinSig sig;
    sig.code = code;
    sig.ret = TypeSpec(typeFromCode(code[0]));
    bool output = false;
    for (size_t i = 1; i < code.size(); ++i) {
        char c = code[i];
        if (c == '&') {
            output = true;
            continue;
        }
        if (c == '+') { sig.repeatLast = true; continue; }
        if (c == '*') { sig.paramPairs = true; continue; }
        if (c == '.') { sig.variadic = true; continue; }
        BuiltinArg a;
        a.output = output;
        output = false;
        if (c == '?') {
            a.anyType = true;
        } else if (c >= 'A' && c <= 'Z') {
            a.type = TypeSpec(typeFromCode(static_cast<char>(c - 'A' + 'a')), -1);
        } else {
            a.type = TypeSpec(typeFromCode(c));
        }
        sig.args.push_back(a);
    }
    return sig;
}

std::vector<Builtin> buildTable() {
    std::vector<Builtin> table;
    auto add = [&](const char* name, const char* sigs, unsigned flags) {
        Builtin b;
        b.name = name;
        b.flags = flags;
        std::istringstream in(sigs);
        std::string code;
        while (in >> code) b.sigs.push_back(decodeSig(code));
        table.push_back(b);
    };
#define RSL_BUILTIN(name, sigs, flags) add(#name, sigs, flags);
#include "builtins.def"
#undef RSL_BUILTIN
    return table;
}

// Cost of calling sig with these argument types, or -1.
int matchCost(const BuiltinSig& sig, const std::vector<TypeSpec>& args) {
    size_t fixed = sig.args.size();
    if (args.size() < fixed) return -1;
    int cost = 0;
    for (size_t i = 0; i < fixed; ++i) {
        const BuiltinArg& a = sig.args[i];
        if (a.anyType) continue;
        int c = a.output ? (args[i] == a.type || args[i].isError() ? 0 : -1)
                         : coercionCost(args[i], a.type);
        if (c < 0) return -1;
        cost += c;
    }
    size_t extra = args.size() - fixed;
    if (extra == 0) return cost;
    if (sig.variadic) return cost + 5 * static_cast<int>(extra);
    if (sig.repeatLast && fixed > 0) {
        for (size_t i = fixed; i < args.size(); ++i) {
            int c = coercionCost(args[i], sig.args[fixed - 1].type);
            if (c < 0) return -1;
            cost += c;
        }
        return cost;
    }
    if (sig.paramPairs) {
        if (extra % 2 != 0) return -1;
        for (size_t i = fixed; i < args.size(); i += 2)
            if (!args[i].isString() && !args[i].isError()) return -1;
        return cost + 5 * static_cast<int>(extra);
    }
    return -1;
}

}  // namespace

const std::vector<Builtin>& builtinTable() {
    static const std::vector<Builtin> table = buildTable();
    return table;
}

const Builtin* findBuiltin(const std::string& name) {
    for (const Builtin& b : builtinTable())
        if (b.name == name) return &b;
    return nullptr;
}

const BuiltinSig* resolveOverload(const Builtin& b, const std::vector<TypeSpec>& args,
                                  const TypeSpec& expected) {
    const BuiltinSig* best = nullptr;
    int bestCost = INT_MAX;
    bool bestExpected = false;
    for (const BuiltinSig& sig : b.sigs) {
        int c = matchCost(sig, args);
        if (c < 0) continue;
        bool isExpected = !expected.isError() && sig.ret == expected;
        if (c < bestCost || (c == bestCost && isExpected && !bestExpected)) {
            best = &sig;
            bestCost = c;
            bestExpected = isExpected;
        }
    }
    return best;
}

std::string describeSignatures(const Builtin& b) {
    std::string out;
    for (const BuiltinSig& sig : b.sigs) {
        std::string s = sig.ret.str() + " " + b.name + "(";
        for (size_t i = 0; i < sig.args.size(); ++i) {
            const BuiltinArg& a = sig.args[i];
            s += (i ? ", " : "") + std::string(a.output ? "output " : "") +
                 (a.anyType ? "any" : a.type.str());
        }
        if (sig.repeatLast) s += ", ...";
        if (sig.paramPairs) s += sig.args.empty() ? "[\"param\", value]..." : ", [\"param\", value]...";
        if (sig.variadic) s += ", ...";
        out += "    " + s + ")\n";
    }
    return out;
}

}  // namespace rsl
