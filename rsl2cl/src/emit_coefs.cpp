// emit_coefs.cpp: light coefficients (rsl_abi.h, LIGHT COEFFICIENTS). Ci is affine in
// every light's Cl (affine.cpp), so its part from light l is the derivative of Ci by that
// light's Cl, which one evaluation can carry alongside the values: every variable that
// depends on the lights gets an array v_x_light[RSL_LIGHT_COEFS] holding its part per
// light, and every assignment to it updates that array with the linear part of its
// right-hand side (lin()). The renderer then needs the base evaluation only, where it
// ran the whole shader once more per light; the work that does not depend on a light
// (normalisation, face-forwarding, reflection directions, textures...) is done once.
// A user function whose result depends on the lights (an illumination model written as
// a function, as in Advanced RenderMan's material.h) takes one more argument under
// RSL_LIGHT_COEFS, the array its result's parts per light go to, filled at each return.
// Supported where every light-dependent value lives in a local variable, Ci or such a
// result and is combined by + - * / (by independent values), ?:, mix(), casts and
// triples; anything else (arrays, parameters, output parameters, colour-space casts)
// and the shader is compiled without, evaluated per light as before.
#include "emit_internal.h"

namespace rsl {

bool lightDependent(const Expr& e, const LightTaint& t) {
    switch (e.kind) {
    case ExprKind::Ident:
        if (!e.symbol) return false;
        if (e.symbol->kind == SymbolKind::Global && e.symbol->name == "Cl") return true;
        return t.symbols.count(e.symbol) > 0;
    case ExprKind::Call:
        if (e.function) return t.functions.count(e.function) > 0;  // its arguments never
        if (e.text == "diffuse" || e.text == "specular" || e.text == "phong") return true;
        break;
    default: break;
    }
    for (const ExprPtr& a : e.args)
        if (lightDependent(*a, t)) return true;
    return false;
}

namespace {

bool linearType(const TypeSpec& t) { return !t.isArray() && (t.isFloat() || t.isTriple()); }

// lin() evaluates a light-dependent expression's independent operands (multiplicands,
// divisors, conditions, mix weights, the lighting builtins' arguments) again for each
// light. That is right only where evaluating them again changes nothing: not for a
// user function, random() (a new site each time it is emitted), derivatives and texture
// lookups (each call a site of the point's derivative sequence). Such an operand is
// computed once into a temporary that the value and the parts both read (hoistOperands),
// unless it sits in a ?: branch (it would then run when the branch does not). An
// assignment, or a builtin with output arguments, there is not carried at all.
bool writes(const Expr& e) {
    if (e.kind == ExprKind::Assign) return true;
    if (e.kind == ExprKind::Call && e.function)
        for (const VarDecl& p : e.function->params)
            if (p.output) return true;
    if (e.kind == ExprKind::Call && e.builtin)
        for (const BuiltinSig& sig : e.builtin->sigs)
            for (const BuiltinArg& a : sig.args)
                if (a.output) return true;
    for (const ExprPtr& a : e.args)
        if (writes(*a)) return true;
    return e.channel && writes(*e.channel);
}
bool pure(const Expr& e) {
    if (e.kind == ExprKind::Call) {
        if (e.function || !e.builtin || e.text == "random") return false;
        const unsigned impure =
            BF_DERIV | BF_TRACE | BF_TEXTURE | BF_ENVIRONMENT | BF_SHADOW | BF_MESSAGE;
        if (e.builtin->flags & impure) return false;
    }
    if (writes(e)) return false;
    for (const ExprPtr& a : e.args)
        if (!pure(*a)) return false;
    return !e.channel || pure(*e.channel);
}

bool declaresExtern(const Stmt& s) {
    for (const VarDecl& d : s.decls)
        if (d.isExtern) return true;
    for (const StmtPtr& c : s.stmts)
        if (declaresExtern(*c)) return true;
    return (s.init && declaresExtern(*s.init)) || (s.body && declaresExtern(*s.body)) ||
           (s.elseBody && declaresExtern(*s.elseBody));
}

// Whether the shader body keeps to what lin() and the statement rules handle.
class CoefCheck {
public:
    explicit CoefCheck(const LightTaint& t) : m_t(t) {}

    bool run(const ShaderDecl& sh) {
        for (const Symbol* s : m_t.symbols) {
            bool local = s->kind == SymbolKind::Local && linearType(s->type);
            bool ci = s->kind == SymbolKind::Global && s->name == "Ci";
            if (local || ci) continue;
            fail(s->loc, "'" + s->name + "' depends on the lights and is " +
                             (s->kind == SymbolKind::Param ? (s->output ? "an output parameter" : "a parameter")
                              : s->type.isArray()           ? "an array"
                                                            : "a " + s->type.str()));
            return false;
        }
        for (const FunctionDecl* f : m_t.functions)
            if (!linearType(f->returnType)) {
                fail(f->loc, "function '" + f->name + "' returns a light-dependent " + f->returnType.str());
                return false;
            }
        stmt(*sh.body);
        // the user functions called, each once (their bodies do not depend on the caller)
        while (!m_pending.empty()) {
            const FunctionDecl* f = m_pending.back();
            m_pending.pop_back();
            m_fn = f;
            stmt(*f->body);
        }
        return m_ok;
    }

private:
    bool dep(const Expr& e) const { return lightDependent(e, m_t); }
    void calls(const Expr& e) {
        if (e.kind == ExprKind::Call && e.function && m_seen.insert(e.function).second) {
            m_pending.push_back(e.function);
            if (declaresExtern(*e.function->body))  // (its writes are not carried)
                fail(e.loc, "function '" + e.text + "' uses a variable of an enclosing scope");
        }
        for (const ExprPtr& a : e.args) calls(*a);
        if (e.channel) calls(*e.channel);
    }
    bool taintedTarget(const Expr& l) const {
        return l.kind == ExprKind::Ident && l.symbol && m_t.symbols.count(l.symbol);
    }
    // No assignment inside e changes a light-dependent variable: only whole statements
    // may (stmt), so that its part per light is updated with it.
    void noTaintedAssign(const Expr& e) {
        calls(e);
        if (e.kind == ExprKind::Assign) {
            const Expr* t = e.args[0].get();
            while (t->kind == ExprKind::Index) t = t->args[0].get();
            if (t->kind == ExprKind::Ident && t->symbol && m_t.symbols.count(t->symbol))
                fail(e.loc, "'" + t->symbol->name + "' is assigned inside an expression");
        }
        for (const ExprPtr& a : e.args) noTaintedAssign(*a);
        if (e.channel) noTaintedAssign(*e.channel);
    }
    void independent(const Expr& e) {
        if (dep(e)) fail(e.loc, "a light-dependent value where only independent ones are carried");
        noTaintedAssign(e);
    }
    // An independent operand lin() reads for each light (pure(), hoistOperands()).
    void reevaluated(const Expr& e) {
        independent(e);
        if (writes(e))
            fail(e.loc, "'" + exprToString(e) + "' assigns in a light-dependent expression");
        else if (!pure(e) && m_branch > 0)
            fail(e.loc, "'" + exprToString(e) + "' in a ?: branch would run in every case");
    }
    void linear(const Expr& e) {
        calls(e);
        if (!dep(e)) {
            noTaintedAssign(e);
            return;
        }
        if (!linearType(e.type)) fail(e.loc, "a light-dependent " + e.type.str());
        switch (e.kind) {
        case ExprKind::Ident:
            if (e.symbol->kind == SymbolKind::Global && e.symbol->name == "Cl" && m_illuminance == 0)
                fail(e.loc, "Cl outside an illuminance loop");
            return;
        case ExprKind::Unary:
            if (e.text != "-") fail(e.loc, "operator " + e.text + " on a light-dependent value");
            linear(*e.args[0]);
            return;
        case ExprKind::Binary:
            if (e.text == "+" || e.text == "-") {
                linear(*e.args[0]);
                linear(*e.args[1]);
            } else if (e.text == "*") {  // one side depends on the lights (affine.cpp)
                // (both may here: a variable light-dependent elsewhere, which affine.cpp
                // follows through the code and this check does not)
                if (dep(*e.args[0]) && dep(*e.args[1]))
                    fail(e.loc, "a product of two values that depend on the lights somewhere");
                for (const ExprPtr& a : e.args)
                    if (dep(*a)) linear(*a);
                    else reevaluated(*a);
            } else if (e.text == "/") {
                linear(*e.args[0]);
                reevaluated(*e.args[1]);
            } else {
                fail(e.loc, "operator " + e.text + " on a light-dependent value");
            }
            return;
        case ExprKind::Ternary:
            reevaluated(*e.args[0]);
            ++m_branch;
            linear(*e.args[1]);
            linear(*e.args[2]);
            --m_branch;
            return;
        case ExprKind::Call:
            if (e.function) {  // a light-dependent result: its arguments are independent
                for (const ExprPtr& a : e.args) independent(*a);
            } else if (e.text == "mix" && e.args.size() == 3) {
                linear(*e.args[0]);
                linear(*e.args[1]);
                reevaluated(*e.args[2]);
            } else if (e.text == "diffuse" || e.text == "specular" || e.text == "phong") {
                for (const ExprPtr& a : e.args) reevaluated(*a);
            } else {
                fail(e.loc, e.text + "() of a light-dependent value");
            }
            return;
        case ExprKind::Cast:
            if (!e.text.empty() && e.text != "rgb")
                fail(e.loc, "a light-dependent value cast to \"" + e.text + "\"");
            linear(*e.args[0]);
            return;
        case ExprKind::Tuple:
            for (const ExprPtr& a : e.args) linear(*a);
            return;
        default: fail(e.loc, "a light-dependent array element or assignment");
        }
    }
    void stmt(const Stmt& s) {
        switch (s.kind) {
        case StmtKind::Expr:
            if (s.expr->kind == ExprKind::Assign && taintedTarget(*s.expr->args[0])) {
                const std::string& op = s.expr->text;
                if (op == "*=" || op == "/=") reevaluated(*s.expr->args[1]);
                else if (op == "=" || op == "+=" || op == "-=") linear(*s.expr->args[1]);
                else fail(s.loc, "operator " + op + " on a light-dependent variable");
            } else {
                noTaintedAssign(*s.expr);
            }
            break;
        case StmtKind::Decl:
            for (const VarDecl& d : s.decls)
                if (d.init) linear(*d.init);
            break;
        case StmtKind::Block:
            for (const StmtPtr& c : s.stmts) stmt(*c);
            break;
        case StmtKind::If:
        case StmtKind::While:
            independent(*s.expr);
            stmt(*s.body);
            if (s.elseBody) stmt(*s.elseBody);
            break;
        case StmtKind::For:
            if (s.init) stmt(*s.init);
            if (s.expr) independent(*s.expr);
            if (s.step) independent(*s.step);
            stmt(*s.body);
            break;
        case StmtKind::Return:
            if (s.expr && m_fn && m_t.functions.count(m_fn)) linear(*s.expr);
            else if (s.expr) noTaintedAssign(*s.expr);
            break;
        case StmtKind::Illuminance:
            for (const ExprPtr& a : s.args) independent(*a);
            ++m_illuminance;
            stmt(*s.body);
            --m_illuminance;
            break;
        case StmtKind::Illuminate:
        case StmtKind::Solar: fail(s.loc, "illuminate or solar in a surface"); break;
        default: break;
        }
    }

public:
    std::string m_why;  // the first reason the coefficients cannot be carried

private:
    void fail(const SourceLoc& loc, const std::string& why) {
        if (m_ok) m_why = loc.str() + ": " + why;
        m_ok = false;
    }

    const LightTaint& m_t;
    const FunctionDecl* m_fn = nullptr;  // the function being checked (none: the shader)
    std::set<const FunctionDecl*> m_seen;
    std::vector<const FunctionDecl*> m_pending;
    int m_illuminance = 0;
    int m_branch = 0;  // inside ?: branches of a light-dependent expression
    bool m_ok = true;
};

// Whether e's dependence on the lights comes from Cl alone (no variable, no call).
bool onlyCl(const Expr& e, const LightTaint& t) {
    if (e.kind == ExprKind::Ident) return !(e.symbol && t.symbols.count(e.symbol));
    if (e.kind == ExprKind::Call && (e.function ? t.functions.count(e.function) > 0
                                                : e.text == "diffuse" || e.text == "specular" ||
                                                      e.text == "phong"))
        return false;
    for (const ExprPtr& a : e.args)
        if (!onlyCl(*a, t)) return false;
    return true;
}

}  // namespace

bool coefsSupported(const ShaderDecl& sh, const LightTaint& t, std::string* why) {
    if (sh.kind != ShaderKind::Surface) return false;
    CoefCheck check(t);
    bool ok = check.run(sh);
    if (why) *why = check.m_why;
    return ok;
}

bool lightCoefsSupported(const ShaderDecl& shader, std::string* why) {
    Diagnostics quiet;
    LightTaint taint;
    if (!checkAffine(shader, Program(), quiet, &taint) || taint.nonAffine) {
        if (why) *why = "Ci is not affine in the lights";
        return false;
    }
    return coefsSupported(shader, taint, why);
}

std::string Emitter::coefName(const Symbol* s) {
    if (s->kind == SymbolKind::Global) return "ev->Ci_light";
    return varName(s) + "_light";
}

std::string Emitter::linAs(const Expr& e, const TypeSpec& to, const std::string& k) {
    std::string l = lin(e, k);
    return l.empty() ? clZero(to) : coerce(l, e.type, to);
}

// The part of e's value that comes from light k (empty: none), given that the value is
// linear in the lights (CoefCheck).
std::string Emitter::lin(const Expr& e, const std::string& k) {
    if (!lightDependent(e, *m_coefs)) return "";
    switch (e.kind) {
    case ExprKind::Ident:
        if (e.symbol->kind == SymbolKind::Global && e.symbol->name == "Cl") {
            if (k == m_lightVars.back()) return m_lightRaw.back();
            return "(" + k + " == " + m_lightVars.back() + " ? " + m_lightRaw.back() +
                   " : rsl_f2c(0.0f))";
        }
        return coefName(e.symbol) + "[" + k + "]";
    case ExprKind::Unary: return "(-" + lin(*e.args[0], k) + ")";
    case ExprKind::Binary: {
        const Expr &a = *e.args[0], &b = *e.args[1];
        std::string la = lin(a, k), lb = lin(b, k);
        if (e.text == "+" || e.text == "-") {
            if (la.empty()) {
                std::string r = coerce(lb, b.type, e.type);
                return e.text == "+" ? r : "(-" + r + ")";
            }
            if (lb.empty()) return coerce(la, a.type, e.type);
            return binop(e.text, la, a.type, lb, b.type, e.loc);
        }
        if (la.empty()) return binop(e.text, expr(a), a.type, lb, b.type, e.loc);
        return binop(e.text, la, a.type, expr(b), b.type, e.loc);
    }
    case ExprKind::Ternary:
        return "((" + expr(*e.args[0]) + ") != 0.0f ? " + linAs(*e.args[1], e.type, k) + " : " +
               linAs(*e.args[2], e.type, k) + ")";
    case ExprKind::Call: {
        if (e.function) return m_callCoefs.at(&e) + "[" + k + "]";  // filled by the call
        std::string v = builtin(e);
        std::string fn = v.substr(0, v.find('('));
        if (e.text == "mix")
            return fn + "(" + linAs(*e.args[0], e.type, k) + ", " + linAs(*e.args[1], e.type, k) +
                   ", " + exprAs(*e.args[2], BaseType::Float) + ")";
        // rsl_diffuse(g, ev, ...) -> rsl_diffuse_light(g, k, ...)
        const std::string head = fn + "(g, ev";
        return fn + "_light(g, " + k + v.substr(head.size());
    }
    case ExprKind::Cast: return coerce(lin(*e.args[0], k), e.args[0]->type, e.castType);
    case ExprKind::Tuple: {  // (a colour written as three numbers is RGB, as in expr())
        std::string s = "rsl_v3(";
        for (size_t i = 0; i < e.args.size(); ++i)
            s += (i ? ", " : "") + linAs(*e.args[i], BaseType::Float, k);
        return e.type.isColor() ? rgbIn(s + ")") : s + ")";
    }
    default: break;
    }
    error(e.loc, "internal: no light coefficient for '" + exprToString(e) + "'");
    return "";
}

void Emitter::coefLines(const std::vector<std::string>& lines) {
    line("#ifdef RSL_LIGHT_COEFS");
    for (const std::string& s : lines) line(s);
    line("#endif");
}

static const char* kEachLight = "if (ev->coefs) for (int _k = 0; _k < RSL_LIGHT_COEFS; ++_k) ";

void Emitter::coefZero(const std::string& array, const TypeSpec& type) {
    coefLines({kEachLight + array + "[_k] = " + clZero(type) + ";"});
}

void Emitter::coefDecl(const VarDecl& d) {
    std::string name = "v_" + d.name + "_light";
    coefLines({std::string(clType(d.type)) + " " + name + "[RSL_LIGHT_COEFS];",
               kEachLight + name + "[_k] = " +
                   (d.init ? linAs(*d.init, d.type, "_k") : clZero(d.type)) + ";"});
}

// After the statement `e` (an assignment to a light-dependent variable) has set the
// value: the same for its part of each light.
void Emitter::coefAssign(const Expr& e) {
    const Expr &l = *e.args[0], &r = *e.args[1];
    const std::string x = coefName(l.symbol), op = e.text;
    if ((op == "+=" || op == "-=") && !m_lightVars.empty() && onlyCl(r, *m_coefs)) {
        // in an illuminance loop, a term of the loop's own light: only its slot changes
        const std::string& k = m_lightVars.back();
        coefLines({"if (ev->coefs && " + k + " < RSL_LIGHT_COEFS) " + x + "[" + k + "] " + op +
                   " " + linAs(r, l.type, k) + ";"});
        return;
    }
    const std::string xk = x + "[_k]";
    std::string v;
    if (op == "=") {
        v = linAs(r, l.type, "_k");
    } else if (op == "+=" || op == "-=") {
        std::string lr = lin(r, "_k");
        if (lr.empty()) return;  // an independent term: the parts are unchanged
        v = coerce(binop(op.substr(0, 1), xk, l.type, lr, r.type, e.loc),
                   binaryResult(op.substr(0, 1), l.type, r.type), l.type);
    } else {
        v = coerce(binop(op.substr(0, 1), xk, l.type, expr(r), r.type, e.loc),
                   binaryResult(op.substr(0, 1), l.type, r.type), l.type);
    }
    coefLines({kEachLight + xk + " = " + v + ";"});
}

// A call of a user function whose result depends on the lights: the array its parts
// per light come back in, declared before the statement (rsl_abi.h RSL_COEF_ARG).
std::string Emitter::coefCallArg(const Expr& e) {
    if (!m_coefs || !e.function || !m_coefs->functions.count(e.function)) return "";
    std::string name = "_cl" + std::to_string(m_tmp++);
    m_pre.push_back("#ifdef RSL_LIGHT_COEFS");
    m_pre.push_back(std::string(clType(e.function->returnType)) + " " + name + "[RSL_LIGHT_COEFS];");
    m_pre.push_back("#endif");
    m_callCoefs[&e] = name;
    return " RSL_COEF_ARG(" + name + ")";
}

// `return e` in a function whose result depends on the lights: the value, then its
// parts per light for the caller (the value first: a call in e fills what they read).
void Emitter::coefReturn(const Expr& e, const TypeSpec& type) {
    hoistOperands(e);
    std::string v = exprAs(e, type), ret = "_ret" + std::to_string(m_tmp++);
    line(std::string(clType(type)) + " " + ret + " = " + v + ";");
    coefLines({kEachLight + std::string("_ret_light[_k] = ") + linAs(e, type, "_k") + ";"});
    line("return " + ret + ";");
    m_exprTemps.clear();
}

// Before a statement that sets a light-dependent value: each impure independent operand
// lin() would read (pure()) into a temporary, in evaluation order; expr() then gives the
// temporary, to the value and to the parts alike.
void Emitter::hoistOnce(const Expr& op) {
    if (pure(op) || m_exprTemps.count(&op)) return;
    std::string v = expr(op), name = "_h" + std::to_string(m_tmp++);
    line(std::string(clType(op.type)) + " " + name + " = " + v + ";");
    m_exprTemps[&op] = name;
}

void Emitter::hoistOperands(const Expr& e) {
    if (!lightDependent(e, *m_coefs)) return;
    switch (e.kind) {
    case ExprKind::Binary:
        if (e.text == "*")
            for (const ExprPtr& a : e.args)
                lightDependent(*a, *m_coefs) ? hoistOperands(*a) : hoistOnce(*a);
        else if (e.text == "/")
            hoistOperands(*e.args[0]), hoistOnce(*e.args[1]);
        else
            hoistOperands(*e.args[0]), hoistOperands(*e.args[1]);
        return;
    case ExprKind::Ternary:  // (CoefCheck: nothing impure in the branches)
        hoistOnce(*e.args[0]);
        return;
    case ExprKind::Call:
        if (e.function) return;  // its arguments are evaluated once, by the call
        if (e.text == "mix") {
            hoistOperands(*e.args[0]), hoistOperands(*e.args[1]), hoistOnce(*e.args[2]);
            return;
        }
        for (const ExprPtr& a : e.args) hoistOnce(*a);  // diffuse(), specular(), phong()
        return;
    default:
        for (const ExprPtr& a : e.args) hoistOperands(*a);
    }
}

void Emitter::hoistAssign(const Expr& assign) {
    const std::string& op = assign.text;
    if (op == "*=" || op == "/=") hoistOnce(*assign.args[1]);  // the independent operand
    else hoistOperands(*assign.args[1]);
}

}  // namespace rsl
