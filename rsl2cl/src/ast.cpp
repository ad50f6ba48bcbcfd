// ast.cpp: names of shader kinds and a readable dump of the tree.
#include "ast.h"

#include <cstdio>
#include <sstream>

namespace rsl {

const char* shaderKindName(ShaderKind k) {
    switch (k) {
    case ShaderKind::Surface: return "surface";
    case ShaderKind::Light: return "light";
    case ShaderKind::Displacement: return "displacement";
    case ShaderKind::Volume: return "volume";
    case ShaderKind::Imager: return "imager";
    }
    return "?";
}

static std::string numberText(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

static std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out += c;
    }
    return out + "\"";
}

std::string exprToString(const Expr& e) {
    auto arg = [&](size_t i) { return i < e.args.size() ? exprToString(*e.args[i]) : ""; };
    auto list = [&]() {
        std::string s;
        for (size_t i = 0; i < e.args.size(); ++i) s += (i ? ", " : "") + arg(i);
        return s;
    };
    switch (e.kind) {
    case ExprKind::Number: return numberText(e.number);
    case ExprKind::String: return quote(e.text);
    case ExprKind::Ident: return e.text;
    case ExprKind::Unary: return e.text + arg(0);
    case ExprKind::Binary: return "(" + arg(0) + " " + e.text + " " + arg(1) + ")";
    case ExprKind::Ternary: return "(" + arg(0) + " ? " + arg(1) + " : " + arg(2) + ")";
    case ExprKind::Assign: return arg(0) + " " + e.text + " " + arg(1);
    case ExprKind::Call: {
        std::string s = e.text + "(";
        for (size_t i = 0; i < e.args.size(); ++i) {
            s += (i ? ", " : "") + arg(i);
            if (i == 0 && e.channel) s += "[" + exprToString(*e.channel) + "]";
        }
        return s + ")";
    }
    case ExprKind::Cast:
        return e.castType.str() + (e.text.empty() ? "" : " " + quote(e.text)) + " " + arg(0);
    case ExprKind::Tuple: return "(" + list() + ")";
    case ExprKind::Index: return arg(0) + "[" + arg(1) + "]";
    }
    return "?";
}

namespace {

class Dumper {
public:
    std::ostringstream out;

    void line(int ind, const std::string& s) { out << std::string(2 * ind, ' ') << s << "\n"; }

    std::string typed(const Expr& e) {
        std::string s = exprToString(e);
        if (!e.type.isError())
            s += "  : " + std::string(e.varying ? "varying " : "uniform ") + e.type.str();
        return s;
    }

    void decl(int ind, const VarDecl& d, const char* what) {
        std::string s = std::string(what) + " " + (d.isExtern ? "extern " : "") +
                        (d.output ? "output " : "") +
                        (d.storage == Storage::Uniform   ? "uniform "
                         : d.storage == Storage::Varying ? "varying "
                                                         : "") +
                        d.type.str() + " " + d.name;
        if (d.symbol) s += d.symbol->varying ? "  [varying]" : "  [uniform]";
        line(ind, s + "  @" + std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col));
        if (d.init) line(ind + 1, "= " + typed(*d.init));
    }

    void function(int ind, const FunctionDecl& f) {
        line(ind, "function " + f.returnType.str() + " " + f.name);
        for (const VarDecl& p : f.params) decl(ind + 1, p, "param");
        if (f.body) stmt(ind + 1, *f.body);
    }

    void stmt(int ind, const Stmt& s) {
        switch (s.kind) {
        case StmtKind::Empty: line(ind, ";"); break;
        case StmtKind::Expr: line(ind, "expr " + typed(*s.expr)); break;
        case StmtKind::Decl:
            for (const VarDecl& d : s.decls) decl(ind, d, "local");
            break;
        case StmtKind::Block:
            line(ind, "{");
            for (const StmtPtr& c : s.stmts) stmt(ind + 1, *c);
            line(ind, "}");
            break;
        case StmtKind::If:
            line(ind, "if " + typed(*s.expr));
            stmt(ind + 1, *s.body);
            if (s.elseBody) {
                line(ind, "else");
                stmt(ind + 1, *s.elseBody);
            }
            break;
        case StmtKind::While:
            line(ind, "while " + typed(*s.expr));
            stmt(ind + 1, *s.body);
            break;
        case StmtKind::For:
            line(ind, "for");
            if (s.init) stmt(ind + 1, *s.init);
            if (s.expr) line(ind + 1, "cond " + typed(*s.expr));
            if (s.step) line(ind + 1, "step " + typed(*s.step));
            stmt(ind + 1, *s.body);
            break;
        case StmtKind::Break: line(ind, "break " + std::to_string(s.level)); break;
        case StmtKind::Continue: line(ind, "continue " + std::to_string(s.level)); break;
        case StmtKind::Return: line(ind, "return" + (s.expr ? " " + typed(*s.expr) : "")); break;
        case StmtKind::Illuminance:
        case StmtKind::Illuminate:
        case StmtKind::Solar: {
            std::string n = s.kind == StmtKind::Illuminance  ? "illuminance"
                            : s.kind == StmtKind::Illuminate ? "illuminate"
                                                             : "solar";
            line(ind, n);
            for (const ExprPtr& a : s.args) line(ind + 1, "arg " + typed(*a));
            stmt(ind + 1, *s.body);
            break;
        }
        case StmtKind::Function: function(ind, *s.function); break;
        }
    }
};

}  // namespace

std::string dumpAst(const Program& prog) {
    Dumper d;
    for (const auto& f : prog.functions) d.function(0, *f);
    for (const auto& sh : prog.shaders) {
        d.line(0, std::string(shaderKindName(sh->kind)) + " " + sh->name);
        for (const VarDecl& p : sh->params) d.decl(1, p, "param");
        if (sh->body) d.stmt(1, *sh->body);
    }
    return d.out.str();
}

}  // namespace rsl
