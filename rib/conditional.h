// conditional.h: the expressions of conditional RIB (PRMan's IfBegin "expr" / ElseIf
// "expr" / Else / IfEnd). An expression compares values: numbers, strings in single
// quotes, and variables `$name` or `${name}` (the reader looks them up: `$user:pass` is
// Attribute "user" "pass" where set, else Option "user" "pass"; `$Frame` the frame
// number; an unset variable is the empty string). Operators, loosest first: `||`, `&&`,
// `!`, then `==` `!=` `<` `>` `<=` `>=` (numbers compared as numbers when both sides are
// numbers, else as strings) and `=~` (the left side matched against a regular
// expression, ECMAScript syntax); parentheses group. Functions: `defined(name)` (or
// `defined($name)`), `concat(a, b, ...)`, `match('regex', s)`. A value is true when it
// is a non-zero number or a non-empty string.
#pragma once
#include <functional>
#include <optional>
#include <string>

namespace rib {

struct CondValue {
    bool isNumber = false;
    double number = 0;
    std::string text;
    bool truth() const { return isNumber ? number != 0 : !text.empty(); }
};

// The value of variable `name` (without its '$'), or nothing when it is not set.
using CondLookup = std::function<std::optional<CondValue>(const std::string& name)>;

// Evaluates `expr`; false with `error` set (what and where in the expression) when it
// does not parse or a regular expression is bad.
bool evaluateCondition(const std::string& expr, const CondLookup& lookup, bool& result,
                       std::string& error);

}  // namespace rib
