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
    const std::string pre = "__g" + std::to_string(id) + "_";
    auto v = [&](const char* n) { return ident(loc, pre + n); };
    // a pass's ray at its trace site: (p, d, maxdist, pass, base, id, samples)
    auto siteArgs = [&] {
        std::vector<ExprPtr> a;
        for (const char* n : {"p", "d", "md", "i", "b"}) a.push_back(v(n));
        a.push_back(number(loc, id));
        a.push_back(v("n"));
        return a;
    };
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
    ExprPtr maxdist = number(loc, 0.0);
    int cosine = 1;
    // a direction's rays: its visibility ray, then a traced one for "surface:Ci" and a
    // distance ray for "ray:length" when asked for
    bool traced = false, lengths = false;
    std::vector<std::pair<ExprPtr, ExprPtr>> outputs;  // (variable, value)
    std::vector<std::pair<ExprPtr, std::string>>
        both;  // "ray:direction", "ray:origin": both branches
    for (size_t i = 5; i + 1 < args.size(); i += 2) {
        const Expr& key = *args[i];
        if (key.kind != ExprKind::String) {
            diag.error(key.loc, "gather(): a parameter name must be a string literal");
            continue;
        }
        const std::string& k = key.text;
        if (k == "maxdist")
            maxdist = std::move(args[i + 1]);
        else if (k == "distribution") {
            const Expr& d = *args[i + 1];
            if (d.kind == ExprKind::String && (d.text == "uniform" || d.text == "cosine"))
                cosine = d.text == "cosine";
            else
                diag.warning(d.loc,
                             "gather(): distribution must be \"uniform\" or \"cosine\"; "
                             "\"cosine\" taken");
        } else if (k == "surface:Ci" || k == "ray:length") {
            lengths |= k == "ray:length";
            traced |= k == "surface:Ci";
            outputs.push_back(
                {std::move(args[i + 1]),
                 call(loc, k == "ray:length" ? "__gather_length" : "__gather_trace",
                      siteArgs())});
        } else if (k == "primitive:P") {
            // where the ray met the surface: its origin plus its direction times its
            // distance ray's length (affine in what the ray brings back)
            lengths = true;
            outputs.push_back({std::move(args[i + 1]),
                               binary(loc, "+", v("p"),
                                      binary(loc, "*", v("d"),
                                             call(loc, "__gather_length", siteArgs())))});
        } else if (k == "ray:direction" || k == "ray:origin")
            both.push_back({std::move(args[i + 1]), k == "ray:direction" ? "d" : "p"});
        else if (k == "bias" || k == "label" || k == "subset" || k == "samplebase" ||
                 k == "hitmode" || k == "hitsides" || k == "othreshold" || k == "volumes")
            continue;  // (robust offsets replace the bias; the rest do not apply)
        else
            diag.error(
                key.loc,
                "gather(): \"" + k +
                    "\" is not supported (outputs: \"surface:Ci\", \"ray:length\", "
                    "\"primitive:P\", \"ray:direction\", \"ray:origin\"; inputs: "
                    "\"maxdist\", "
                    "\"distribution\")");
    }
    out->stmts.push_back(decl(loc, BaseType::Point, pre + "p", std::move(args[1])));
    out->stmts.push_back(decl(loc, BaseType::Vector, pre + "d0", std::move(args[2])));
    out->stmts.push_back(decl(loc, BaseType::Float, pre + "a", std::move(args[3])));
    out->stmts.push_back(decl(loc, BaseType::Float, pre + "n", std::move(args[4])));
    out->stmts.push_back(decl(loc, BaseType::Float, pre + "md", std::move(maxdist)));
    {
        std::vector<ExprPtr> a;
        a.push_back(number(loc, wanted));
        a.push_back(number(loc, id));
        a.push_back(number(loc, traced));
        a.push_back(number(loc, lengths));
        out->stmts.push_back(decl(loc, BaseType::Float, pre + "b",
                                  call(loc, "__gather_begin", std::move(a))));
    }
    out->stmts.push_back(decl(loc, BaseType::Float, pre + "i", nullptr));

    auto loop = std::make_unique<Stmt>(StmtKind::For, loc);
    loop->init = exprStmt(binary(loc, "=", v("i"), number(loc, 0)));
    loop->expr = binary(loc, "<", v("i"), v("n"));
    loop->step = binary(loc, "+=", v("i"), number(loc, 1));
    auto body = block(loc);
    {
        std::vector<ExprPtr> a;
        a.push_back(v("p"));
        a.push_back(v("d0"));
        a.push_back(v("a"));
        a.push_back(v("i"));
        a.push_back(v("b"));
        a.push_back(number(loc, id));
        a.push_back(number(loc, cosine));
        a.push_back(v("n"));
        body->stmts.push_back(decl(loc, BaseType::Vector, pre + "d",
                                   call(loc, "__gather_dir", std::move(a))));
    }
    auto branch = std::make_unique<Stmt>(StmtKind::If, loc);
    {
        branch->expr =
            binary(loc, "==", call(loc, "__gather_visible", siteArgs()), number(loc, 0));
    }
    auto hitBlock = block(loc), missBlock = block(loc);
    for (auto& [var, value] : outputs)
        hitBlock->stmts.push_back(
            exprStmt(binary(loc, "=", std::move(var), std::move(value))));
    for (auto& [var, what] : both) {
        // (the variable named twice: the same name again for the miss branch)
        if (var->kind != ExprKind::Ident) {
            diag.error(var->loc, "gather(): an output must be a variable");
            continue;
        }
        hitBlock->stmts.push_back(
            exprStmt(binary(loc, "=", ident(var->loc, var->text), v(what.c_str()))));
        missBlock->stmts.push_back(
            exprStmt(binary(loc, "=", std::move(var), v(what.c_str()))));
    }
    if (hit) hitBlock->stmts.push_back(std::move(hit));
    if (miss) missBlock->stmts.push_back(std::move(miss));
    branch->body = std::move(hitBlock);
    branch->elseBody = std::move(missBlock);
    body->stmts.push_back(std::move(branch));
    loop->body = std::move(body);
    out->stmts.push_back(std::move(loop));
    return out;
}

}  // namespace rsl
