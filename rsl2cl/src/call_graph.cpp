// call_graph.cpp: call cycles among user functions (call_graph.h).
#include "call_graph.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

namespace rsl {
namespace {

// The calls of user functions in a body, in source order. A nested function definition's
// body is not the enclosing body's: its calls are its own, followed when it is called.
void collectCalls(const Expr* e, std::vector<const Expr*>& out) {
    if (!e) return;
    if (e->kind == ExprKind::Call && e->function) out.push_back(e);
    for (const ExprPtr& a : e->args) collectCalls(a.get(), out);
    collectCalls(e->channel.get(), out);
}

void collectCalls(const Stmt* s, std::vector<const Expr*>& out) {
    if (!s || s->kind == StmtKind::Function) return;
    collectCalls(s->expr.get(), out);
    for (const VarDecl& d : s->decls) collectCalls(d.init.get(), out);
    for (const StmtPtr& c : s->stmts) collectCalls(c.get(), out);
    collectCalls(s->body.get(), out);
    collectCalls(s->elseBody.get(), out);
    collectCalls(s->init.get(), out);
    collectCalls(s->step.get(), out);
    for (const ExprPtr& a : s->args) collectCalls(a.get(), out);
}

class CallChecker {
public:
    explicit CallChecker(Diagnostics& diag) : m_diag(diag) {}

    // Follows the calls of a body (of `function`, or of a shader when null), depth first,
    // on a stack of its own (a chain of many functions must not overflow the thread's).
    // Reports a call of a function still being followed, and a chain of calls deeper than
    // kMaxCallDepth: every later stage (the affinity check, the code generator) walks
    // inlined calls recursively.
    void follow(const FunctionDecl* function, const Stmt* body) {
        if (function) {
            if (m_state[function] != State::New) return;
            m_state[function] = State::Open;
        }
        std::vector<Frame> stack(1, Frame{function, {}, 0, 0});
        collectCalls(body, stack.back().calls);
        while (!stack.empty()) {
            Frame& top = stack.back();
            if (top.next == top.calls.size()) {
                const Frame done = std::move(top);
                stack.pop_back();
                if (!done.function) continue;
                m_state[done.function] = State::Done;
                const int depth = m_depth[done.function] = done.deepest + 1;
                if (depth == kMaxCallDepth + 1) {
                    m_diag.error(done.function->loc,
                                 "'" + done.function->name + "' calls functions nested more than " +
                                     std::to_string(kMaxCallDepth) +
                                     " deep (shading language functions are inlined)");
                    m_found = true;
                }
                if (!stack.empty()) stack.back().deepest = std::max(stack.back().deepest, depth);
                continue;
            }
            const Expr* c = top.calls[top.next++];
            State& st = m_state[c->function];
            if (st == State::Open) {
                m_diag.error(c->loc, "recursive call of '" + c->function->name +
                                         "': shading language functions are inlined, so "
                                         "they cannot call themselves");
                m_found = true;
            } else if (st == State::Done) {
                top.deepest = std::max(top.deepest, m_depth[c->function]);
            } else {
                st = State::Open;
                stack.push_back(Frame{c->function, {}, 0, 0});
                collectCalls(c->function->body.get(), stack.back().calls);
            }
        }
    }
    bool found() const { return m_found; }

private:
    static constexpr int kMaxCallDepth = 200;
    enum class State { New, Open, Done };
    struct Frame {
        const FunctionDecl* function;  // null for a shader's body
        std::vector<const Expr*> calls;
        size_t next;
        int deepest;  // the longest chain of calls below this body so far
    };
    Diagnostics& m_diag;
    std::map<const FunctionDecl*, State> m_state;
    std::map<const FunctionDecl*, int> m_depth;  // of each function followed to its end
    bool m_found = false;
};

}  // namespace

bool checkCallGraph(const Program& prog, Diagnostics& diag) {
    CallChecker checker(diag);
    // the functions too, so a library of functions (no shader) is checked as well
    for (const auto& f : prog.functions) checker.follow(f.get(), f->body.get());
    for (const auto& sh : prog.shaders) checker.follow(nullptr, sh->body.get());
    return !checker.found();
}

}  // namespace rsl

namespace rsl {
namespace {

void declaredIn(const Stmt* s, std::set<const Symbol*>& out) {
    if (!s || s->kind == StmtKind::Function) return;
    for (const VarDecl& d : s->decls)
        if (!d.isExtern && d.symbol) out.insert(d.symbol);
    for (const StmtPtr& c : s->stmts) declaredIn(c.get(), out);
    declaredIn(s->init.get(), out);
    declaredIn(s->body.get(), out);
    declaredIn(s->elseBody.get(), out);
}

void usedIn(const Expr* e, std::vector<const Symbol*>& out) {
    if (!e) return;
    if (e->kind == ExprKind::Ident && e->symbol &&
        (e->symbol->kind == SymbolKind::Local || e->symbol->kind == SymbolKind::Param))
        out.push_back(e->symbol);
    for (const ExprPtr& a : e->args) usedIn(a.get(), out);
    usedIn(e->channel.get(), out);
}

void usedIn(const Stmt* s, std::vector<const Symbol*>& out) {
    if (!s || s->kind == StmtKind::Function) return;
    usedIn(s->expr.get(), out);
    for (const VarDecl& d : s->decls) usedIn(d.init.get(), out);
    for (const StmtPtr& c : s->stmts) usedIn(c.get(), out);
    usedIn(s->body.get(), out);
    usedIn(s->elseBody.get(), out);
    usedIn(s->init.get(), out);
    usedIn(s->step.get(), out);
    for (const ExprPtr& a : s->args) usedIn(a.get(), out);
}

}  // namespace

FunctionCaptures functionCaptures(const std::vector<const FunctionDecl*>& functions) {
    FunctionCaptures out;
    for (const FunctionDecl* f : functions) {
        std::set<const Symbol*> own;
        for (const VarDecl& p : f->params) own.insert(p.symbol);
        declaredIn(f->body.get(), own);
        std::vector<const Symbol*> used;
        usedIn(f->body.get(), used);
        std::vector<const Expr*> calls;
        collectCalls(f->body.get(), calls);
        for (const Expr* c : calls)
            if (auto it = out.find(c->function); it != out.end())
                used.insert(used.end(), it->second.begin(), it->second.end());
        std::vector<const Symbol*>& caps = out[f];
        for (const Symbol* s : used)
            if (!own.count(s) && std::find(caps.begin(), caps.end(), s) == caps.end())
                caps.push_back(s);
    }
    return out;
}

}  // namespace rsl
