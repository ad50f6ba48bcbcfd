// varying.cpp: uniform/varying inference. A variable declared without a storage class
// becomes varying when it is assigned a varying value or assigned under varying
// control flow (an if/while/for on a varying condition, a light loop). Parameters and
// explicitly declared variables keep their class; assigning a varying value to an
// explicitly uniform one is an error. Iterates to a fixed point over the whole program.
#include "builtins.h"
#include "typecheck.h"

namespace rsl {
namespace {

class VaryingPass {
public:
    VaryingPass(Program& prog, Diagnostics& diag) : m_prog(prog), m_diag(diag) {}

    void run() {
        for (int iter = 0; iter < 100; ++iter) {
            m_changed = false;
            sweep(false);
            if (!m_changed) break;
        }
        for (const auto& [at, name] : m_promoted)
            m_diag.warning(at, "uniform variable '" + name +
                                   "' is assigned a varying value (or under a varying "
                                   "condition): it is made varying");
        sweep(true);
    }

private:
    void sweep(bool report) {
        m_report = report;
        for (auto& f : m_prog.functions) function(*f);
        for (auto& sh : m_prog.shaders) {
            m_ctx.assign(1, false);
            m_fn = nullptr;
            for (VarDecl& p : sh->params)
                if (p.init) expr(*p.init);
            stmt(*sh->body);
        }
    }

    void function(FunctionDecl& f) {
        std::vector<bool> savedCtx = m_ctx;
        FunctionDecl* savedFn = m_fn;
        m_ctx.assign(1, false);
        m_fn = &f;
        stmt(*f.body);
        m_ctx = savedCtx;
        m_fn = savedFn;
    }

    bool ctxVarying() const { return !m_ctx.empty() && m_ctx.back(); }
    void pushCtx(bool v) { m_ctx.push_back(ctxVarying() || v); }
    void popCtx() { m_ctx.pop_back(); }

    // A write of a value of the given class to the variable behind lvalue e.
    void write(Expr& e, bool varying, const SourceLoc& at) {
        Expr* target = e.kind == ExprKind::Index ? e.args[0].get() : &e;
        if (target->kind != ExprKind::Ident || !target->symbol) return;
        Symbol* s = target->symbol;
        bool v = varying || ctxVarying();
        if (!v || s->varying) return;
        if (!s->explicitStorage) {
            s->varying = true;
            target->varying = true;
            m_changed = true;
        } else if (s->kind == SymbolKind::Local) {
            // Each point runs its own copy of the shader here, so a local declared uniform
            // (BMRT's glass.sl: a loop counter under a varying if) simply becomes varying,
            // with a warning; a uniform parameter's value is the instance's and stays so.
            s->varying = true;
            target->varying = true;
            m_changed = true;
            m_promoted.push_back({at, s->name});
        } else if (m_report && s->kind != SymbolKind::Global) {
            m_diag.error(at, "cannot assign a varying value to uniform variable '" + s->name + "'");
        }
    }

    void decl(VarDecl& d) {
        if (!d.init) return;
        bool v = expr(*d.init);
        if (d.symbol && !d.isExtern) {
            Expr id(ExprKind::Ident, d.loc);
            id.symbol = d.symbol;
            write(id, v, d.init->loc);
        }
    }

    void stmt(Stmt& s) {
        switch (s.kind) {
        case StmtKind::Empty:
        case StmtKind::Break:
        case StmtKind::Continue: break;
        case StmtKind::Expr: expr(*s.expr); break;
        case StmtKind::Decl:
            for (VarDecl& d : s.decls) decl(d);
            break;
        case StmtKind::Block:
            for (StmtPtr& c : s.stmts) stmt(*c);
            break;
        case StmtKind::If:
            pushCtx(expr(*s.expr));
            stmt(*s.body);
            if (s.elseBody) stmt(*s.elseBody);
            popCtx();
            break;
        case StmtKind::While:
        case StmtKind::For: {
            if (s.init) stmt(*s.init);
            bool v = s.expr ? expr(*s.expr) : false;
            pushCtx(v);
            stmt(*s.body);
            if (s.step) expr(*s.step);
            popCtx();
            break;
        }
        case StmtKind::Return:
            if (s.expr) {
                bool v = expr(*s.expr) || ctxVarying();
                if (v && m_fn && !m_fn->readsVarying) {
                    m_fn->readsVarying = true;
                    m_changed = true;
                }
            }
            break;
        case StmtKind::Illuminance:
        case StmtKind::Illuminate:
        case StmtKind::Solar:
            for (ExprPtr& a : s.args) expr(*a);
            pushCtx(true);
            stmt(*s.body);
            popCtx();
            break;
        case StmtKind::Function: function(*s.function); break;
        }
    }

    // Returns whether e is varying (and records it in e.varying).
    bool expr(Expr& e) {
        bool v = false;
        switch (e.kind) {
        case ExprKind::Number:
        case ExprKind::String: break;
        case ExprKind::Ident: v = e.symbol && e.symbol->varying; break;
        case ExprKind::Assign: {
            bool r = expr(*e.args[1]);
            bool l = expr(*e.args[0]);
            v = r || (e.text != "=" && l);
            write(*e.args[0], v, e.loc);
            v = v || ctxVarying();
            break;
        }
        case ExprKind::Call: v = call(e); break;
        default:
            for (ExprPtr& a : e.args) v = expr(*a) || v;
            break;
        }
        if (e.channel) v = expr(*e.channel) || v;
        e.varying = v;
        return v;
    }

    bool call(Expr& e) {
        bool v = false;
        for (ExprPtr& a : e.args) v = expr(*a) || v;
        if (e.builtin && (e.builtin->flags & BF_VARYING)) v = true;
        if (e.function) {
            v = v || e.function->readsVarying;
            for (size_t i = 0; i < e.args.size() && i < e.function->params.size(); ++i) {
                VarDecl& p = e.function->params[i];
                if (p.symbol && e.args[i]->varying && !p.symbol->varying &&
                    p.storage == Storage::Default) {
                    p.symbol->varying = true;  // a varying argument reaches this parameter
                    m_changed = true;
                }
                if (p.output) write(*e.args[i], v, e.args[i]->loc);
            }
        }
        if (e.sig)
            for (size_t i = 0; i < e.sig->args.size() && i < e.args.size(); ++i)
                if (e.sig->args[i].output) write(*e.args[i], v, e.args[i]->loc);
        return v;
    }

    Program& m_prog;
    Diagnostics& m_diag;
    std::vector<bool> m_ctx;
    FunctionDecl* m_fn = nullptr;
    bool m_changed = false;
    bool m_report = false;
    std::vector<std::pair<SourceLoc, std::string>> m_promoted;  // locals made varying
};

}  // namespace

void inferVarying(Program& prog, Diagnostics& diag) { VaryingPass(prog, diag).run(); }

}  // namespace rsl
