// typecheck.h: name resolution, type checking and uniform/varying inference.
#pragma once
#include "ast.h"
#include "diagnostics.h"

namespace rsl {

// Resolves every identifier and call, assigns types (Expr::type), picks builtin
// overloads (Expr::builtin/sig) and user functions (Expr::function), then infers
// uniform/varying (Expr::varying, Symbol::varying). Returns false on any error.
// Top-level functions are checked against the globals of the first shader's kind.
bool typecheckProgram(Program& prog, Diagnostics& diag);

// The uniform/varying pass alone (run by typecheckProgram after typing).
void inferVarying(Program& prog, Diagnostics& diag);

}  // namespace rsl
