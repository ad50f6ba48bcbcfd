// constfold.cpp: constant folding of literals, arithmetic, casts and simple math.
#include "constfold.h"

#include <cmath>
#include <cstdio>

namespace rsl {
namespace {

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// Widens a float to n components (triples and matrices; a float matrix is diagonal).
bool widen(ConstValue& v, const TypeSpec& to) {
    if (to.isArray() || to.isString()) return v.type.base == to.base;
    size_t n = to.isMatrix() ? 16 : to.isTriple() ? 3 : 1;
    if (v.values.size() == n) {
        v.type = to;
        return true;
    }
    if (v.values.size() != 1) return false;
    double x = v.values[0];
    if (to.isMatrix()) {
        v.values.assign(16, 0.0);
        for (int i = 0; i < 4; ++i) v.values[i * 5] = x;
    } else {
        v.values.assign(n, x);
    }
    v.type = to;
    return true;
}

bool binary(const std::string& op, ConstValue a, ConstValue b, const TypeSpec& rt,
            ConstValue& out) {
    if (op == "." || op == "^" || rt.isMatrix()) return false;
    if (op == "==" || op == "!=" || op == "<" || op == ">" || op == "<=" || op == ">=" ||
        op == "&&" || op == "||") {
        if (a.values.size() != 1 || b.values.size() != 1) return false;
        double x = a.values[0], y = b.values[0];
        double r = op == "==" ? x == y : op == "!=" ? x != y : op == "<" ? x < y
                 : op == ">" ? x > y : op == "<=" ? x <= y : op == ">=" ? x >= y
                 : op == "&&" ? (x != 0 && y != 0) : (x != 0 || y != 0);
        out.type = TypeSpec(BaseType::Float);
        out.values = {r};
        return true;
    }
    if (!widen(a, rt) || !widen(b, rt)) return false;
    out.type = rt;
    out.values.resize(a.values.size());
    for (size_t i = 0; i < a.values.size(); ++i) {
        double x = a.values[i], y = b.values[i];
        out.values[i] = op == "+" ? x + y : op == "-" ? x - y : op == "*" ? x * y : x / y;
    }
    return true;
}

}  // namespace

std::string ConstValue::text() const {
    if (type.isString()) return "\"" + str + "\"";
    std::string s;
    if (!space.empty()) s = "\"" + space + "\" ";
    if (values.size() == 1 && !type.isArray()) return s + num(values[0]);
    s += "[";
    for (size_t i = 0; i < values.size(); ++i) s += (i ? " " : "") + num(values[i]);
    return s + "]";
}

bool colorSpaceToRgb(const std::string& space, double* c) {
    const double a = c[0], b = c[1], d = c[2];
    auto fromXyz = [&](double x, double y, double z) {
        c[0] = 3.240479 * x - 1.537150 * y - 0.498535 * z;
        c[1] = -0.969256 * x + 1.875992 * y + 0.041556 * z;
        c[2] = 0.055648 * x - 0.204043 * y + 1.057311 * z;
    };
    if (space.empty() || space == "rgb") return true;
    if (space == "hsv") {
        const double h = (a - std::floor(a)) * 6, s = b, v = d;
        const int i = int(std::floor(h));
        const double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
        const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
        for (int k = 0; k < 3; ++k) c[k] = rgb[i % 6][k];
        return true;
    }
    if (space == "hsl") {
        const double h = a, s = b, l = d;
        if (s == 0) return c[0] = c[1] = c[2] = l, true;
        const double m2 = l <= 0.5 ? l * (1 + s) : l + s - l * s, m1 = 2 * l - m2;
        auto v = [&](double hh) {
            hh -= std::floor(hh);
            if (hh < 1.0 / 6) return m1 + (m2 - m1) * hh * 6;
            if (hh < 0.5) return m2;
            if (hh < 2.0 / 3) return m1 + (m2 - m1) * (2.0 / 3 - hh) * 6;
            return m1;
        };
        c[0] = v(h + 1.0 / 3), c[1] = v(h), c[2] = v(h - 1.0 / 3);
        return true;
    }
    if (space == "XYZ" || space == "xyz") return fromXyz(a, b, d), true;
    if (space == "xyY") {  // chromaticity x, y and luminance Y
        if (b == 0) return fromXyz(0, 0, 0), true;
        return fromXyz(a * d / b, d, (1 - a - b) * d / b), true;
    }
    if (space == "YIQ") {
        c[0] = a + 0.956 * b + 0.621 * d;
        c[1] = a - 0.272 * b - 0.647 * d;
        c[2] = a - 1.105 * b + 1.702 * d;
        return true;
    }
    return false;
}

bool evalConst(const Expr& e, ConstValue& out) {
    out = ConstValue();
    switch (e.kind) {
    case ExprKind::Number:
        out.type = TypeSpec(BaseType::Float);
        out.values = {e.number};
        return true;
    case ExprKind::String:
        out.type = TypeSpec(BaseType::String);
        out.str = e.text;
        return true;
    case ExprKind::Unary: {
        if (!evalConst(*e.args[0], out) || out.type.isString()) return false;
        for (double& v : out.values) v = e.text == "-" ? -v : (v == 0 ? 1 : 0);
        return true;
    }
    case ExprKind::Binary: {
        ConstValue a, b;
        if (!evalConst(*e.args[0], a) || !evalConst(*e.args[1], b)) return false;
        if (a.type.isString() || b.type.isString()) return false;
        return binary(e.text, a, b, e.type, out);
    }
    case ExprKind::Ternary: {
        ConstValue c;
        if (!evalConst(*e.args[0], c) || c.values.size() != 1) return false;
        if (!evalConst(*e.args[c.values[0] != 0 ? 1 : 2], out)) return false;
        return widen(out, e.type);
    }
    case ExprKind::Cast: {
        if (!evalConst(*e.args[0], out) || !widen(out, e.castType)) return false;
        out.space = e.text;
        return true;
    }
    case ExprKind::Tuple: {
        out.type = e.type;
        for (const ExprPtr& a : e.args) {
            ConstValue c;
            if (!evalConst(*a, c) || c.type.isString()) return false;
            out.values.insert(out.values.end(), c.values.begin(), c.values.end());
        }
        return true;
    }
    case ExprKind::Call: {
        if (e.args.size() != 1 || !e.builtin) return false;
        ConstValue a;
        if (!evalConst(*e.args[0], a) || a.values.size() != 1) return false;
        double x = a.values[0];
        const std::string& n = e.text;
        double r;
        if (n == "radians") r = x * M_PI / 180;
        else if (n == "degrees") r = x * 180 / M_PI;
        else if (n == "cos") r = std::cos(x);
        else if (n == "sin") r = std::sin(x);
        else if (n == "sqrt") r = std::sqrt(x);
        else if (n == "abs") r = std::fabs(x);
        else return false;
        out.type = TypeSpec(BaseType::Float);
        out.values = {r};
        return true;
    }
    default: return false;
    }
}

}  // namespace rsl
