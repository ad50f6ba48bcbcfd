// emit_trace_builtins.cpp: OpenCL C for the builtins that trace rays: their trace sites
// (rsl_abi.h TRACE), occlusion() and indirectdiffuse(), and the calls gather() loops are
// written with (gather.cpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "emit_internal.h"

namespace rsl {

// A call that asks for rays (rsl_abi.h TRACE): its site is counted once per evaluation
// unless it may run more than once (in a function, a loop or a light loop).
void Emitter::traceSite(const Expr& e, int rays) {
    m_out.usesTrace = true;
    if (m_func || !m_loops.empty() || !m_lightVars.empty())
        m_traceRepeats = true;
    else
        m_traceSites[&e] = rays;
}

int Emitter::traceRaysSoFar() const {
    int rays = 0;
    for (const auto& [site, n] : m_traceSites) rays += n;
    return rays;
}

// occlusion(P, N, samples, ...) and indirectdiffuse(P, N, samples, ...): rays in
// cosine-distributed directions about N, spread over the hemisphere by a lattice rotated
// by two random sites: as many as a literal `samples` asks for, up to the rays an
// evaluation records (RSL_MAX_TRACE, with the other calls' rays), else one; the pixel's
// samples add up to the hemisphere's average either way. indirectdiffuse is the mean
// radiance they meet; occlusion is 1 - the fraction of them that escape within
// "maxdist", its rays visibility rays. "coneangle" narrows the hemisphere to a cone about
// N (cosine-distributed within it).
std::string Emitter::hemisphereCall(const Expr& e) {
    const std::string& n = e.text;
    int rays = 1;
    const Expr& samples = *e.args[2];
    if (samples.kind == ExprKind::Number && !m_func && m_loops.empty() &&
        m_lightVars.empty())
        rays = std::clamp(int(std::lround(samples.number)), 1,
                          std::max(1, EmittedShader::kMaxTrace - traceRaysSoFar()));
    traceSite(e, rays);
    m_out.usesRandom = true;
    std::string maxdist = "0.0f";  // (0: no limit)
    std::string cone = "1.0f";     // sin^2 of the cone's half-angle (1: the hemisphere)
    for (size_t i = 3; i + 1 < e.args.size(); i += 2) {
        const Expr& key = *e.args[i];
        if (key.kind != ExprKind::String) {
            m_diag.warning(key.loc,
                           n + "(): a parameter name must be a string literal; ignored");
            continue;
        }
        if (key.text == "maxdist")
            maxdist = exprAs(*e.args[i + 1], BaseType::Float);
        else if (key.text == "coneangle")
            cone = "rsl_cone_sin2(" + exprAs(*e.args[i + 1], BaseType::Float) + ")";
        else if (key.text != "samples" && key.text != "bias" && key.text != "adaptive" &&
                 key.text != "maxvariation" && key.text != "hitmode" &&
                 key.text != "label" && key.text != "subset")
            m_diag.warning(key.loc, n + "(): parameter \"" + key.text +
                                        "\" is not supported; ignored");
    }
    const int site = m_randomSite;
    m_randomSite += 2;
    const std::string args = "(ev, g, " + exprAs(*e.args[0], BaseType::Point) + ", " +
                             exprAs(*e.args[1], BaseType::Normal) + ", " +
                             std::to_string(site) + ", " + maxdist + ", " + cone + ", " +
                             std::to_string(rays) + ")";
    if (n == "indirectdiffuse") return "rsl_indirectdiffuse" + args;
    m_out.usesVisibility = true;
    return "rsl_occlusion" + args;
}

namespace {
int countCalls(const Expr& e, const std::string& name) {
    int n = e.kind == ExprKind::Call && e.text == name;
    for (const ExprPtr& a : e.args) n += countCalls(*a, name);
    return n;
}
int countCalls(const Stmt& s, const std::string& name) {
    int n = 0;
    if (s.expr) n += countCalls(*s.expr, name);
    if (s.step) n += countCalls(*s.step, name);
    for (const VarDecl& d : s.decls)
        if (d.init) n += countCalls(*d.init, name);
    for (const StmtPtr& c : s.stmts) n += countCalls(*c, name);
    for (const StmtPtr* c : {&s.body, &s.elseBody, &s.init})
        if (*c) n += countCalls(**c, name);
    return n;
}
}  // namespace

// The gather() loop's calls (gather.cpp): __gather_begin reserves a trace site for each
// of at most M directions (a visibility ray), and one more each for a traced ray when
// "surface:Ci" is asked for and for a distance ray when "ray:length" is, M what it is
// given (a literal samples, else 64) up to what an evaluation records with the other
// calls' rays, keeping one direction for each gather after it (at least one); a shading
// sample traces m = min(samples, M) of them, and every pass k of the loop takes direction
// k mod m, its visibility ray at site base + 2 (k mod m) (3 (k mod m)) and its traced ray
// (and its distance ray) after it, so that the shader's own sums over `samples` passes
// stay as written.
std::string Emitter::gatherCall(const Expr& e) {
    const std::string& n = e.text;
    auto lit = [&](size_t i) { return int(std::lround(e.args[i]->number)); };
    auto A = [&](size_t i, BaseType t) { return exprAs(*e.args[i], t); };
    if (n == "__gather_begin") {
        // (the gathers after this one keep a direction each)
        const int id = lit(1), traced = lit(2), per = 1 + traced + lit(3);
        if (m_gathersLeft < 0) m_gathersLeft = countCalls(*m_sh.body, "__gather_begin");
        const int after = std::max(0, --m_gathersLeft);
        const int m = std::clamp(
            lit(0), 1,
            std::max(1, (EmittedShader::kMaxTrace - traceRaysSoFar()) / per - after));
        m_gather[id] = {m, m_randomSite, per, 1 + traced};
        m_randomSite += 2;
        traceSite(e, per * m);
        m_out.usesVisibility = true;
        m_out.usesRandom = true;
        return "(float)rsl_gather_begin(ev, " + std::to_string(per * m) + ")";
    }
    // (the passes' directions: samples, up to the sites reserved)
    const GatherSites& gs = m_gather[lit(5)];
    const std::string ms = "clamp((int)(" +
                           A(n == "__gather_dir" ? 7 : 6, BaseType::Float) + "), 1, " +
                           std::to_string(gs.most) + ")";
    if (n == "__gather_dir")
        return "rsl_gather_dir(g, " + A(1, BaseType::Vector) + ", " +
               A(2, BaseType::Float) + ", (int)(" + A(3, BaseType::Float) + ") % " + ms +
               ", " + ms + ", " + std::to_string(gs.randomSite) + ", " +
               std::to_string(lit(6)) + ")";
    // (p, d, maxdist, pass, base, id, samples): the pass's visibility ray (rsl_abi.h
    // TRACE: flag 1), its traced ray (0), or its distance ray (2: "ray:length")
    const int kind = n == "__gather_visible" ? 0 : n == "__gather_trace" ? 1 : 2;
    const int offset = kind == 2 ? gs.lengthOffset : kind;
    const std::string k = "(int)(" + A(4, BaseType::Float) + ") + " +
                          std::to_string(gs.per) + " * ((int)(" + A(3, BaseType::Float) +
                          ") % " + ms + ") + " + std::to_string(offset);
    const std::string site = "rsl_trace_site(ev, " + k + ", " + A(0, BaseType::Point) +
                             ", " + A(1, BaseType::Vector) + ", " +
                             (kind == 0   ? "1.0f"
                              : kind == 1 ? "0.0f"
                                          : "2.0f") +
                             ", " + A(2, BaseType::Float) + ")";
    return kind == 1 ? "rsl_f2c(" + site + ")" : site;
}

}  // namespace rsl
