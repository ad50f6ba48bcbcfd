// gather.h: the gather() loop as a plain loop over trace sites (gather.cpp).
#pragma once
#include <vector>

#include "ast.h"

namespace rsl {

// The block that replaces `gather(args) hit else miss` (miss may be null); `id` tells
// this gather's variables and calls from every other's. Errors in the parameters go to
// diag.
StmtPtr desugarGather(const SourceLoc& loc, std::vector<ExprPtr> args, StmtPtr hit,
                      StmtPtr miss, int id, Diagnostics& diag);

}  // namespace rsl
