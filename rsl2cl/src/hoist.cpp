// hoist.cpp: which uniform declarations a shader computes once per instance (hoist.h).
#include "hoist.h"

#include <set>

#include "builtins.h"

namespace rsl {
namespace {

// Builtins that read the shading point, the renderer or write their arguments.
constexpr unsigned kImpure = BF_VARYING | BF_DERIV | BF_TRACE | BF_TEXTURE | BF_ENVIRONMENT |
                             BF_SHADOW | BF_LIGHTING | BF_MESSAGE;

int slotsFor(const TypeSpec& t, int colorSlots) {
    switch (t.base) {
    case BaseType::Float: return 1;
    case BaseType::Point:
    case BaseType::Vector:
    case BaseType::Normal: return 3;
    case BaseType::Color: return colorSlots;
    case BaseType::Matrix: return 16;
    default: return 0;  // strings and the rest stay where they are
    }
}

class Planner {
public:
    Planner(const ShaderDecl& sh, const std::vector<bool>& computed, int colorSlots)
        : m_sh(sh), m_colorSlots(colorSlots) {
        written(*sh.body);
        // a parameter the body assigns is not the instance's value once it has
        for (size_t i = 0; i < sh.params.size(); ++i)
            if (sh.params[i].symbol && !sh.params[i].symbol->varying &&
                !(i < computed.size() && computed[i]) && !m_written.count(sh.params[i].symbol))
                m_uniformParams.insert(sh.params[i].symbol);
    }

    HoistPlan run() {
        HoistPlan plan;
        for (const StmtPtr& s : m_sh.body->stmts) {
            if (s->kind != StmtKind::Decl) continue;
            for (const VarDecl& d : s->decls) {
                int n = slotsFor(d.type, m_colorSlots);
                if (!d.init || d.isExtern || d.type.isArray() || n == 0 || !d.symbol ||
                    d.symbol->varying || m_written.count(d.symbol) || !pure(*d.init) ||
                    !worthIt(*d.init))
                    continue;
                plan.slot[&d] = plan.floats;
                plan.floats += n;
                plan.decls.push_back(&d);
                m_hoisted.insert(d.symbol);
            }
        }
        cones(*m_sh.body, plan);
        return plan;
    }

private:
    // (a literal angle's cosine rsl2cl folds; a cone inside a loop or a condition is
    // still the instance's: the angle is)
    void cones(const Stmt& s, HoistPlan& plan) {
        if (const Expr* a = coneAngle(s); a && pure(*a) && a->kind != ExprKind::Number) {
            plan.coneSlot[&s] = plan.floats++;
            plan.cones.push_back(&s);
        }
        for (const StmtPtr& c : s.stmts) cones(*c, plan);
        if (s.body) cones(*s.body, plan);
        if (s.elseBody) cones(*s.elseBody, plan);
    }

    // Variables assigned anywhere, or passed where a call may write them.
    void written(const Stmt& s) {
        if (s.expr) written(*s.expr);
        for (const VarDecl& d : s.decls)
            if (d.init) written(*d.init);
        for (const StmtPtr& c : s.stmts) written(*c);
        if (s.init) written(*s.init);
        if (s.step) written(*s.step);
        for (const ExprPtr& a : s.args) written(*a);
        if (s.body) written(*s.body);
        if (s.elseBody) written(*s.elseBody);
    }
    void written(const Expr& e) {
        auto target = [&](const Expr& lv) {
            const Expr* t = &lv;
            while (t->kind == ExprKind::Index && !t->args.empty()) t = t->args[0].get();
            if (t->kind == ExprKind::Ident && t->symbol) m_written.insert(t->symbol);
        };
        if (e.kind == ExprKind::Assign && !e.args.empty()) target(*e.args[0]);
        if (e.kind == ExprKind::Call && e.function) {  // a user function's output params
            for (size_t i = 0; i < e.args.size(); ++i)
                if (i >= e.function->params.size() || e.function->params[i].output)
                    target(*e.args[i]);
            // ... and what its body assigns: variables of the caller's it declares extern
            if (m_walked.insert(e.function).second) written(*e.function->body);
        } else if (e.kind == ExprKind::Call &&
                   (!e.sig || e.sig->code.find('&') != std::string::npos ||
                    (e.builtin && (e.builtin->flags & BF_MESSAGE)))) {
            for (const ExprPtr& a : e.args) target(*a);  // builtins that write arguments
        }
        for (const ExprPtr& a : e.args) written(*a);
        if (e.channel) written(*e.channel);
    }

    bool pure(const Expr& e) const {
        switch (e.kind) {
        case ExprKind::Number:
        case ExprKind::String: return true;
        case ExprKind::Ident:
            return e.symbol && (m_uniformParams.count(e.symbol) || m_hoisted.count(e.symbol));
        case ExprKind::Assign: return false;
        case ExprKind::Call:
            if (!e.builtin || e.function || (e.builtin->flags & kImpure) || e.channel)
                return false;
            if (e.sig && e.sig->code.find('&') != std::string::npos) return false;
            if (e.text == "printf" || e.text == "random") return false;
            break;
        default: break;
        }
        for (const ExprPtr& a : e.args)
            if (!pure(*a)) return false;
        return true;
    }

    // A copy of a parameter or a constant is no work: the OpenCL compiler folds it.
    static bool worthIt(const Expr& e) {
        if (e.kind == ExprKind::Call || e.kind == ExprKind::Binary ||
            e.kind == ExprKind::Ternary || (e.kind == ExprKind::Cast && !e.text.empty()))
            return true;
        for (const ExprPtr& a : e.args)
            if (worthIt(*a)) return true;
        return false;
    }

    const ShaderDecl& m_sh;
    const int m_colorSlots;
    std::set<const Symbol*> m_uniformParams, m_hoisted, m_written;
    std::set<const FunctionDecl*> m_walked;  // user functions whose writes are in m_written
};

}  // namespace

const Expr* coneAngle(const Stmt& s) {
    if (s.kind == StmtKind::Illuminate) return s.args.size() == 3 ? s.args[2].get() : nullptr;
    if (s.kind != StmtKind::Illuminance) return nullptr;
    const size_t first = (!s.args.empty() && s.args[0]->type.isString()) ? 1 : 0;
    return s.args.size() - first == 3 ? s.args[first + 2].get() : nullptr;
}

HoistPlan planHoisting(const ShaderDecl& shader, const std::vector<bool>& computedDefault,
                       int colorSlots) {
    return Planner(shader, computedDefault, colorSlots).run();
}

}  // namespace rsl
