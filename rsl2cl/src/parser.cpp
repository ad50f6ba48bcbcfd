// parser.cpp: hand-written recursive-descent parser for RSL (RenderMan Interface 3.2).
// Precedence, lowest first: = += -= *= /=, ?:, ||, &&, == !=, < > <= >=, + -, * /,
// ^ (cross), . (dot), unary - !, postfix [] and calls.
#include "parser.h"

#include "gather.h"

namespace rsl {
namespace {

struct SyntaxError {};

class Parser {
public:
    Parser(const std::vector<Token>& toks, Program& prog, Diagnostics& diag)
        : m_toks(toks), m_prog(prog), m_diag(diag) {}

    bool run() {
        int start = m_diag.errorCount();
        while (cur().kind != TokKind::End) {
            size_t before = m_pos;
            try {
                topLevel();
            } catch (const SyntaxError&) {
                recoverTop();
            }
            if (m_pos == before) ++m_pos;  // always make progress
            if (m_diag.errorCount() - start > 50) break;
        }
        return m_diag.errorCount() == start;
    }

private:
    const Token& cur() const { return m_toks[m_pos]; }
    const Token& peek(size_t k) const {
        size_t i = m_pos + k;
        return i < m_toks.size() ? m_toks[i] : m_toks.back();
    }
    void next() {
        if (cur().kind != TokKind::End) ++m_pos;
    }
    bool accept(const char* p) {
        if (!cur().is(p)) return false;
        next();
        return true;
    }
    [[noreturn]] void fail(const std::string& what) {
        const Token& t = cur();
        std::string found = t.kind == TokKind::End      ? "end of input"
                            : t.kind == TokKind::String ? "string \"" + t.text + "\""
                                                        : "'" + t.text + "'";
        m_diag.error(t.loc, "expected " + what + " but found " + found);
        throw SyntaxError();
    }
    void expect(const char* p) {
        if (!accept(p)) fail(std::string("'") + p + "'");
    }
    std::string expectIdent(const char* what) {
        if (cur().kind != TokKind::Ident || isKeyword(cur().text)) fail(what);
        std::string s = cur().text;
        next();
        return s;
    }

    static bool isTypeName(const std::string& s) {
        return baseTypeFromName(s) != BaseType::Error;
    }
    static bool isShaderKind(const std::string& s, ShaderKind& k) {
        static const ShaderKind kinds[] = {ShaderKind::Surface, ShaderKind::Light,
                                           ShaderKind::Displacement, ShaderKind::Volume,
                                           ShaderKind::Imager};
        for (ShaderKind sk : kinds)
            if (s == shaderKindName(sk)) {
                k = sk;
                return true;
            }
        return false;
    }
    // (the shader kinds are keywords only where a shader begins, at the top level: old
    // shaders name variables `light`, as the RenderMan Repository's IDscartissue.sl does)
    static bool isKeyword(const std::string& s) {
        static const char* const kw[] = {
            "if",       "else",    "while",       "for",    "break",
            "continue", "return",  "illuminance", "gather", "illuminate",
            "solar",    "uniform", "varying",     "output", "extern"};
        for (const char* k : kw)
            if (s == k) return true;
        return isTypeName(s);
    }
    bool atTypeName() const { return cur().kind == TokKind::Ident && isTypeName(cur().text); }
    bool atDeclStart() const {
        if (cur().kind != TokKind::Ident) return false;
        const std::string& s = cur().text;
        if (s == "uniform" || s == "varying" || s == "output" || s == "extern") return true;
        // `color c` or `float f(` (a function); `color (1,0,0)` is an expression
        return isTypeName(s) && peek(1).kind == TokKind::Ident;
    }

    struct Depth {
        Parser& p;
        explicit Depth(Parser& parser) : p(parser) {
            if (++p.m_depth > 200) {
                p.m_depth = 0;
                p.fail("shallower nesting (too deep)");
            }
        }
        ~Depth() {
            if (p.m_depth > 0) --p.m_depth;
        }
    };

    // ---- top level -------------------------------------------------------------------
    void topLevel() {
        ShaderKind kind;
        if (cur().kind == TokKind::Ident && isShaderKind(cur().text, kind)) {
            auto sh = std::make_unique<ShaderDecl>();
            sh->loc = cur().loc;
            sh->kind = kind;
            next();
            sh->name = expectIdent("a shader name");
            expect("(");
            sh->params = formals(true);
            expect(")");
            sh->body = block();
            m_prog.shaders.push_back(std::move(sh));
            return;
        }
        m_prog.functions.push_back(functionDef());
    }

    std::unique_ptr<FunctionDecl> functionDef() {
        auto fn = std::make_unique<FunctionDecl>();
        fn->loc = cur().loc;
        fn->returnType = TypeSpec(BaseType::Void);
        // (PRMan takes a storage class before the result's type: `uniform float f()`)
        if ((cur().isIdent("uniform") || cur().isIdent("varying")) &&
            isTypeName(peek(1).text))
            next();
        if (atTypeName()) {
            fn->returnType = TypeSpec(baseTypeFromName(cur().text));
            next();
        }
        if (cur().kind != TokKind::Ident || isKeyword(cur().text))
            fail("a shader or function definition");
        fn->loc = cur().loc;
        fn->name = cur().text;
        next();
        expect("(");
        fn->params = formals(false);
        expect(")");
        fn->body = block();
        return fn;
    }

    void recoverTop() {
        int nest = 0;
        while (cur().kind != TokKind::End) {
            if (cur().is("{")) ++nest;
            if (cur().is("}") && --nest <= 0) {
                next();
                if (nest == 0) return;
                nest = 0;
                continue;
            }
            next();
        }
    }

    // Formal parameters: groups `[output] [uniform|varying] type name [= default]`,
    // separated by ';' (commas continue a group with the same type).
    std::vector<VarDecl> formals(bool isShader) {
        std::vector<VarDecl> out;
        while (!cur().is(")")) {
            VarDecl proto;
            proto.loc = cur().loc;
            declPrefix(proto);
            for (;;) {
                VarDecl d;
                d.loc = cur().loc;
                d.type = proto.type;
                d.storage = proto.storage;
                d.output = proto.output;
                d.name = expectIdent("a parameter name");
                arraySuffix(d);
                if (accept("="))
                    d.init = d.type.isArray() && cur().is("{") ? arrayInit() : assignment();
                out.push_back(std::move(d));
                if (cur().is(",") && peek(1).kind == TokKind::Ident &&
                    !isKeyword(peek(1).text)) {
                    next();
                    continue;
                }
                break;
            }
            if (cur().is(")")) break;
            if (!accept(";") && !accept(",")) fail("';' or ')' after a parameter");
        }
        (void)isShader;
        return out;
    }

    // [extern] [output] [uniform|varying] type
    void declPrefix(VarDecl& d) {
        for (;;) {
            if (cur().isIdent("extern")) d.isExtern = true;
            else if (cur().isIdent("output")) d.output = true;
            else if (cur().isIdent("uniform")) d.storage = Storage::Uniform;
            else if (cur().isIdent("varying")) d.storage = Storage::Varying;
            else break;
            next();
        }
        if (!atTypeName() || cur().isIdent("void")) fail("a type name");
        d.type = TypeSpec(baseTypeFromName(cur().text));
        next();
    }

    void arraySuffix(VarDecl& d) {
        if (!accept("[")) return;
        if (accept("]")) {
            d.type.arraySize = -1;
            return;
        }
        if (cur().kind != TokKind::Number || cur().number < 1 || cur().number > 1e6 ||
            cur().number != static_cast<int>(cur().number))
            fail("a positive integer array length");
        d.type.arraySize = static_cast<int>(cur().number);
        next();
        expect("]");
    }

    // ---- statements ------------------------------------------------------------------
    StmtPtr block() {
        Depth depth(*this);
        auto b = std::make_unique<Stmt>(StmtKind::Block, cur().loc);
        expect("{");
        while (!cur().is("}")) {
            if (cur().kind == TokKind::End) fail("'}'");
            size_t before = m_pos;
            try {
                b->stmts.push_back(statement());
            } catch (const SyntaxError&) {
                recoverStmt();
            }
            if (m_pos == before) next();
        }
        next();
        return b;
    }

    void recoverStmt() {
        int nest = 0;
        while (cur().kind != TokKind::End) {
            if (cur().is("{")) ++nest;
            if (cur().is("}")) {
                if (nest == 0) return;  // let the enclosing block close
                if (--nest == 0) {
                    next();
                    return;
                }
            }
            if (cur().is(";") && nest == 0) {
                next();
                return;
            }
            next();
        }
    }

    StmtPtr statement() {
        Depth depth(*this);
        SourceLoc loc = cur().loc;
        if (cur().is("{")) return block();
        if (accept(";")) return std::make_unique<Stmt>(StmtKind::Empty, loc);
        if (cur().kind == TokKind::Ident) {
            const std::string& w = cur().text;
            if (w == "if") return ifStmt();
            if (w == "while") return whileStmt(loc);
            if (w == "for") return forStmt();
            if (w == "break" || w == "continue") return jumpStmt(loc);
            if (w == "return") return returnStmt(loc);
            if (w == "gather") return gatherStmt(loc);
            if (w == "illuminance" || w == "illuminate" || w == "solar")
                return lightStmt(loc);
            if (atDeclStart()) return declarationOrFunction(loc);
        }
        auto s = std::make_unique<Stmt>(StmtKind::Expr, loc);
        s->expr = expression();
        expect(";");
        return s;
    }

    // ( [assignment {, assignment}] )
    std::vector<ExprPtr> parenthesisedArgs() {
        std::vector<ExprPtr> args;
        expect("(");
        if (!cur().is(")")) {
            args.push_back(assignment());
            while (accept(",")) args.push_back(assignment());
        }
        expect(")");
        return args;
    }

    StmtPtr whileStmt(const SourceLoc& loc) {
        next();
        auto s = std::make_unique<Stmt>(StmtKind::While, loc);
        expect("(");
        s->expr = expression();
        expect(")");
        s->body = statement();
        return s;
    }

    // break [N]; continue [N];
    StmtPtr jumpStmt(const SourceLoc& loc) {
        auto s = std::make_unique<Stmt>(
            cur().text == "break" ? StmtKind::Break : StmtKind::Continue, loc);
        next();
        if (cur().kind == TokKind::Number) {
            if (cur().number < 1 || cur().number != static_cast<int>(cur().number))
                fail("a positive integer loop level");
            s->level = static_cast<int>(cur().number);
            next();
        }
        expect(";");
        return s;
    }

    StmtPtr returnStmt(const SourceLoc& loc) {
        next();
        auto s = std::make_unique<Stmt>(StmtKind::Return, loc);
        if (!cur().is(";")) s->expr = expression();
        expect(";");
        return s;
    }

    // gather(...) statement [else statement]: written as a loop (gather.cpp)
    StmtPtr gatherStmt(const SourceLoc& loc) {
        next();
        std::vector<ExprPtr> args = parenthesisedArgs();
        StmtPtr hit = statement(), miss;
        if (cur().isIdent("else")) {
            next();
            miss = statement();
        }
        return desugarGather(loc, std::move(args), std::move(hit), std::move(miss),
                             m_gathers++, m_diag);
    }

    // illuminance, illuminate or solar (...) statement
    StmtPtr lightStmt(const SourceLoc& loc) {
        const std::string& w = cur().text;
        StmtKind k = w == "illuminance"  ? StmtKind::Illuminance
                     : w == "illuminate" ? StmtKind::Illuminate
                                         : StmtKind::Solar;
        next();
        auto s = std::make_unique<Stmt>(k, loc);
        s->args = parenthesisedArgs();
        s->body = statement();
        return s;
    }

    // A declaration, or a nested function: [uniform | varying] type name (
    StmtPtr declarationOrFunction(const SourceLoc& loc) {
        const int at = cur().isIdent("uniform") || cur().isIdent("varying") ? 1 : 0;
        if ((isTypeName(peek(at).text) && peek(at + 1).kind == TokKind::Ident &&
             peek(at + 2).is("(")) ||
            (cur().isIdent("void"))) {
            auto s = std::make_unique<Stmt>(StmtKind::Function, loc);
            s->function = functionDef();
            return s;
        }
        auto s = declaration();
        expect(";");
        return s;
    }

    StmtPtr declaration() {
        auto s = std::make_unique<Stmt>(StmtKind::Decl, cur().loc);
        VarDecl proto;
        declPrefix(proto);
        do {
            VarDecl d;
            d.loc = cur().loc;
            d.type = proto.type;
            d.storage = proto.storage;
            d.output = proto.output;
            d.isExtern = proto.isExtern;
            d.name = expectIdent("a variable name");
            arraySuffix(d);
            if (accept("=")) {
                if (d.type.isArray() && cur().is("{")) {
                    d.init = arrayInit();
                } else {
                    d.init = assignment();
                }
            }
            s->decls.push_back(std::move(d));
        } while (accept(","));
        return s;
    }

    // { a, b, c } initialiser of an array: a Tuple
    ExprPtr arrayInit() {
        auto t = std::make_unique<Expr>(ExprKind::Tuple, cur().loc);
        expect("{");
        if (!cur().is("}")) {
            t->args.push_back(assignment());
            while (accept(",")) t->args.push_back(assignment());
        }
        expect("}");
        return t;
    }

    StmtPtr ifStmt() {
        auto s = std::make_unique<Stmt>(StmtKind::If, cur().loc);
        next();
        expect("(");
        s->expr = expression();
        expect(")");
        s->body = statement();
        if (cur().isIdent("else")) {
            next();
            s->elseBody = statement();
        }
        return s;
    }

    StmtPtr forStmt() {
        auto s = std::make_unique<Stmt>(StmtKind::For, cur().loc);
        next();
        expect("(");
        if (!cur().is(";")) {
            SourceLoc l = cur().loc;
            if (atDeclStart()) {
                s->init = declaration();
            } else {
                s->init = std::make_unique<Stmt>(StmtKind::Expr, l);
                s->init->expr = expression();
            }
        }
        expect(";");
        if (!cur().is(";")) s->expr = expression();
        expect(";");
        if (!cur().is(")")) s->step = expression();
        expect(")");
        s->body = statement();
        return s;
    }

    // ---- expressions -----------------------------------------------------------------
    ExprPtr expression() { return assignment(); }

    ExprPtr assignment() {
        Depth depth(*this);
        ExprPtr lhs = ternary();
        static const char* const ops[] = {"=", "+=", "-=", "*=", "/="};
        for (const char* op : ops) {
            if (cur().is(op)) {
                auto e = std::make_unique<Expr>(ExprKind::Assign, cur().loc);
                e->text = op;
                next();
                e->args.push_back(std::move(lhs));
                e->args.push_back(assignment());
                return e;
            }
        }
        return lhs;
    }

    ExprPtr ternary() {
        ExprPtr c = binary(0);
        if (!cur().is("?")) return c;
        auto e = std::make_unique<Expr>(ExprKind::Ternary, cur().loc);
        next();
        e->args.push_back(std::move(c));
        e->args.push_back(assignment());
        expect(":");
        Depth depth(*this);
        e->args.push_back(ternary());
        return e;
    }

    ExprPtr binary(int level) {
        static const std::vector<std::vector<const char*>> levels = {
            {"||"}, {"&&"}, {"==", "!="}, {"<", ">", "<=", ">="}, {"+", "-"},
            {"*", "/"}, {"^"}, {"."}};
        if (level == static_cast<int>(levels.size())) return unary();
        ExprPtr lhs = binary(level + 1);
        for (;;) {
            const char* found = nullptr;
            for (const char* op : levels[level])
                if (cur().is(op)) found = op;
            if (!found) return lhs;
            auto e = std::make_unique<Expr>(ExprKind::Binary, cur().loc);
            e->text = found;
            next();
            e->args.push_back(std::move(lhs));
            e->args.push_back(binary(level + 1));
            lhs = std::move(e);
        }
    }

    ExprPtr unary() {
        Depth depth(*this);
        if (cur().is("-") || cur().is("!") || cur().is("+")) {
            auto e = std::make_unique<Expr>(ExprKind::Unary, cur().loc);
            e->text = cur().text;
            next();
            e->args.push_back(unary());
            if (e->text == "+") return std::move(e->args[0]);
            return e;
        }
        if (atTypeName() && !cur().isIdent("void")) {
            // typecast: type ["space"] expr
            auto e = std::make_unique<Expr>(ExprKind::Cast, cur().loc);
            e->castType = TypeSpec(baseTypeFromName(cur().text));
            next();
            if (cur().kind == TokKind::String) {
                e->text = cur().text;
                next();
            }
            e->args.push_back(unary());
            return e;
        }
        return postfix(primary());
    }

    ExprPtr postfix(ExprPtr e) {
        while (cur().is("[")) {
            auto ix = std::make_unique<Expr>(ExprKind::Index, cur().loc);
            next();
            ix->args.push_back(std::move(e));
            ix->args.push_back(expression());
            expect("]");
            e = std::move(ix);
        }
        return e;
    }

    ExprPtr primary() {
        const Token& t = cur();
        if (t.kind == TokKind::Number) {
            auto e = std::make_unique<Expr>(ExprKind::Number, t.loc);
            e->number = t.number;
            e->text = t.text;
            next();
            return e;
        }
        if (t.kind == TokKind::String) {
            auto e = std::make_unique<Expr>(ExprKind::String, t.loc);
            e->text = t.text;
            next();
            return e;
        }
        ShaderKind sk;
        bool messageCall = t.kind == TokKind::Ident && isShaderKind(t.text, sk) &&
                           peek(1).is("(");  // surface("Kd", x), displacement(...)
        if (t.kind == TokKind::Ident && (!isKeyword(t.text) || messageCall)) {
            SourceLoc loc = t.loc;
            std::string name = t.text;
            next();
            if (!cur().is("(")) {
                auto e = std::make_unique<Expr>(ExprKind::Ident, loc);
                e->text = name;
                return e;
            }
            auto e = std::make_unique<Expr>(ExprKind::Call, loc);
            e->text = name;
            next();
            if (!cur().is(")")) {
                e->args.push_back(assignment());
                while (accept(",")) e->args.push_back(assignment());
            }
            expect(")");
            return e;
        }
        if (t.is("(")) {
            SourceLoc loc = t.loc;
            next();
            ExprPtr first = expression();
            if (accept(")")) return first;
            auto tup = std::make_unique<Expr>(ExprKind::Tuple, loc);
            tup->args.push_back(std::move(first));
            while (accept(",")) tup->args.push_back(assignment());
            expect(")");
            if (tup->args.size() != 3 && tup->args.size() != 16) {
                m_diag.error(loc, "a tuple needs 3 or 16 components, not " +
                                      std::to_string(tup->args.size()));
            }
            return tup;
        }
        fail("an expression");
    }

    const std::vector<Token>& m_toks;
    Program& m_prog;
    Diagnostics& m_diag;
    size_t m_pos = 0;
    int m_depth = 0;
    int m_gathers = 0;  // gather() loops so far (their variables' names)
};

}  // namespace

bool parseProgram(const std::vector<Token>& toks, Program& prog, Diagnostics& diag) {
    if (toks.empty() || toks.back().kind != TokKind::End) {
        std::vector<Token> copy = toks;
        copy.emplace_back();
        if (toks.size()) copy.back().loc = toks.back().loc;
        return Parser(copy, prog, diag).run();
    }
    return Parser(toks, prog, diag).run();
}

}  // namespace rsl
