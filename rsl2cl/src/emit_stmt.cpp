// emit_stmt.cpp: statements as OpenCL C: declarations (a hoisted one read from the
// instance's prepared block), expressions, conditionals, loops with their guards and
// labelled break/continue N, returns, and the light loops (illuminance, illuminate,
// solar).
#include <string>

#include "emit_internal.h"

namespace rsl {

void Emitter::decl(const VarDecl& d) {
    if (d.isExtern) return;
    std::string t = clType(d.type), name = "v_" + d.name;
    if (auto h = m_hoist.slot.find(&d); h != m_hoist.slot.end() && !m_func) {
        std::string once =
            blockRead(d.type.base, std::to_string(m_out.prepOffset + h->second));
        if (const char* guard = pointParamsGuard()) {
            // an instance whose parameters vary per point: the prepared value was made
            // from the block's values, not the point's, so compute it here instead
            line(guard);
            line(t + " " + name + " = g->pv_count > 0 ? " + exprAs(*d.init, d.type) +
                 " : " + once + ";");
            line("#else");
            line(t + " " + name + " = " + once + "; /* once per instance */");
            line("#endif");
            return;
        }
        line(t + " " + name + " = " + once + "; /* once per instance */");
        return;
    }
    if (d.type.isArray()) {
        int n = d.type.arraySize;
        if (n <= 0) {
            error(d.loc, "local array '" + d.name + "' needs a size");
            return;
        }
        if (d.init && d.init->kind == ExprKind::Tuple) {
            std::string s = t + " " + name + "[" + std::to_string(n) + "] = {";
            for (size_t i = 0; i < d.init->args.size(); ++i)
                s += (i ? ", " : "") + exprAs(*d.init->args[i], d.type.element());
            line(s + "};");
            return;
        }
        line(t + " " + name + "[" + std::to_string(n) + "];");
        line("for (int _i = 0; _i < " + std::to_string(n) + "; ++_i) " + name +
             "[_i] = " + clZero(d.type) + ";");
        if (d.init)
            error(d.loc, "array initialisers other than {...} lists are not supported");
        return;
    }
    const bool coefs = m_coefs && m_coefs->symbols.count(d.symbol);
    if (coefs && d.init) hoistOperands(*d.init);
    line(t + " " + name + " = " + (d.init ? exprAs(*d.init, d.type) : clZero(d.type)) +
         ";");
    if (coefs) coefDecl(d);
    m_exprTemps.clear();
}

// A loop's pass counter for RSL_LOOP_GUARD (rsl_abi.h, LOOPS), declared before it.
std::string Emitter::loopGuardCounter() {
    const std::string name = "_passes" + std::to_string(m_tmp++);
    line("int " + name + " = 0;");
    return name;
}

void Emitter::loopBody(const Stmt& body) {
    int id = m_tmp++;
    m_loops.push_back(id);
    stmt(body);
    if (m_continueTargets.count(id)) line("_cont" + std::to_string(id) + ": ;");
}

void Emitter::loopEnd() {
    if (m_breakTargets.count(m_loops.back()))
        line("_brk" + std::to_string(m_loops.back()) + ": ;");
    m_loops.pop_back();
}

void Emitter::lightLoop(const Stmt& s) {
    int id = m_tmp++;
    std::string k = std::to_string(id);
    if (s.kind == StmtKind::Illuminance) {
        m_out.usesLighting = true;
        size_t first = (!s.args.empty() && s.args[0]->type.isString()) ? 1 : 0;
        line("{");
        ++m_indent;
        line("float4 _ilP" + k + " = " + exprAs(*s.args[first], BaseType::Point) + ";");
        bool cone = s.args.size() - first == 3;
        line("float4 _ilA" + k + " = " +
             (cone ? exprAs(*s.args[first + 1], BaseType::Vector) : "rsl_f2v(0.0f)") +
             ";");
        line("float _ilC" + k + " = " + (cone ? coneCos(s) : std::string("-2.0f")) + ";");
        line("int _nl" + k + " = rsl_light_count();");
        line("for (int _l" + k + " = 0; _l" + k + " < _nl" + k + "; ++_l" + k + ") {");
        ++m_indent;
        // the unshadowed Cl (_Clr: what light coefficients read), then this mode's
        line("float4 _L" + k + "; rsl_color _Clr" + k + ";");
        line("if (!rsl_light_raw(_l" + k + ", g, _ilP" + k + ", _ilA" + k + ", _ilC" + k +
             ", &_L" + k + ", &_Clr" + k + ")) continue;");
        line("rsl_color _Cl" + k + " = rsl_light_mode(ev, _l" + k + ", _Clr" + k +
             ", _ilP" + k + ");");
        line("g->L = _L" + k + "; g->Cl = _Cl" + k + ";");
        m_lightVars.push_back("_l" + k);
        m_lightRaw.push_back("_Clr" + k);
        stmt(*s.body);
        m_lightVars.pop_back();
        m_lightRaw.pop_back();
        --m_indent;
        line("}");
        --m_indent;
        line("}");
        return;
    }
    line("{");
    ++m_indent;
    if (s.kind == StmtKind::Illuminate) {
        line("g->L = rsl_w0(g->Ps - " + exprAs(*s.args[0], BaseType::Point) + ");");
        if (s.args.size() == 3) {
            line("if (rsl_in_cone(g->L, " + exprAs(*s.args[1], BaseType::Vector) + ", " +
                 coneCos(s) + "))");
        }
    } else {
        line("g->L = " +
             (s.args.size() == 2 ? "rsl_w0(" + exprAs(*s.args[0], BaseType::Vector) + ")"
                                 : std::string("rsl_f2v(0.0f)")) +
             ";");
        line("RSL_CW(g->Ol) = 1.0f; /* solar: the light is infinitely far */");
    }
    line("{");
    ++m_indent;
    stmt(*s.body);
    --m_indent;
    line("}");
    --m_indent;
    line("}");
}

// A whole array assigned as a statement (`b = a;`, arrays of one element type and
// length): element by element. Elsewhere in an expression it is an error (emit_expr.cpp).
void Emitter::arrayAssign(const Expr& e) {
    const TypeSpec& l = e.args[0]->type;
    const TypeSpec& r = e.args[1]->type;
    if (!r.isArray() || r.element().base != l.element().base ||
        r.arraySize != l.arraySize || l.arraySize <= 0) {
        error(e.loc, "an array takes a whole array only of its own type and length ('" +
                         l.str() + "' from '" + r.str() + "')");
        return;
    }
    const std::string k = "_k" + std::to_string(m_tmp++);
    const std::string to = expr(*e.args[0]), from = expr(*e.args[1]);
    line("for (int " + k + " = 0; " + k + " < " + std::to_string(l.arraySize) + "; ++" +
         k + ") " + to + "[" + k + "] = " + from + "[" + k + "];");
}

void Emitter::stmt(const Stmt& s) {
    switch (s.kind) {
        case StmtKind::Empty:
            break;
        case StmtKind::Expr:
            exprStatement(*s.expr);
            break;
        case StmtKind::Decl:
            for (const VarDecl& d : s.decls) decl(d);
            break;
        case StmtKind::Block:
            line("{");
            ++m_indent;
            for (const StmtPtr& c : s.stmts) stmt(*c);
            --m_indent;
            line("}");
            break;
        case StmtKind::If:
            line("if ((" + expr(*s.expr) + ") != 0.0f) {");
            ++m_indent;
            stmt(*s.body);
            --m_indent;
            if (s.elseBody) {
                line("} else {");
                ++m_indent;
                stmt(*s.elseBody);
                --m_indent;
            }
            line("}");
            break;
        case StmtKind::While:
        case StmtKind::For:
            loop(s);
            break;
        case StmtKind::Break:
        case StmtKind::Continue:
            jump(s);
            break;
        case StmtKind::Return:
            returnStatement(s);
            break;
        case StmtKind::Illuminance:
        case StmtKind::Illuminate:
        case StmtKind::Solar:
            lightLoop(s);
            break;
        case StmtKind::Function:
            break;  // emitted before the shader when called
    }
}

void Emitter::exprStatement(const Expr& e) {
    if (e.kind == ExprKind::Assign && e.text == "=" && e.args[0]->type.isArray())
        return arrayAssign(e);
    if (coefTarget(e)) hoistAssign(e);
    // a builtin the renderer answers at compile time (an unknown lightsource() or
    // textureinfo() name is 0) leaves a bare constant: the OpenCL compiler would warn
    // "expression result unused" to the user
    const std::string code = expr(e);
    const bool constant =
        !code.empty() && code.find_first_not_of("0123456789.f-") == std::string::npos;
    line((constant ? "(void)" : "") + code + ";");
    if (coefTarget(e)) coefAssign(e);
    m_exprTemps.clear();
}

// while and for: in a block of their own, with a pass counter for RSL_LOOP_GUARD
void Emitter::loop(const Stmt& s) {
    line("{");
    ++m_indent;
    if (s.kind == StmtKind::For && s.init) stmt(*s.init);
    const std::string passes = loopGuardCounter();
    if (s.kind == StmtKind::While)
        line("while ((" + expr(*s.expr) + ") != 0.0f) {");
    else
        line("for (; " + (s.expr ? "(" + expr(*s.expr) + ") != 0.0f" : std::string("1")) +
             "; " + (s.step ? expr(*s.step) : std::string()) + ") {");
    ++m_indent;
    line("RSL_LOOP_GUARD(" + passes + ")");
    loopBody(*s.body);
    --m_indent;
    line("}");
    loopEnd();
    --m_indent;
    line("}");
}

// break N / continue N leave or continue the N-th enclosing loop: a goto to the label
// after that loop, or at the end of its body (where a for loop's step follows)
void Emitter::jump(const Stmt& s) {
    const bool isBreak = s.kind == StmtKind::Break;
    int n = s.level;
    if (n < 1 || n > int(m_loops.size())) {
        error(s.loc, std::string(isBreak ? "break" : "continue") + " " +
                         std::to_string(n) + " outside of " + std::to_string(n) +
                         " enclosing loop(s)");
        return;
    }
    if (n == 1) {
        line(isBreak ? "break;" : "continue;");
        return;
    }
    int id = m_loops[m_loops.size() - size_t(n)];
    (isBreak ? m_breakTargets : m_continueTargets).insert(id);
    line(std::string("goto ") + (isBreak ? "_brk" : "_cont") + std::to_string(id) + ";");
}

// A function's return; a shader's writes its outputs first
void Emitter::returnStatement(const Stmt& s) {
    if (m_func && s.expr && coefFunction(m_func))
        coefReturn(*s.expr, m_func->returnType);
    else if (m_func && s.expr)
        line("return " + exprAs(*s.expr, m_func->returnType) + ";");
    else if (m_func || m_sh.kind == ShaderKind::Light ||
             (m_out.outputFloats == 0 && m_sh.kind != ShaderKind::Imager))
        line("return;");
    else {
        line("{");
        ++m_indent;
        writeOutputs();
        line("return;");
        --m_indent;
        line("}");
    }
}

}  // namespace rsl
