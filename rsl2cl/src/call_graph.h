// call_graph.h: the check that no shader reaches a function that calls itself, directly or
// through others. Shading language functions are inlined (as PRMan inlines them), and
// OpenCL C has no recursion: PoCL's compiler overflowed its own stack on a recursive
// kernel (the renderer crashed). Run after the type checker has bound every call.
#pragma once
#include <map>
#include <vector>

#include "ast.h"
#include "diagnostics.h"

namespace rsl {

// Reports each call that closes a cycle ("recursive call of 'f'") and a chain of calls
// nested more than 200 deep; false if there is either.
bool checkCallGraph(const Program& prog, Diagnostics& diag);

// The variables of enclosing scopes each function reaches (PRMan's `extern` in a nested
// function: a shader's parameters and locals, an enclosing function's), its own and
// those of the functions it calls, in first-use order. `functions` lists callees before
// callers (the code generator's order); the code generator passes each by address.
using FunctionCaptures = std::map<const FunctionDecl*, std::vector<const Symbol*>>;
FunctionCaptures functionCaptures(const std::vector<const FunctionDecl*>& functions);

}  // namespace rsl
