// info.cpp: gathers and prints shader metadata from the typed AST.
#include "info.h"

#include "builtins.h"
#include "emit_cl.h"
#include "hoist.h"

namespace rsl {
namespace {

class InfoWalker {
public:
    explicit InfoWalker(ShaderInfo& info) : m_info(info) {}

    void stmt(const Stmt& s) {
        if (s.expr) expr(*s.expr);
        for (const VarDecl& d : s.decls)
            if (d.init) expr(*d.init);
        for (const StmtPtr& c : s.stmts) stmt(*c);
        if (s.init) stmt(*s.init);
        if (s.step) expr(*s.step);
        for (const ExprPtr& a : s.args) expr(*a);
        if (s.kind == StmtKind::Illuminance) {
            m_info.services.insert("illuminance");
            m_info.globalsRead.insert("L");
            m_info.globalsRead.insert("Cl");
        }
        if (s.kind == StmtKind::Illuminate || s.kind == StmtKind::Solar) {
            m_info.services.insert(s.kind == StmtKind::Illuminate ? "illuminate" : "solar");
            m_info.globalsWritten.insert("L");
        }
        if (s.body) stmt(*s.body);
        if (s.elseBody) stmt(*s.elseBody);
        // nested function bodies are walked where they are called
    }

    void expr(const Expr& e, bool written = false) {
        switch (e.kind) {
        case ExprKind::Ident:
            if (e.symbol && e.symbol->kind == SymbolKind::Global)
                (written ? m_info.globalsWritten : m_info.globalsRead).insert(e.symbol->name);
            return;
        case ExprKind::Assign:
            expr(*e.args[0], true);
            if (e.text != "=") expr(*e.args[0], false);
            expr(*e.args[1]);
            return;
        case ExprKind::Index:
            expr(*e.args[0], written);
            expr(*e.args[1]);
            return;
        case ExprKind::Call: call(e); return;
        default:
            for (const ExprPtr& a : e.args) expr(*a);
        }
    }

private:
    void call(const Expr& e) {
        if (e.channel) expr(*e.channel);
        for (size_t i = 0; i < e.args.size(); ++i) {
            bool out = (e.sig && i < e.sig->args.size() && e.sig->args[i].output) ||
                       (e.function && i < e.function->params.size() &&
                        e.function->params[i].output);
            expr(*e.args[i], out);
        }
        if (e.function) {
            if (m_visited.insert(e.function).second && e.function->body)
                stmt(*e.function->body);
            return;
        }
        if (!e.builtin) return;
        unsigned f = e.builtin->flags;
        if (f & BF_TRACE) m_info.services.insert("trace");
        if (f & BF_LIGHTING) m_info.services.insert("lighting");
        if (f & BF_MESSAGE) m_info.services.insert("message");
        if (f & BF_DERIV) {
            m_info.services.insert("derivatives");
            m_info.derivatives.insert(e.text);
        }
        const char* svc = (f & BF_TEXTURE)       ? "texture"
                          : (f & BF_ENVIRONMENT) ? "environment"
                          : (f & BF_SHADOW)      ? "shadow"
                                                 : nullptr;
        if (svc) {
            m_info.services.insert(svc);
            if (!e.args.empty() && e.args[0]->kind == ExprKind::String)
                m_info.textures.insert(e.args[0]->text);
        }
    }

    ShaderInfo& m_info;
    std::set<const FunctionDecl*> m_visited;
};

std::string join(const std::set<std::string>& s) {
    if (s.empty()) return "(none)";
    std::string out;
    for (const std::string& x : s) out += (out.empty() ? "" : " ") + x;
    return out;
}

}  // namespace

ShaderInfo collectInfo(const ShaderDecl& shader) {
    ShaderInfo info;
    info.kind = shader.kind;
    info.name = shader.name;
    for (const VarDecl& p : shader.params) {
        ParamInfo pi;
        pi.name = p.name;
        pi.type = p.type;
        pi.varying = p.symbol ? p.symbol->varying : p.storage == Storage::Varying;
        pi.output = p.output;
        if (p.init) {
            pi.hasDefault = true;
            pi.constantDefault = evalConst(*p.init, pi.value);
            if (pi.constantDefault && !p.type.isArray() && !p.type.isString() &&
                pi.value.values.size() == 1 && (p.type.isTriple() || p.type.isMatrix())) {
                // a float default of a colour/point parameter: widen for the reader
                ConstValue v = pi.value;
                size_t n = p.type.isMatrix() ? 16 : 3;
                if (n == 16) {
                    v.values.assign(16, 0.0);
                    for (int i = 0; i < 4; ++i) v.values[i * 5] = pi.value.values[0];
                } else {
                    v.values.assign(3, pi.value.values[0]);
                }
                pi.value = v;
            }
            if (!pi.constantDefault) pi.defaultText = exprToString(*p.init);
        }
        info.params.push_back(pi);
    }
    InfoWalker walker(info);
    for (const VarDecl& p : shader.params)
        if (p.init) walker.expr(*p.init);
    if (shader.body) walker.stmt(*shader.body);
    if (shader.body && shader.kind != ShaderKind::Light) {
        std::vector<bool> computed;
        for (const VarDecl& p : shader.params) {
            ConstValue v;
            computed.push_back(p.init && !evalConst(*p.init, v));
        }
        for (const VarDecl* d : planHoisting(shader, computed).decls)
            info.oncePerInstance.push_back(d->name);
    }
    if (shader.kind == ShaderKind::Surface) {
        std::string why;
        info.lightCoefficients = lightCoefsSupported(shader, &why) ? "yes" : "no (" + why + ")";
    }
    return info;
}

std::string formatInfo(const ShaderInfo& info) {
    std::string out = std::string(shaderKindName(info.kind)) + " \"" + info.name + "\"\n";
    for (const ParamInfo& p : info.params) {
        out += "    \"" + p.name + "\" \"" + (p.output ? "output " : "") + "parameter " +
               (p.varying ? "varying " : "uniform ") + p.type.str() + "\"\n";
        if (p.hasDefault)
            out += "        Default value: " +
                   (p.constantDefault ? p.value.text() : p.defaultText) + "\n";
    }
    out += "    globals read: " + join(info.globalsRead) + "\n";
    out += "    globals written: " + join(info.globalsWritten) + "\n";
    out += "    services: " + join(info.services) + "\n";
    if (!info.lightCoefficients.empty())
        out += "    light coefficients: " + info.lightCoefficients + "\n";
    if (!info.textures.empty()) out += "    textures: " + join(info.textures) + "\n";
    if (!info.derivatives.empty()) out += "    derivatives: " + join(info.derivatives) + "\n";
    if (!info.oncePerInstance.empty()) {
        out += "    once per instance:";
        for (const std::string& v : info.oncePerInstance) out += " " + v;
        out += "\n";
    }
    return out;
}

}  // namespace rsl
