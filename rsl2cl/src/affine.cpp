// affine.cpp: the static check that Ci is affine in every trace() result and every
// light's Cl (DESIGN.md section 4), per colour channel. Values derived from trace() and
// from Cl (and diffuse/specular/phong) are tainted; the allowed operations keep a value
// affine and channel-wise: + - negation, * and / by untainted values, assignment,
// casts, ?: with an untainted condition, mix() with an untainted weight. Anything else
// touching a tainted value is an error naming file:line:col and the expression; where
// only Cl is involved, a warning (the first place): the shader is then evaluated one
// light at a time (LightTaint::nonAffine), exact for a single light.
// Taint follows the flow of the code: an assignment of an untainted value cleans the
// variable for what follows (a classic shader's `Ci = texture(...); Ci = Ci *
// diffuse(Nf)`), branches join, and loops (light loops too) and user functions only add
// taint, iterated to a fixed point. What a variable ever holds (flow-insensitive) is what
// Oi's check and the light coefficients (emit_coefs.cpp) see.
#include <algorithm>
#include <map>
#include <set>

#include "builtins.h"
#include "emit_cl.h"

namespace rsl {
namespace {

enum : unsigned { T_TRACE = 1, T_LIGHT = 2 };

std::string unknowns(unsigned m) {
    if (m == T_TRACE) return "trace()";
    if (m == T_LIGHT) return "Cl";
    return "trace() and Cl";
}
std::string describe(unsigned m) {
    if (m == T_TRACE) return "a trace() result";
    if (m == T_LIGHT) return "a light's Cl";
    return "a value depending on trace() and Cl";
}

class Affine {
public:
    Affine(const ShaderDecl& sh, Diagnostics& diag) : m_sh(sh), m_diag(diag) {}

    bool run() {
        for (int pass = 0; pass < 32; ++pass) {
            m_changed = false;
            walk();
            if (!m_changed) break;
        }
        m_report = true;
        walk();
        for (const auto& kv : m_ever) {
            if (kv.first->kind == SymbolKind::Global && kv.first->name == "Oi" && kv.second) {
                report(m_oiLoc, "Oi must not depend on " + unknowns(kv.second) +
                                    " (opacity is needed before any ray is cast)");
            }
        }
        // in source order (the walk visits call arguments before the call)
        std::stable_sort(m_errors.begin(), m_errors.end(), [](const auto& a, const auto& b) {
            if (a.first.file != b.first.file) return a.first.file < b.first.file;
            if (a.first.line != b.first.line) return a.first.line < b.first.line;
            return a.first.col < b.first.col;
        });
        for (const auto& e : m_errors) m_diag.error(e.first, e.second);
        if (m_nonAffine && !m_failed)
            m_diag.warning(
                m_nonAffineAt.first,
                m_nonAffineAt.second +
                    "; each light is shaded on its own and its shadow scales its "
                    "part (exact for one light or lights whose parts add)");
        return !m_failed;
    }

    // The symbols that depend on some light's Cl, and the user functions whose result
    // does (after run()).
    void lightTaint(LightTaint* out) const {
        out->symbols.clear();
        out->functions.clear();
        out->nonAffine = m_nonAffine;
        for (const auto& kv : m_ever)
            if (kv.second & T_LIGHT) out->symbols.insert(kv.first);
        for (const auto& kv : m_fnRet)
            if (kv.second & T_LIGHT) out->functions.insert(kv.first);
    }

private:
    void walk() {
        m_visited.clear();
        m_fn = nullptr;
        m_state.clear();
        stmt(*m_sh.body);
    }

    // A loop's body (and step) run again with what they left, until nothing more is
    // tainted; inside, assignments only add taint.
    template <class Body>
    void loop(Body body) {
        ++m_weak;
        for (int pass = 0; pass < 64; ++pass) {
            const std::map<const Symbol*, unsigned> before = m_state;
            body();
            if (m_state == before) break;
        }
        --m_weak;
    }

    void report(const SourceLoc& loc, const std::string& msg) {
        if (!m_report) return;
        m_failed = true;
        if (m_reported.insert(loc.str() + msg).second) m_errors.push_back({loc, msg});
    }
    void fail(const Expr& e, unsigned m, const std::string& what) {
        const std::string msg = "Ci is not affine in " + unknowns(m) + ": " + what +
                                " in '" + exprToString(e) + "'";
        if (m != T_LIGHT) return report(e.loc, msg);
        // Cl alone: each light is shaded on its own instead (the first place is said)
        if (m_report && !m_nonAffine) {
            m_nonAffine = true;
            m_nonAffineAt = {e.loc, msg};
        }
    }

    // s takes a value of taint m: all of it (`whole`, outside loops and functions: what it
    // held before is gone), or beside what it held (an array element, a loop).
    void taintSym(const Symbol* s, unsigned m, const SourceLoc& loc, bool whole) {
        if (!s) return;
        if (whole && m_weak == 0) {
            if (m) m_state[s] = m;
            else m_state.erase(s);
        } else if (m) {
            m_state[s] |= m;
        }
        if (!m) return;
        unsigned& t = m_ever[s];
        if ((t | m) != t) {
            t |= m;
            m_changed = true;
        }
        if (s->kind == SymbolKind::Global && s->name == "Oi" && m_oiLoc.line == 0) m_oiLoc = loc;
    }

    static const Symbol* target(const Expr& e) {
        const Expr* t = &e;
        while (t->kind == ExprKind::Index) t = t->args[0].get();
        return t->kind == ExprKind::Ident ? t->symbol : nullptr;
    }

    unsigned binary(const Expr& e, const std::string& op, unsigned a, unsigned b) {
        if (op == "+" || op == "-") return a | b;
        if (op == "*") {
            if (a && b) {
                fail(e, a | b, a == b ? (a == T_TRACE ? "product of two trace() results"
                                         : a == T_LIGHT ? "product of two Cl values"
                                                        : "product of two tainted values")
                                      : "product of " + describe(a) + " and " + describe(b));
            }
            return a | b;
        }
        if (op == "/") {
            if (b) fail(e, b, "division by " + describe(b));
            return a | b;
        }
        if (a | b) {
            if (op == "." || op == "^") fail(e, a | b, describe(a | b) + " used in a dot or cross product");
            else fail(e, a | b, describe(a | b) + " used in a comparison");
        }
        return 0;
    }

    // gather() (gather.cpp): the branch on whether a pass's ray escaped
    static bool isGatherBranch(const Expr& e) {
        return e.kind == ExprKind::Binary && e.text == "==" &&
               e.args[0]->kind == ExprKind::Call && e.args[0]->text == "__gather_visible";
    }
    // A value the gather loop's code computes: its builtins, its variables, and sums and
    // products of them ("primitive:P" is its origin plus its direction times a length).
    static bool gatherOwn(const Expr& r) {
        if (r.kind == ExprKind::Call) return r.text.rfind("__gather_", 0) == 0;
        if (r.kind == ExprKind::Ident) return r.text.rfind("__g", 0) == 0;
        return r.kind == ExprKind::Binary && (r.text == "+" || r.text == "*") &&
               gatherOwn(*r.args[0]) && gatherOwn(*r.args[1]);
    }
    // An assignment in a gather() branch: what it assigns depends on which rays escape,
    // which Ci is affine in only through sums: a variable declared outside the loop may
    // change by += and -= alone (the loop's own outputs are set by its code).
    unsigned gatherAssign(const Expr& e) {
        const Symbol* t = target(*e.args[0]);
        const Expr& r = *e.args[1];
        if (t && t->name.rfind("__g", 0) == 0) return 0;  // (an inner gather's own)
        const bool own = gatherOwn(r);
        if (t && !m_gatherLocals.count(t) && !own && e.text != "+=" && e.text != "-=")
            fail(e, T_TRACE,
                 "'" + t->name + "' (declared outside the gather loop) changed by '" +
                     e.text + "' in it; only += and -= keep it a sum over the rays");
        // (a pass's direction and origin are known before any ray is traced)
        return r.kind == ExprKind::Ident && r.text.rfind("__g", 0) == 0 ? 0u : T_TRACE;
    }

    void condition(const Expr& e, const char* what) {
        unsigned m = expr(e);
        if (m) fail(e, m, describe(m) + " used in the condition of " + what);
    }

    unsigned call(const Expr& e) {
        std::vector<unsigned> a;
        for (const ExprPtr& x : e.args) a.push_back(expr(*x));
        if (e.function) {
            bool tainted = false;
            for (unsigned m : a) tainted |= m != 0;
            if (!tainted) return function(*e.function);
            // a tainted argument: the body is walked again with its parameters as passed
            // (Ci stays affine when the function is affine in them, as an illumination
            // model taking Cl is), and an output parameter hands its taint back
            const FunctionDecl& f = *e.function;
            const FunctionDecl* saved = m_fn;
            m_fn = &f;
            ++m_weak;
            for (size_t i = 0; i < a.size() && i < f.params.size(); ++i)
                taintSym(f.params[i].symbol, a[i], e.loc, false);
            stmt(*f.body);
            for (size_t i = 0; i < e.args.size() && i < f.params.size(); ++i)
                if (f.params[i].output)
                    if (auto it = m_state.find(f.params[i].symbol); it != m_state.end())
                        taintSym(target(*e.args[i]), it->second, e.loc, false);
            --m_weak;
            m_fn = saved;
            return m_fnRet[&f];
        }
        const std::string& n = e.text;
        // a point's or vector's component is linear in it; such a triple depends on the
        // rays only through a scalar (gather()'s "primitive:P": origin + direction x
        // length), the same in every colour channel. (comp() of a colour is not: a
        // traced colour's coefficients are per channel.)
        if ((n == "xcomp" || n == "ycomp" || n == "zcomp") && a.size() == 1 &&
            !(a[0] & T_LIGHT))
            return a[0];
        if (n == "mix" && a.size() == 3) {
            if (a[2]) fail(e, a[2], describe(a[2]) + " used as the weight of mix()");
            return a[0] | a[1];
        }
        for (size_t i = 0; i < a.size(); ++i)
            if (a[i]) fail(e, a[i], describe(a[i]) + " passed to " + n + "()");
        if (n == "trace" || n == "__gather_trace" || n == "__gather_length")
            return T_TRACE;
        if (n == "diffuse" || n == "specular" || n == "phong")
            return m_sh.kind == ShaderKind::Surface ? T_LIGHT : 0u;
        return 0;
    }

    unsigned function(const FunctionDecl& f) {
        if (!m_visited.count(&f)) {
            m_visited.insert(&f);
            const FunctionDecl* saved = m_fn;
            m_fn = &f;
            ++m_weak;  // (walked once, for every call: what it assigns only adds)
            stmt(*f.body);
            --m_weak;
            m_fn = saved;
        }
        return m_fnRet[&f];
    }

    unsigned expr(const Expr& e) {
        switch (e.kind) {
        case ExprKind::Number:
        case ExprKind::String: return 0;
        case ExprKind::Ident: {
            if (!e.symbol) return 0;
            // (a volume shader sees every light's Cl as it is: nothing is deferred)
            if (e.symbol->kind == SymbolKind::Global && e.symbol->name == "Cl")
                return m_sh.kind == ShaderKind::Surface ? T_LIGHT : 0u;
            auto it = m_state.find(e.symbol);
            return it == m_state.end() ? 0 : it->second;
        }
        case ExprKind::Unary: {
            unsigned a = expr(*e.args[0]);
            if (a && e.text == "!") fail(e, a, describe(a) + " used in a comparison");
            return e.text == "!" ? 0 : a;
        }
        case ExprKind::Binary:
            return binary(e, e.text, expr(*e.args[0]), expr(*e.args[1]));
        case ExprKind::Ternary: {
            condition(*e.args[0], "?:");
            return expr(*e.args[1]) | expr(*e.args[2]);
        }
        case ExprKind::Assign: {
            unsigned l = expr(*e.args[0]);
            unsigned r = expr(*e.args[1]);
            unsigned v = e.text == "=" ? r : binary(e, e.text.substr(0, 1), l, r);
            if (m_gather > 0) v |= gatherAssign(e);
            taintSym(target(*e.args[0]), v, e.loc, e.args[0]->kind == ExprKind::Ident);
            return v;
        }
        case ExprKind::Call: return call(e);
        case ExprKind::Cast: {
            // (a colour's channels made a point's coordinates would be mixed by xcomp())
            const unsigned a = expr(*e.args[0]);
            if (a && e.args[0]->type.isColor() && e.type.isTriple() && !e.type.isColor())
                fail(e, a, describe(a) + " made a point, vector or normal");
            return a;
        }
        case ExprKind::Tuple: {
            unsigned m = 0;
            for (const ExprPtr& a : e.args) m |= expr(*a);
            return m;
        }
        case ExprKind::Index: {
            unsigned ix = expr(*e.args[1]);
            if (ix) fail(e, ix, describe(ix) + " used as an array index");
            return expr(*e.args[0]);
        }
        }
        return 0;
    }

    void stmt(const Stmt& s) {
        switch (s.kind) {
        case StmtKind::Expr: expr(*s.expr); break;
        case StmtKind::Decl:
            for (const VarDecl& d : s.decls) {
                if (m_gather > 0) m_gatherLocals.insert(d.symbol);
                if (d.init) taintSym(d.symbol, expr(*d.init), d.loc, true);
            }
            break;
        case StmtKind::Block:
            for (const StmtPtr& c : s.stmts) stmt(*c);
            break;
        case StmtKind::If:
            if (isGatherBranch(*s.expr)) {  // gather(): which of its rays escape
                expr(*s.expr);
                ++m_gather;
                branches(*s.body, s.elseBody.get());
                --m_gather;
                break;
            }
            condition(*s.expr, "if");
            branches(*s.body, s.elseBody.get());
            break;
        case StmtKind::While:
            loop([&] {
                condition(*s.expr, "while");
                stmt(*s.body);
            });
            break;
        case StmtKind::For:
            if (s.init) stmt(*s.init);
            loop([&] {
                if (s.expr) condition(*s.expr, "for");
                stmt(*s.body);
                if (s.step) expr(*s.step);
            });
            break;
        case StmtKind::Return:
            if (s.expr) {
                unsigned m = expr(*s.expr);
                if (m_fn && m) {
                    unsigned& r = m_fnRet[m_fn];
                    if ((r | m) != r) {
                        r |= m;
                        m_changed = true;
                    }
                }
            }
            break;
        case StmtKind::Illuminance:
        case StmtKind::Illuminate:
        case StmtKind::Solar:
            for (const ExprPtr& a : s.args) {
                unsigned m = expr(*a);
                if (m) fail(*a, m, describe(m) + " used as an argument of a light loop");
            }
            loop([&] { stmt(*s.body); });  // (once per light)
            break;
        default: break;
        }
    }

    // if / else: each branch from the state before it, then what either may leave
    void branches(const Stmt& then, const Stmt* otherwise) {
        const std::map<const Symbol*, unsigned> before = m_state;
        stmt(then);
        std::map<const Symbol*, unsigned> joined = m_state;
        m_state = before;
        if (otherwise) stmt(*otherwise);
        for (const auto& kv : m_state) joined[kv.first] |= kv.second;
        m_state = std::move(joined);
    }

    const ShaderDecl& m_sh;
    Diagnostics& m_diag;
    std::map<const Symbol*, unsigned> m_state;  // what each variable holds here
    std::map<const Symbol*, unsigned> m_ever;   // ... and anywhere
    int m_weak = 0;                             // loops and functions around
    std::map<const FunctionDecl*, unsigned> m_fnRet;
    std::set<const FunctionDecl*> m_visited;
    std::set<std::string> m_reported;
    std::vector<std::pair<SourceLoc, std::string>> m_errors;
    const FunctionDecl* m_fn = nullptr;
    int m_gather = 0;                        // gather() branches around
    std::set<const Symbol*> m_gatherLocals;  // variables declared inside them
    SourceLoc m_oiLoc;
    bool m_changed = false, m_report = false, m_failed = false, m_nonAffine = false;
    std::pair<SourceLoc, std::string> m_nonAffineAt;  // where Cl is first used so
};

}  // namespace

bool checkAffine(const ShaderDecl& shader, const Program&, Diagnostics& diag, LightTaint* taint) {
    Affine a(shader, diag);
    bool ok = a.run();
    if (taint) a.lightTaint(taint);
    return ok;
}

}  // namespace rsl
