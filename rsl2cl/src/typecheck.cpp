// typecheck.cpp: scopes, symbol resolution and typing of RSL expressions and statements.
#include "typecheck.h"

#include <map>
#include <unordered_map>

#include "builtins.h"
#include "globals.h"

namespace rsl {
namespace {

class Checker {
public:
    Checker(Program& prog, Diagnostics& diag) : m_prog(prog), m_diag(diag) {}

    void run() {
        ShaderKind kind = m_prog.shaders.empty() ? ShaderKind::Surface
                                                 : m_prog.shaders[0]->kind;
        pushScope(false);
        for (auto& f : m_prog.functions) declareFunction(*f);
        for (auto& f : m_prog.functions) {
            setKind(kind);
            checkFunction(*f);
        }
        for (auto& sh : m_prog.shaders) {
            setKind(sh->kind);
            pushScope(false);
            for (VarDecl& p : sh->params) declareVar(p, SymbolKind::Param);
            m_returnType = TypeSpec(BaseType::Void);
            m_inShader = true;
            checkStmt(*sh->body);
            m_inShader = false;
            popScope();
        }
    }

private:
    struct Scope {
        std::unordered_map<std::string, Symbol*> vars;
        std::unordered_map<std::string, std::vector<FunctionDecl*>> funcs;
        bool functionBoundary = false;
    };

    void pushScope(bool boundary) {
        m_scopes.emplace_back();
        m_scopes.back().functionBoundary = boundary;
    }
    void popScope() { m_scopes.pop_back(); }

    void setKind(ShaderKind k) {
        m_kind = k;
        m_globals.clear();
        for (const GlobalVar& g : globalsFor(k)) {
            auto it = m_globalSyms.find(std::string(g.name) + "/" + shaderKindName(k));
            Symbol* s;
            if (it != m_globalSyms.end()) {
                s = it->second;
            } else {
                s = m_prog.newSymbol();
                s->name = g.name;
                s->kind = SymbolKind::Global;
                s->type = TypeSpec(g.type);
                s->varying = g.varying;
                s->explicitStorage = true;
                s->readOnly = !g.writable;
                m_globalSyms[std::string(g.name) + "/" + shaderKindName(k)] = s;
            }
            m_globals[g.name] = s;
        }
    }

    // Finds a variable; locals of enclosing functions are hidden unless `extern`.
    Symbol* lookupVar(const std::string& name, bool throughFunctions = false) {
        bool crossed = false;
        for (size_t i = m_scopes.size(); i-- > 0;) {
            auto it = m_scopes[i].vars.find(name);
            if (it != m_scopes[i].vars.end() && (!crossed || throughFunctions || i == 0))
                return it->second;
            if (m_scopes[i].functionBoundary) crossed = true;
        }
        auto g = m_globals.find(name);
        return g == m_globals.end() ? nullptr : g->second;
    }

    const std::vector<FunctionDecl*>* lookupFunction(const std::string& name) {
        for (size_t i = m_scopes.size(); i-- > 0;) {
            auto it = m_scopes[i].funcs.find(name);
            if (it != m_scopes[i].funcs.end()) return &it->second;
        }
        return nullptr;
    }

    void declareFunction(FunctionDecl& f) {
        Symbol* s = m_prog.newSymbol();
        s->name = f.name;
        s->kind = SymbolKind::Function;
        s->type = f.returnType;
        s->loc = f.loc;
        s->function = &f;
        f.symbol = s;
        m_scopes.back().funcs[f.name].push_back(&f);
    }

    void checkFunction(FunctionDecl& f) {
        pushScope(true);
        for (VarDecl& p : f.params) {
            if (p.init) m_diag.error(p.loc, "function parameters cannot have default values");
            declareVar(p, SymbolKind::Param);
            if (p.symbol && !p.isExtern) p.symbol->explicitStorage = p.storage != Storage::Default;
        }
        TypeSpec savedRet = m_returnType;
        bool savedShader = m_inShader;
        int savedLoops = m_loops;
        m_returnType = f.returnType;
        m_inShader = false;
        m_loops = 0;
        checkStmt(*f.body);
        m_returnType = savedRet;
        m_inShader = savedShader;
        m_loops = savedLoops;
        popScope();
    }

    void declareVar(VarDecl& d, SymbolKind kind) {
        if (d.isExtern) {
            Symbol* outer = lookupVar(d.name, true);
            if (!outer) {
                m_diag.error(d.loc, "extern variable '" + d.name + "' is not declared in an enclosing scope");
            } else if (outer->type != d.type) {
                m_diag.error(d.loc, "extern '" + d.name + "' declared as '" + d.type.str() +
                                        "' but is '" + outer->type.str() + "'");
            }
            if (outer) {
                d.symbol = outer;
                m_scopes.back().vars[d.name] = outer;
            }
            return;
        }
        if (m_scopes.back().vars.count(d.name)) {
            m_diag.error(d.loc, "redeclaration of '" + d.name + "'");
        }
        if (d.init) {
            TypeSpec t = check(*d.init, d.type);
            if (!assignable(t, d.type)) {
                m_diag.error(d.init->loc, "cannot initialise '" + d.type.str() + " " +
                                              d.name + "' with a value of type '" +
                                              t.str() + "'");
            }
        }
        Symbol* s = m_prog.newSymbol();
        s->name = d.name;
        s->kind = kind;
        s->type = d.type;
        s->loc = d.loc;
        s->output = d.output;
        s->explicitStorage = d.storage != Storage::Default || kind == SymbolKind::Param;
        s->varying = d.storage == Storage::Varying;
        d.symbol = s;
        m_scopes.back().vars[d.name] = s;
    }

    // ---- statements ------------------------------------------------------------------
    void checkCondition(Expr& e, const char* what) {
        TypeSpec t = check(e, TypeSpec());
        if (!t.isError() && !t.isFloat())
            m_diag.error(e.loc, std::string("condition of ") + what +
                                    " must be a float or relation, not '" + t.str() + "'");
    }

    void checkStmt(Stmt& s) {
        switch (s.kind) {
        case StmtKind::Empty: break;
        case StmtKind::Expr: check(*s.expr, TypeSpec()); break;
        case StmtKind::Decl:
            for (VarDecl& d : s.decls) declareVar(d, SymbolKind::Local);
            break;
        case StmtKind::Block:
            pushScope(false);
            for (StmtPtr& c : s.stmts) checkStmt(*c);
            popScope();
            break;
        case StmtKind::If:
            checkCondition(*s.expr, "if");
            checkStmt(*s.body);
            if (s.elseBody) checkStmt(*s.elseBody);
            break;
        case StmtKind::While:
            checkCondition(*s.expr, "while");
            loopBody(*s.body);
            break;
        case StmtKind::For:
            pushScope(false);
            if (s.init) checkStmt(*s.init);
            if (s.expr) checkCondition(*s.expr, "for");
            if (s.step) check(*s.step, TypeSpec());
            loopBody(*s.body);
            popScope();
            break;
        case StmtKind::Break:
        case StmtKind::Continue:
            if (m_loops == 0)
                m_diag.error(s.loc, std::string(s.kind == StmtKind::Break ? "break" : "continue") +
                                        " outside a loop");
            else if (s.level > m_loops)
                m_diag.error(s.loc, "loop level " + std::to_string(s.level) +
                                        " exceeds the " + std::to_string(m_loops) +
                                        " enclosing loop(s)");
            break;
        case StmtKind::Return: checkReturn(s); break;
        case StmtKind::Illuminance:
        case StmtKind::Illuminate:
        case StmtKind::Solar: checkLightLoop(s); break;
        case StmtKind::Function:
            declareFunction(*s.function);
            checkFunction(*s.function);
            break;
        }
    }

    void loopBody(Stmt& body) {
        ++m_loops;
        checkStmt(body);
        --m_loops;
    }

    void checkReturn(Stmt& s) {
        if (!s.expr) {
            if (!m_inShader && !m_returnType.isVoid())
                m_diag.error(s.loc, "return without a value in a function returning '" +
                                        m_returnType.str() + "'");
            return;
        }
        TypeSpec t = check(*s.expr, m_returnType);
        if (m_inShader || m_returnType.isVoid()) {
            m_diag.error(s.loc, m_inShader ? "a shader cannot return a value"
                                           : "return with a value in a void function");
        } else if (!assignable(t, m_returnType)) {
            m_diag.error(s.expr->loc, "cannot return '" + t.str() + "' from a function returning '" +
                                          m_returnType.str() + "'");
        }
    }

    void checkLightLoop(Stmt& s) {
        const char* name = s.kind == StmtKind::Illuminance  ? "illuminance"
                           : s.kind == StmtKind::Illuminate ? "illuminate"
                                                            : "solar";
        std::vector<TypeSpec> want;
        size_t first = 0;
        if (s.kind == StmtKind::Illuminance) {
            if (m_kind != ShaderKind::Surface && m_kind != ShaderKind::Volume)
                m_diag.error(s.loc, "illuminance is only allowed in surface and volume shaders");
            if (!s.args.empty() && check(*s.args[0], TypeSpec(BaseType::String)).isString())
                first = 1;  // light category
            want = {BaseType::Point, BaseType::Vector, BaseType::Float};
        } else {
            if (m_kind != ShaderKind::Light)
                m_diag.error(s.loc, std::string(name) + " is only allowed in light shaders");
            if (s.kind == StmtKind::Illuminate) want = {BaseType::Point, BaseType::Vector, BaseType::Float};
            else want = {BaseType::Vector, BaseType::Float};
        }
        size_t n = s.args.size() - first;
        bool countOk = s.kind == StmtKind::Solar ? (n == 0 || n == 2) : (n == 1 || n == 3);
        if (!countOk) {
            m_diag.error(s.loc, std::string("wrong number of arguments to ") + name + ": " +
                                    std::to_string(n) + " given");
        }
        for (size_t i = first; i < s.args.size(); ++i) {
            TypeSpec w = i - first < want.size() ? want[i - first] : TypeSpec();
            TypeSpec t = check(*s.args[i], w);
            if (!w.isError() && !assignable(t, w))
                m_diag.error(s.args[i]->loc, std::string("argument ") + std::to_string(i + 1) +
                                                 " of " + name + " must be '" + w.str() +
                                                 "', not '" + t.str() + "'");
        }
        if (s.kind == StmtKind::Illuminance && m_inIlluminance)
            m_diag.error(s.loc, "illuminance loops cannot be nested");
        bool saved = m_inIlluminance;
        m_inIlluminance = true;
        checkStmt(*s.body);
        m_inIlluminance = saved;
    }

    // ---- expressions -----------------------------------------------------------------
    TypeSpec check(Expr& e, const TypeSpec& expected) {
        e.type = checkInner(e, expected);
        return e.type;
    }

    TypeSpec checkInner(Expr& e, const TypeSpec& expected);
    TypeSpec checkAssign(Expr& e);
    TypeSpec checkCall(Expr& e, const TypeSpec& expected);
    TypeSpec checkUserCall(Expr& e, const std::vector<FunctionDecl*>& fns,
                           const std::vector<TypeSpec>& args, const TypeSpec& expected);
    TypeSpec checkCast(Expr& e);
    TypeSpec checkTuple(Expr& e, const TypeSpec& expected);
    bool checkLvalue(Expr& e, const std::string& what);

    Program& m_prog;
    Diagnostics& m_diag;
    std::vector<Scope> m_scopes;
    std::unordered_map<std::string, Symbol*> m_globals;
    std::map<std::string, Symbol*> m_globalSyms;
    ShaderKind m_kind = ShaderKind::Surface;
    TypeSpec m_returnType;
    bool m_inShader = false;
    bool m_inIlluminance = false;
    int m_loops = 0;
};

#include "typecheck_expr.inc"

}  // namespace

bool typecheckProgram(Program& prog, Diagnostics& diag) {
    int before = diag.errorCount();
    Checker(prog, diag).run();
    if (diag.errorCount() == before) inferVarying(prog, diag);
    return diag.errorCount() == before;
}

}  // namespace rsl
