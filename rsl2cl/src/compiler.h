// compiler.h: the front-end pipeline in one call: preprocess, parse, type-check.
#pragma once
#include <memory>
#include <string>

#include "ast.h"
#include "diagnostics.h"
#include "info.h"
#include "preprocess.h"
#include "typecheck.h"

namespace rsl {

// Runs the front end on a file. Returns the program (possibly partial) and whether
// it is free of errors; every problem is in diag. Never throws for bad input.
bool compileFile(const std::string& path, const PreprocessOptions& opts, Program& prog,
                 Diagnostics& diag);
bool compileSource(const std::string& text, const std::string& name,
                   const PreprocessOptions& opts, Program& prog, Diagnostics& diag);

}  // namespace rsl
