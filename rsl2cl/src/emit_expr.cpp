// emit_expr.cpp: OpenCL C for RSL expressions (operators, coercions, casts, calls).
#include <cmath>
#include <cstdio>

#include "emit_internal.h"

namespace rsl {

const char* clType(const TypeSpec& t) {
    switch (t.base) {
    case BaseType::Float: return "float";
    case BaseType::Point:
    case BaseType::Vector:
    case BaseType::Normal: return "float4";
    case BaseType::Color: return "rsl_color";
    case BaseType::Matrix: return "RslMatrix";
    case BaseType::String: return "int";
    case BaseType::Void: return "void";
    default: return "float";
    }
}

std::string clZero(const TypeSpec& t) {
    switch (t.base) {
    case BaseType::Point:
    case BaseType::Vector:
    case BaseType::Normal: return "rsl_f2v(0.0f)";
    case BaseType::Color: return "rsl_f2c(0.0f)";
    case BaseType::Matrix: return "rsl_mscalar(0.0f)";
    case BaseType::String: return "0";
    default: return "0.0f";
    }
}

std::string clNumber(double v) {
    if (!std::isfinite(v)) return v > 0 ? "INFINITY" : (v < 0 ? "(-INFINITY)" : "NAN");
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    s += "f";
    return v < 0 ? "(" + s + ")" : s;
}

int spaceIdOf(const std::string& n) {
    static const char* names[] = {"current", "world", "camera", "object",
                                  "shader", "screen", "raster", "NDC"};
    for (int i = 0; i < 8; ++i)
        if (n == names[i]) return i;
    return -1;
}

int colorIdOf(const std::string& n) {
    if (n == "rgb") return 0;
    if (n == "hsv") return 1;
    if (n == "hsl") return 2;
    if (n == "xyz" || n == "XYZ") return 3;
    if (n == "xyY") return 4;
    if (n == "YIQ") return 5;
    return -1;
}

int stringId(const std::string& s) {
    if (s.empty()) return 0;
    uint32_t h = 0x811c9dc5u;
    for (unsigned char c : s) {
        h ^= c;
        h *= 0x01000193u;
    }
    h &= 0xffffffu;
    return h ? static_cast<int>(h) : 1;
}

std::string Emitter::stringLiteral(const std::string& s) {
    bool seen = false;
    for (const std::string& x : m_out.strings) seen = seen || x == s;
    if (!seen) m_out.strings.push_back(s);
    return std::to_string(stringId(s));
}

std::string Emitter::coerce(const std::string& code, const TypeSpec& from, const TypeSpec& to) {
    if (from.isArray() || to.isArray()) return code;
    if (from.isFloat() && to.isColor()) return "rsl_f2c(" + code + ")";
    if (from.isFloat() && to.isTriple()) return "rsl_f2v(" + code + ")";
    if (from.isPointLike() && to.isColor()) return "rsl_c3(" + code + ")";  // a cast
    if (from.isColor() && to.isPointLike()) return "rsl_c2v(" + code + ")";
    if (from.isFloat() && to.isMatrix()) return "rsl_mscalar(" + code + ")";
    return code;
}

std::string Emitter::exprAs(const Expr& e, const TypeSpec& to) {
    return coerce(expr(e), e.type, to);
}

std::string Emitter::varName(const Symbol* s) {
    if (!s) return "0";
    if (s->kind == SymbolKind::Global) {
        static const std::set<std::string> inStruct = {
            "P", "N", "Ng", "I", "E", "dPdu", "dPdv", "Cs", "Os", "Ci", "Oi", "L", "Cl",
            "Ol", "Ps", "u", "v", "s", "t", "du", "dv", "ncomps", "time"};
        if (inStruct.count(s->name)) return "g->" + s->name;
        if (s->name == "PI") return "RSL_PI";
        return "_g_" + s->name;  // alpha, dtime, dPdtime: locals of every function
    }
    if (s->kind == SymbolKind::Param && !m_func) return "p_" + s->name;
    if (m_func && !m_fnLocals.count(s)) {  // a variable of an enclosing scope (extern)
        const std::string c = captureName(s);
        if (!c.empty()) return s->type.isArray() ? c : "(*" + c + ")";
        error(s->loc, "'" + s->name + "' of an enclosing scope used (extern) in function '" +
                          m_func->name + "': not reached");
        return "0";
    }
    if (m_pointerParams.count(s)) return "(*v_" + s->name + ")";
    return "v_" + s->name;
}

std::string Emitter::lvalue(const Expr& e) { return expr(e); }

std::string Emitter::captureName(const Symbol* s) {
    if (!m_func) return "";
    const std::vector<const Symbol*>& caps = m_captures[m_func];
    for (size_t k = 0; k < caps.size(); ++k)
        if (caps[k] == s) return "c" + std::to_string(k) + "_" + s->name;
    return "";
}

std::string Emitter::addressOf(const Symbol* s) {
    const std::string c = captureName(s);  // (passed on from the caller's own captures)
    if (!c.empty()) return c;
    const std::string v = varName(s);
    return s->type.isArray() ? v : "&" + v;
}

static bool isRel(const std::string& op) {
    return op == "<" || op == ">" || op == "<=" || op == ">=" || op == "==" || op == "!=" ||
           op == "&&" || op == "||";
}

std::string Emitter::binop(const std::string& op, const std::string& a, const TypeSpec& ta,
                           const std::string& b, const TypeSpec& tb, const SourceLoc& loc) {
    TypeSpec r = binaryResult(op, ta, tb);
    if (op == ".") return (ta.isColor() ? "rsl_cdot(" : "rsl_dot(") + a + ", " + b + ")";
    if (op == "^") return "rsl_cross(" + a + ", " + b + ")";
    if (op == "&&" || op == "||") return "((float)(" + a + " " + op + " " + b + "))";
    if (op == "==" || op == "!=") {
        std::string neg = op == "!=" ? "!" : "";
        if (ta.isMatrix() || tb.isMatrix())
            return "((float)" + neg + "rsl_meq(" + coerce(a, ta, BaseType::Matrix) + ", " +
                   coerce(b, tb, BaseType::Matrix) + "))";
        if (ta.isColor() || tb.isColor())
            return "((float)" + neg + "rsl_ceq(" + coerce(a, ta, BaseType::Color) + ", " +
                   coerce(b, tb, BaseType::Color) + "))";
        if (ta.isTriple() || tb.isTriple())
            return "((float)" + neg + "rsl_veq(" + coerce(a, ta, BaseType::Vector) +
                   ", " + coerce(b, tb, BaseType::Vector) + "))";
        return "((float)(" + a + " " + op + " " + b + "))";
    }
    if (isRel(op)) return "((float)(" + a + " " + op + " " + b + "))";
    if (r.isMatrix()) {
        std::string ma = coerce(a, ta, r), mb = coerce(b, tb, r);
        if (op == "+") return "rsl_madd(" + ma + ", " + mb + ", 1.0f)";
        if (op == "-") return "rsl_madd(" + ma + ", " + mb + ", -1.0f)";
        if (op == "*") {
            if (ta.isFloat()) return "rsl_mscale(" + b + ", " + a + ")";
            if (tb.isFloat()) return "rsl_mscale(" + a + ", " + b + ")";
            return "rsl_mmul(" + a + ", " + b + ")";
        }
        if (op == "/") {
            if (tb.isFloat()) return "rsl_mscale(" + a + ", 1.0f / " + b + ")";
            if (ta.isFloat()) return "rsl_mscale(rsl_minverse(" + b + "), " + a + ")";
            return "rsl_mdiv(" + a + ", " + b + ")";
        }
    }
    if (r.isTriple()) {
        if (op == "+" || op == "-")
            return "(" + coerce(a, ta, r) + " " + op + " " + coerce(b, tb, r) + ")";
        if (op == "*") return "(" + a + " * " + b + ")";
        if (op == "/") {
            const std::string k = r.isColor() ? "c" : "v";
            if (tb.isFloat()) return "rsl_div_" + k + "f(" + a + ", " + b + ")";
            return "rsl_div_" + k + k + "(" + coerce(a, ta, r) + ", " + b + ")";
        }
    }
    if (r.isFloat()) return "(" + a + " " + op + " " + b + ")";
    error(loc, "operator '" + op + "' on '" + ta.str() + "' and '" + tb.str() +
                   "' is not supported by the code generator");
    return "0";
}

std::string Emitter::userCall(const Expr& e) {
    const FunctionDecl* f = e.function;
    if (m_fnUsesSpaces.count(f)) m_usesSpaces = true;
    auto it = m_fnNames.find(f);
    std::string s = (it == m_fnNames.end() ? "rsl_missing_" + e.text : it->second) + "(g, ev, sp";
    for (size_t i = 0; i < e.args.size() && i < f->params.size(); ++i) {
        const VarDecl& p = f->params[i];
        if (p.output && !p.type.isArray()) s += ", &" + lvalue(*e.args[i]);
        else s += ", " + exprAs(*e.args[i], p.type);
    }
    if (auto c = m_captures.find(f); c != m_captures.end())
        for (const Symbol* v : c->second) s += ", " + addressOf(v);
    return s + coefCallArg(e) + ")";
}

std::string Emitter::expr(const Expr& e) {
    if (!m_exprTemps.empty())  // computed once before the statement (emit_coefs.cpp)
        if (auto it = m_exprTemps.find(&e); it != m_exprTemps.end()) return it->second;
    switch (e.kind) {
    case ExprKind::Number: return clNumber(e.number);
    case ExprKind::String: return stringLiteral(e.text);
    case ExprKind::Ident: return varName(e.symbol);
    case ExprKind::Unary: {
        std::string a = expr(*e.args[0]);
        if (e.text == "!") return "((float)!(" + a + "))";
        if (e.type.isMatrix()) return "rsl_mscale(" + a + ", -1.0f)";
        return "(-" + a + ")";
    }
    case ExprKind::Binary:
        return binop(e.text, expr(*e.args[0]), e.args[0]->type, expr(*e.args[1]),
                     e.args[1]->type, e.loc);
    case ExprKind::Ternary:
        return "((" + expr(*e.args[0]) + ") != 0.0f ? " + exprAs(*e.args[1], e.type) + " : " +
               exprAs(*e.args[2], e.type) + ")";
    case ExprKind::Assign: {
        const Expr& l = *e.args[0];
        const Expr& r = *e.args[1];
        if (l.type.isArray()) {
            error(e.loc,
                  "a whole array is assigned only as a statement of its own (b = a;)");
            return "0";
        }
        // Oi below Os: a surface the ray sees through, where Os alone says it is opaque
        if (l.kind == ExprKind::Ident && l.symbol && l.symbol->kind == SymbolKind::Global &&
            l.text == "Oi" &&
            !(e.text == "=" && ((r.kind == ExprKind::Ident && r.text == "Os") ||
                                (r.kind == ExprKind::Number && r.number >= 1.0))))
            m_out.writesOpacity = true;
        std::string lv = lvalue(l);
        if (e.text == "=") return "(" + lv + " = " + exprAs(r, l.type) + ")";
        std::string op = e.text.substr(0, 1);
        TypeSpec rt = binaryResult(op, l.type, r.type);
        return "(" + lv + " = " + coerce(binop(op, lv, l.type, expr(r), r.type, e.loc), rt, l.type) +
               ")";
    }
    case ExprKind::Call:
        if (e.function) return userCall(e);
        if (e.builtin) return builtin(e);
        error(e.loc, "unresolved call to '" + e.text + "'");
        return "0";
    case ExprKind::Cast: {
        const TypeSpec& to = e.castType;
        std::string a = exprAs(*e.args[0], to);
        if (e.text.empty()) return a;
        if (to.isColor()) {
            int c = colorIdOf(e.text);
            if (c < 0) {
                error(e.loc, "unknown colour space \"" + e.text + "\"");
                return a;
            }
            if (c == 0) return a;
            // the triple's own components are in that space: not an RGB colour yet
            const Expr& in = *e.args[0];
            if (in.kind == ExprKind::Tuple && !in.type.isArray())
                a = "rsl_c3(" + tupleOf(in) + ")";
            return ctransformFn() + std::to_string(c) + ", RSL_COLOR_RGB, " + a + ")";
        }
        if (spaceIdOf(e.text) == 0) return a;  // "current"
        std::string spc = spaceOfName(e.text);
        m_usesSpaces = true;
        if (to.isMatrix()) return "rsl_mmul(" + a + ", rsl_space_to_space(sp, " + spc + ", RSL_SPACE_CURRENT))";
        const char* fn = to.base == BaseType::Point    ? "rsl_transform_p"
                         : to.base == BaseType::Normal ? "rsl_transform_n"
                                                       : "rsl_transform_v";
        return std::string(fn) + "(sp, " + spc + ", RSL_SPACE_CURRENT, " + a + ")";
    }
    case ExprKind::Tuple: {
        if (e.type.isArray()) {
            error(e.loc, "array values are only supported as initialisers");
            return "0";
        }
        // a colour written as three numbers is RGB
        return e.type.isColor() ? rgbIn(tupleOf(e)) : tupleOf(e);
    }
    case ExprKind::Index:
        return expr(*e.args[0]) + "[(int)(" + expr(*e.args[1]) + ")]";
    }
    return "0";
}

std::string Emitter::tupleOf(const Expr& e) {
    std::string s = e.args.size() == 16 ? "rsl_matrix16(" : "rsl_v3(";
    for (size_t i = 0; i < e.args.size(); ++i)
        s += (i ? ", " : "") + exprAs(*e.args[i], BaseType::Float);
    return s + ")";
}

}  // namespace rsl
