// gather.cpp: the gather() loop (PRMan's RSL, after RI 3.2) written as the loop the rest
// of the compiler already knows, so that no later stage needs a case of its own:
//
//   gather(category, P, dir, angle, samples, "surface:Ci", hitc, ...) hit else miss
// becomes
//   { point p = P; vector d0 = dir; float a = angle, n = samples, md = maxdist;
//     float b = __gather_begin(m, id), i, j;
//     for (i = 0; i < n; i += 1) {
//       vector d = __gather_dir(p, d0, a, i, b, id, cosine);
//       if (__gather_visible(p, d, md, i, b, id) == 0) { hitc = __gather_trace(p, d, md,
//       i, b, id);
//                                                         hit }
//       else miss } }
//
// Each of the loop's `samples` passes takes one of m directions (m: the literal
// `samples`, up to what an evaluation records; the emitter decides, emit_builtins.cpp),
// each direction two trace sites: a visibility ray (does it escape?) and a traced one
// (what it meets). Ci stays affine in both (rsl_abi.h TRACE): a missed ray brings back
// nothing, so the product of the two never arises, and the affine check (affine.cpp) lets
// the branch on the first through while it takes every variable the branches change as
// depending on the rays, and allows only += and -= on those declared outside.
#include "gather.h"

#include <cmath>

namespace rsl {
namespace {

ExprPtr ident(const SourceLoc& loc, const std::string& name) {
    auto e = std::make_unique<Expr>(ExprKind::Ident, loc);
    e->text = name;
    return e;
}
ExprPtr number(const SourceLoc& loc, double v) {
    auto e = std::make_unique<Expr>(ExprKind::Number, loc);
    e->number = v;
    return e;
}
ExprPtr call(const SourceLoc& loc, const std::string& name, std::vector<ExprPtr> args) {
    auto e = std::make_unique<Expr>(ExprKind::Call, loc);
    e->text = name;
    e->args = std::move(args);
    return e;
}
ExprPtr binary(const SourceLoc& loc, const std::string& op, ExprPtr a, ExprPtr b) {
    auto e = std::make_unique<Expr>(
        op == "=" || op == "+=" ? ExprKind::Assign : ExprKind::Binary, loc);
    e->text = op;
    e->args.push_back(std::move(a));
    e->args.push_back(std::move(b));
    return e;
}
StmtPtr exprStmt(ExprPtr e) {
    auto s = std::make_unique<Stmt>(StmtKind::Expr, e->loc);
    s->expr = std::move(e);
    return s;
}
StmtPtr decl(const SourceLoc& loc, BaseType type, const std::string& name, ExprPtr init) {
    auto s = std::make_unique<Stmt>(StmtKind::Decl, loc);
    VarDecl d;
    d.loc = loc;
    d.type = TypeSpec(type);
    d.name = name;
    d.init = std::move(init);
    s->decls.push_back(std::move(d));
    return s;
}
StmtPtr block(const SourceLoc& loc) {
    return std::make_unique<Stmt>(StmtKind::Block, loc);
}

// One gather() call being written as its loop: its options and outputs, read from its
// "name", value pairs, then its set-up declarations and its loop.
class GatherLoop {
public:
    GatherLoop(const SourceLoc& loc, int id, Diagnostics& diag)
        : m_loc(loc),
          m_id(id),
          m_pre("__g" + std::to_string(id) + "_"),
          m_diag(diag),
          m_maxdist(number(loc, 0.0)) {}

    void readParam(const Expr& key, ExprPtr& value);
    // The loop's inputs, each evaluated once (P, dir, angle, samples, maxdist), and its
    // begin: `wanted` directions a shading sample
    void declare(Stmt& out, std::vector<ExprPtr>& args, int wanted);
    StmtPtr loop(StmtPtr hit, StmtPtr miss);

private:
    ExprPtr v(const char* n) const { return ident(m_loc, m_pre + n); }
    // a pass's ray at its trace site: (p, d, maxdist, pass, base, id, samples)
    std::vector<ExprPtr> siteArgs() const {
        std::vector<ExprPtr> a;
        for (const char* n : {"p", "d", "md", "i", "b"}) a.push_back(v(n));
        a.push_back(number(m_loc, m_id));
        a.push_back(v("n"));
        return a;
    }
    StmtPtr branch(StmtPtr hit, StmtPtr miss);

    const SourceLoc& m_loc;
    const int m_id;
    const std::string m_pre;  // the loop's variables' prefix
    Diagnostics& m_diag;
    ExprPtr m_maxdist;
    int m_cosine = 1;
    // a direction's rays: its visibility ray, then a traced one for "surface:Ci" and a
    // distance ray for "ray:length" when asked for
    bool m_traced = false, m_lengths = false;
    std::vector<std::pair<ExprPtr, ExprPtr>> m_outputs;  // (variable, value) on a hit
    // "ray:direction", "ray:origin": set in both branches
    std::vector<std::pair<ExprPtr, std::string>> m_both;
};

void GatherLoop::readParam(const Expr& key, ExprPtr& value) {
    if (key.kind != ExprKind::String) {
        m_diag.error(key.loc, "gather(): a parameter name must be a string literal");
        return;
    }
    const std::string& k = key.text;
    if (k == "maxdist")
        m_maxdist = std::move(value);
    else if (k == "distribution") {
        const Expr& d = *value;
        if (d.kind == ExprKind::String && (d.text == "uniform" || d.text == "cosine"))
            m_cosine = d.text == "cosine";
        else
            m_diag.warning(d.loc,
                           "gather(): distribution must be \"uniform\" or \"cosine\"; "
                           "\"cosine\" taken");
    } else if (k == "surface:Ci" || k == "ray:length") {
        m_lengths |= k == "ray:length";
        m_traced |= k == "surface:Ci";
        m_outputs.push_back(
            {std::move(value),
             call(m_loc, k == "ray:length" ? "__gather_length" : "__gather_trace",
                  siteArgs())});
    } else if (k == "primitive:P") {
        // where the ray met the surface: its origin plus its direction times its
        // distance ray's length (affine in what the ray brings back)
        m_lengths = true;
        m_outputs.push_back({std::move(value),
                             binary(m_loc, "+", v("p"),
                                    binary(m_loc, "*", v("d"),
                                           call(m_loc, "__gather_length", siteArgs())))});
    } else if (k == "ray:direction" || k == "ray:origin")
        m_both.push_back({std::move(value), k == "ray:direction" ? "d" : "p"});
    else if (k == "bias" || k == "label" || k == "subset" || k == "samplebase" ||
             k == "hitmode" || k == "hitsides" || k == "othreshold" || k == "volumes")
        return;  // (robust offsets replace the bias; the rest do not apply)
    else
        m_diag.error(key.loc,
                     "gather(): \"" + k +
                         "\" is not supported (outputs: \"surface:Ci\", \"ray:length\", "
                         "\"primitive:P\", \"ray:direction\", \"ray:origin\"; inputs: "
                         "\"maxdist\", "
                         "\"distribution\")");
}

void GatherLoop::declare(Stmt& out, std::vector<ExprPtr>& args, int wanted) {
    out.stmts.push_back(decl(m_loc, BaseType::Point, m_pre + "p", std::move(args[1])));
    out.stmts.push_back(decl(m_loc, BaseType::Vector, m_pre + "d0", std::move(args[2])));
    out.stmts.push_back(decl(m_loc, BaseType::Float, m_pre + "a", std::move(args[3])));
    out.stmts.push_back(decl(m_loc, BaseType::Float, m_pre + "n", std::move(args[4])));
    out.stmts.push_back(decl(m_loc, BaseType::Float, m_pre + "md", std::move(m_maxdist)));
    std::vector<ExprPtr> a;
    for (double x : {double(wanted), double(m_id), double(m_traced), double(m_lengths)})
        a.push_back(number(m_loc, x));
    out.stmts.push_back(decl(m_loc, BaseType::Float, m_pre + "b",
                             call(m_loc, "__gather_begin", std::move(a))));
    out.stmts.push_back(decl(m_loc, BaseType::Float, m_pre + "i", nullptr));
}

StmtPtr GatherLoop::loop(StmtPtr hit, StmtPtr miss) {
    auto loop = std::make_unique<Stmt>(StmtKind::For, m_loc);
    loop->init = exprStmt(binary(m_loc, "=", v("i"), number(m_loc, 0)));
    loop->expr = binary(m_loc, "<", v("i"), v("n"));
    loop->step = binary(m_loc, "+=", v("i"), number(m_loc, 1));
    auto body = block(m_loc);
    std::vector<ExprPtr> a;
    for (const char* n : {"p", "d0", "a", "i", "b"}) a.push_back(v(n));
    a.push_back(number(m_loc, m_id));
    a.push_back(number(m_loc, m_cosine));
    a.push_back(v("n"));
    body->stmts.push_back(decl(m_loc, BaseType::Vector, m_pre + "d",
                               call(m_loc, "__gather_dir", std::move(a))));
    body->stmts.push_back(branch(std::move(hit), std::move(miss)));
    loop->body = std::move(body);
    return loop;
}

// if the visibility ray escapes nothing: the outputs and `hit`; else `miss`
StmtPtr GatherLoop::branch(StmtPtr hit, StmtPtr miss) {
    auto branch = std::make_unique<Stmt>(StmtKind::If, m_loc);
    branch->expr = binary(m_loc, "==", call(m_loc, "__gather_visible", siteArgs()),
                          number(m_loc, 0));
    auto hitBlock = block(m_loc), missBlock = block(m_loc);
    for (auto& [var, value] : m_outputs)
        hitBlock->stmts.push_back(
            exprStmt(binary(m_loc, "=", std::move(var), std::move(value))));
    for (auto& [var, what] : m_both) {
        // (the variable named twice: the same name again for the miss branch)
        if (var->kind != ExprKind::Ident) {
            m_diag.error(var->loc, "gather(): an output must be a variable");
            continue;
        }
        hitBlock->stmts.push_back(
            exprStmt(binary(m_loc, "=", ident(var->loc, var->text), v(what.c_str()))));
        missBlock->stmts.push_back(
            exprStmt(binary(m_loc, "=", std::move(var), v(what.c_str()))));
    }
    if (hit) hitBlock->stmts.push_back(std::move(hit));
    if (miss) missBlock->stmts.push_back(std::move(miss));
    branch->body = std::move(hitBlock);
    branch->elseBody = std::move(missBlock);
    return branch;
}

}  // namespace

StmtPtr desugarGather(const SourceLoc& loc, std::vector<ExprPtr> args, StmtPtr hit,
                      StmtPtr miss, int id, Diagnostics& diag) {
    auto out = block(loc);
    if (args.size() < 5 || (args.size() - 5) % 2 != 0) {
        diag.error(loc,
                   "gather() takes (category, P, dir, angle, samples) and then \"name\", "
                   "value pairs");
        return out;
    }
    if (args[0]->kind == ExprKind::String && !args[0]->text.empty() &&
        args[0]->text != "illuminance")
        diag.warning(args[0]->loc,
                     "gather(): category \"" + args[0]->text +
                         "\" is taken as \"illuminance\" (rays into the scene)");
    // the traced directions a shading sample: as many as samples (its literal, else the
    // most), up to what the emitter finds room for
    const int wanted =
        args[4]->kind == ExprKind::Number
            ? int(std::lround(std::fmax(1.0, std::fmin(args[4]->number, 64.0))))
            : 64;
    GatherLoop g(loc, id, diag);
    for (size_t i = 5; i + 1 < args.size(); i += 2) g.readParam(*args[i], args[i + 1]);
    g.declare(*out, args, wanted);
    out->stmts.push_back(g.loop(std::move(hit), std::move(miss)));
    return out;
}

}  // namespace rsl
