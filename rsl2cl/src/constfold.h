// constfold.h: evaluation of constant expressions (parameter defaults for --info and
// for the host, which fills in uniform parameters once per shader instance).
#pragma once
#include <string>
#include <vector>

#include "ast.h"

namespace rsl {

struct ConstValue {
    TypeSpec type;
    std::vector<double> values;  // 1 (float), 3 (triples), 16 (matrix); arrays flattened
    std::string str;             // string values
    std::string space;           // "rgb", "hsv", "world"... from a typecast, if any
    std::string text() const;    // 0.5 / "rgb" [1 1 1] / "plastic"
};

// Evaluates a typed constant expression; false when it is not constant (a global,
// a call other than a few pure math builtins...).
bool evalConst(const Expr& e, ConstValue& out);

// A triple in a named colour space ("hsv", "hsl", "XYZ"/"xyz", "xyY", "YIQ"; "rgb" or ""
// as it is) to RGB, in place, as rsl_stdlib.clh's rsl_to_rgb does; false for an unknown
// space.
bool colorSpaceToRgb(const std::string& space, double* c);

}  // namespace rsl
