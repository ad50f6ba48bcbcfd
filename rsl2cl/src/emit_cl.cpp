// emit_cl.cpp: the code generator driver: parameter layout, user functions and the
// shader function (its statements: emit_stmt.cpp).
#include "emit_cl.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "constfold.h"
#include "emit_internal.h"

namespace rsl {

std::string runtimeDir() {
#ifdef RSL2CL_RUNTIME_DIR
    return RSL2CL_RUNTIME_DIR;
#else
    return "rsl2cl/runtime";
#endif
}

namespace {
std::string slurpRuntime(const std::string& name) {
    std::ifstream in(runtimeDir() + "/" + name);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
}  // namespace

std::string runtimeSource() {
    std::string lib = slurpRuntime("rsl_abi.h") + "\n" + slurpRuntime("rsl_stdlib.clh");
    for (const char* header : {"rsl_derivatives.clh", "rsl_color_samples.clh"}) {
        const std::string inc = std::string("#include \"") + header + "\"";
        if (size_t at = lib.find(inc); at != std::string::npos)
            lib.replace(at, inc.size(), slurpRuntime(header));
    }
    return lib + "\n";
}

int slotsOf(BaseType b, int colorSlots) {
    switch (b) {
    case BaseType::Point:
    case BaseType::Vector:
    case BaseType::Normal: return 3;
    case BaseType::Color: return colorSlots;
    case BaseType::Matrix: return 16;
    default: return 1;
    }
}

void Emitter::collectCalls(const Expr& e) {
    if (e.kind == ExprKind::Call && e.function && !m_fnNames.count(e.function)) {
        const FunctionDecl* f = e.function;
        m_fnNames[f] = "";  // mark before recursing (RSL has no recursion; be safe)
        collectCallsStmt(*f->body);
        int idx = static_cast<int>(m_fnOrder.size());
        m_fnNames[f] = "rsl_" + m_sh.name + "_" + f->name + "_" + std::to_string(idx);
        m_fnOrder.push_back(f);  // callees first
    }
    for (const ExprPtr& a : e.args) collectCalls(*a);
    if (e.channel) collectCalls(*e.channel);
}

void Emitter::collectCallsStmt(const Stmt& s) {
    if (s.expr) collectCalls(*s.expr);
    for (const VarDecl& d : s.decls)
        if (d.init) collectCalls(*d.init);
    for (const StmtPtr& c : s.stmts) collectCallsStmt(*c);
    if (s.init) collectCallsStmt(*s.init);
    if (s.step) collectCalls(*s.step);
    for (const ExprPtr& a : s.args) collectCalls(*a);
    if (s.body) collectCallsStmt(*s.body);
    if (s.elseBody) collectCallsStmt(*s.elseBody);
}

void Emitter::layoutParams() {
    int offset = 0;
    for (const VarDecl& p : m_sh.params) {
        ParamSlot slot;
        slot.name = p.name;
        slot.type = p.type;
        slot.typeName = baseTypeName(p.type.base);
        slot.output = p.output;
        int n = p.type.arraySize;
        if (n < 0) n = p.init && p.init->kind == ExprKind::Tuple ? int(p.init->args.size()) : 0;
        if (p.type.isArray() && n <= 0)
            error(p.loc, "array parameter '" + p.name + "' needs a size or a default");
        slot.arraySize = p.type.isArray() ? n : 0;
        slot.type.arraySize = slot.arraySize;
        int elem = slots(p.type.base);
        slot.size = elem * (p.type.isArray() ? std::max(n, 0) : 1);
        slot.offset = offset;
        offset += slot.size;
        slot.defaults.assign(slot.size, 0.0f);
        ConstValue cv;
        // A default written in a coordinate system other than "shader" (which the host
        // converts) is computed by the generated code: "object", "camera" and the like
        // are known only where the shader runs.
        const bool spacedDefault = p.init && evalConst(*p.init, cv) &&
                                   !cv.space.empty() && cv.space != "shader" &&
                                   cv.space != "current" &&
                                   p.type.base != BaseType::Color;
        if (p.init && !spacedDefault && evalConst(*p.init, cv)) {
            slot.space = cv.space;
            if (p.type.base == BaseType::String) {
                slot.stringDefaults.push_back(cv.str);
                if (slot.size > 0) slot.defaults[0] = float(stringId(cv.str));
            } else {
                size_t total = size_t(slot.size);
                // a float default of a triple/matrix fills (matrix: diagonal)
                if (cv.values.size() == 1 && elem > 1) {
                    for (size_t i = 0; i < total; ++i)
                        slot.defaults[i] = elem == 16 ? ((i % 16) % 5 == 0 ? float(cv.values[0]) : 0.0f)
                                                      : float(cv.values[0]);
                } else {
                    for (size_t i = 0; i < total && i < cv.values.size(); ++i)
                        slot.defaults[i] = float(cv.values[i]);
                    // a colour written in another space ("hsv"...): its RGB value
                    // (each element's RGB in its first three slots)
                    if (p.type.base == BaseType::Color) {
                        std::fill(slot.defaults.begin(), slot.defaults.end(), 0.0f);
                        for (size_t i = 0, o = 0;
                             i + 3 <= cv.values.size() && o + 3 <= total;
                             i += 3, o += size_t(elem)) {
                            double c[3] = {cv.values[i], cv.values[i + 1], cv.values[i + 2]};
                            colorSpaceToRgb(cv.space, c);
                            for (int k = 0; k < 3; ++k)
                                slot.defaults[o + size_t(k)] = float(c[k]);
                        }
                        slot.rgbDefault = true;
                    }
                }
            }
        } else if (p.init) {
            slot.constantDefault = false;
            if (slot.size > 0) slot.defaults[0] = std::nanf("");
        }
        if (slot.output && m_sh.kind != ShaderKind::Light) {
            if (m_out.outputFloats + slot.size <= 32) {  // RSL_MAX_OUTPUT_FLOATS
                slot.outputOffset = m_out.outputFloats;
                m_out.outputFloats += slot.size;
            } else {
                m_diag.warning(p.loc, "output parameter '" + p.name + "' does not fit in " +
                                          "RslEval::outputs (32 floats): not written back");
            }
        }
        m_out.params.push_back(slot);
    }
    m_out.paramFloats = offset;
    m_out.spaceOffset = offset;
}

void Emitter::writeOutputs() {
    if (m_sh.kind == ShaderKind::Imager) line("RSL_CW(g->Ol) = _g_alpha;");
    for (size_t i = 0; i < m_sh.params.size() && i < m_out.params.size(); ++i) {
        const ParamSlot& slot = m_out.params[i];
        if (slot.outputOffset < 0) continue;
        std::string name = "p_" + slot.name, o = std::to_string(slot.outputOffset);
        int elem = slots(slot.type.base);
        auto one = [&](const std::string& v, const std::string& off) {
            if (slot.type.isColor())
                return "for (int _k = 0; _k < " + std::to_string(elem) +
                       "; ++_k) ev->outputs[" + off + " + _k] = rsl_comp(" + v + ", _k);";
            if (elem == 3)
                return "ev->outputs[" + off + "] = " + v + ".x; ev->outputs[" + off + " + 1] = " + v +
                       ".y; ev->outputs[" + off + " + 2] = " + v + ".z;";
            if (elem == 16)
                return "for (int _k = 0; _k < 16; ++_k) ev->outputs[" + off +
                       " + _k] = rsl_mget(" + v + ", _k / 4, _k % 4);";
            return "ev->outputs[" + off + "] = (float)" + v + ";";
        };
        if (slot.arraySize > 0)
            line("for (int _i = 0; _i < " + std::to_string(slot.arraySize) + "; ++_i) { " +
                 one(name + "[_i]", o + " + " + std::to_string(elem) + " * _i") + " }");
        else
            line(one(name, o));
    }
}

static void collectDecls(const Stmt& s, std::set<const Symbol*>& out) {
    for (const VarDecl& d : s.decls)
        if (!d.isExtern && d.symbol) out.insert(d.symbol);
    for (const StmtPtr& c : s.stmts) collectDecls(*c, out);
    if (s.init) collectDecls(*s.init, out);
    if (s.body) collectDecls(*s.body, out);
    if (s.elseBody) collectDecls(*s.elseBody, out);
}

void Emitter::emitFunction(const FunctionDecl& f, bool prototypeOnly) {
    std::string sig = std::string("static ") + clType(f.returnType) + " " + m_fnNames[&f] +
                      "(RslGlobals* g, RslEval* ev, const RslSpaces* sp";
    m_pointerParams.clear();
    for (const VarDecl& p : f.params) {
        bool ptr = p.output || p.type.isArray();
        sig += std::string(", ") + clType(p.type) + (ptr ? "* v_" : " v_") + p.name;
        if (p.output && !p.type.isArray()) m_pointerParams.insert(p.symbol);
    }
    // the variables of enclosing scopes it reaches (extern), by address
    const std::vector<const Symbol*>& caps = m_captures[&f];
    for (size_t k = 0; k < caps.size(); ++k)
        sig += std::string(", ") + clType(caps[k]->type) + "* c" + std::to_string(k) + "_" +
               caps[k]->name;
    if (coefFunction(&f))  // where its result's parts per light go (emit_coefs.cpp)
        sig += std::string(" RSL_COEF_ARG(") + clType(f.returnType) + "* _ret_light)";
    sig += ")";
    if (prototypeOnly) {
        m_body << sig << ";\n";
        return;
    }
    m_body << sig << " {\n";
    m_func = &f;
    m_fnLocals.clear();
    for (const VarDecl& p : f.params) m_fnLocals.insert(p.symbol);
    collectDecls(*f.body, m_fnLocals);
    m_indent = 1;
    m_usesSpaces = false;
    line("float _g_alpha = 0.0f, _g_dtime = 0.0f; float4 _g_dPdtime = rsl_f2v(0.0f);");
    line("(void)g; (void)ev; (void)sp; (void)_g_alpha; (void)_g_dtime; (void)_g_dPdtime;");
    for (const StmtPtr& s : f.body->stmts) stmt(*s);
    if (coefFunction(&f)) coefZero("_ret_light", f.returnType);  // fell off its end
    if (!f.returnType.isVoid()) line("return " + clZero(f.returnType) + ";");
    m_body << "}\n\n";
    if (m_usesSpaces) m_fnUsesSpaces.insert(&f);
    m_usesSpaces = false;
    m_func = nullptr;
    m_pointerParams.clear();
}

static bool hasLightStatement(const Stmt& s) {
    if (s.kind == StmtKind::Illuminate || s.kind == StmtKind::Solar) return true;
    for (const StmtPtr& c : s.stmts)
        if (hasLightStatement(*c)) return true;
    if (s.body && hasLightStatement(*s.body)) return true;
    if (s.elseBody && hasLightStatement(*s.elseBody)) return true;
    return false;
}

std::string Emitter::blockRead(BaseType base, const std::string& off) const {
    if (base == BaseType::Color) return "rsl_paramc(params, " + off + ")";
    switch (slots(base)) {
    case 3: return "rsl_param3(params, " + off + ")";
    case 16: return "rsl_param16(params, " + off + ")";
    default:
        return base == BaseType::String ? "(int)params[" + off + "]" : "params[" + off + "]";
    }
}

void Emitter::emitParamReads(bool computedDefaults) {
    for (size_t i = 0; i < m_sh.params.size(); ++i) {
        const VarDecl& p = m_sh.params[i];
        const ParamSlot& slot = m_out.params[i];
        std::string name = "p_" + p.name, o = std::to_string(slot.offset);
        if (slot.arraySize > 0) {
            line(std::string(clType(p.type)) + " " + name + "[" + std::to_string(slot.arraySize) + "];");
            line("for (int _i = 0; _i < " + std::to_string(slot.arraySize) + "; ++_i) " +
                 name + "[_i] = " +
                 blockRead(p.type.base,
                           o + " + " + std::to_string(slots(p.type.base)) + " * _i") +
                 ";");
            continue;
        }
        line(std::string(clType(p.type)) + " " + name + " = " + blockRead(p.type.base, o) + ";");
        if (computedDefaults && !slot.constantDefault && p.init)
            line("if (isnan(params[" + o + "])) " + name + " = " + exprAs(*p.init, p.type) + ";");
    }
}

// The instance's uniform work: the hoisted declarations computed from the parameters
// and stored after the space matrices, where the shader body reads them.
void Emitter::emitPrepare() {
    if (m_hoist.floats == 0) return;
    m_body << "void " << m_out.prepFunction
           << "(__global float* params, __global const float* scene) {\n";
    m_indent = 1;
    std::string so = std::to_string(m_out.spaceOffset);
    line("RslSpaces _sp; _sp.spaces = params + " + so + "; _sp.scene = scene;");
    line("const RslSpaces* sp = &_sp; (void)sp;");
    emitParamReads(false);
    for (const VarDecl* d : m_hoist.decls) {
        std::string name = "v_" + d->name;
        std::string off = std::to_string(m_out.prepOffset + m_hoist.slot.at(d));
        line(std::string(clType(d->type)) + " " + name + " = " + exprAs(*d->init, d->type) + ";");
        if (d->type.isColor()) {
            line("for (int _k = 0; _k < " + std::to_string(m_colorSlots) +
                 "; ++_k) params[" + off + " + _k] = rsl_comp(" + name + ", _k);");
            continue;
        }
        switch (slots(d->type.base)) {
        case 3:
            line("params[" + off + "] = " + name + ".x; params[" + off + " + 1] = " + name +
                 ".y; params[" + off + " + 2] = " + name + ".z;");
            break;
        case 16:
            line("for (int _k = 0; _k < 16; ++_k) params[" + off + " + _k] = rsl_mget(" + name +
                 ", _k / 4, _k % 4);");
            break;
        default: line("params[" + off + "] = " + name + ";");
        }
    }
    for (const Stmt* s : m_hoist.cones)
        line("params[" + std::to_string(m_out.prepOffset + m_hoist.coneSlot.at(s)) +
             "] = rsl_cone_cos(" + exprAs(*coneAngle(*s), BaseType::Float) + ");");
    m_body << "}\n";
}

// The cosine a cone statement's test compares with (rsl_cone_cos): prepared once per
// instance, folded here for a literal angle, else computed where the statement runs
// (where PoCL computed cos(angle) for every light at every point).
std::string Emitter::coneCos(const Stmt& s) {
    const Expr& angle = *coneAngle(s);
    if (auto h = m_hoist.coneSlot.find(&s); h != m_hoist.coneSlot.end() && !m_func)
        return "params[" + std::to_string(m_out.prepOffset + h->second) + "]";
    if (angle.kind == ExprKind::Number) {
        const float a = float(angle.number);
        const float c = a >= float(M_PI) ? -2.0f : std::cos(a) - 1e-6f;
        return clNumber(c);
    }
    return "rsl_cone_cos(" + exprAs(angle, BaseType::Float) + ")";
}

// The directive that opens a shader's use of per-point parameters (rsl_abi.h, PER-POINT
// PARAMETERS): surfaces take them in scenes that have them, displacements where the
// renderer also says some displacement shader does; other kinds never (null).
const char* Emitter::pointParamsGuard() const {
    return m_sh.kind == ShaderKind::Surface ? "#ifdef RSL_MAX_PARAM_PRIMVARS"
           : m_sh.kind == ShaderKind::Displacement
               ? "#if defined(RSL_MAX_PARAM_PRIMVARS) && "
                 "defined(RSL_DISPLACEMENT_PRIMVARS)"
               : nullptr;
}

// A surface or displacement instance whose primitives give some parameters per vertex:
// the renderer puts the values interpolated at the point in g->pv_value, keyed by the
// parameter's offset in the block (pv_slot for the surface, pv_dslot for the
// displacement); they replace what was read from the block.
void Emitter::emitPointParams() {
    const char* guard = pointParamsGuard();
    if (!guard) return;
    std::string cases;
    for (size_t i = 0; i < m_sh.params.size(); ++i) {
        const VarDecl& p = m_sh.params[i];
        const ParamSlot& slot = m_out.params[i];
        const BaseType b = p.type.base;
        if (slot.arraySize > 0 || b == BaseType::String || b == BaseType::Matrix)
            continue;
        // (a colour of more than three channels takes several entries: rsl_pv_color)
        const std::string v = "g->pv_value[_k]";
        cases += "case " + std::to_string(slot.offset) + ": p_" + p.name + " = " +
                 (b == BaseType::Float ? v + ".x"
                  : p.type.isColor()   ? std::string("rsl_pv_color(g->pv_value, _k)")
                                       : v) +
                 "; break; ";
    }
    if (cases.empty()) return;
    const char* slots = m_sh.kind == ShaderKind::Surface ? "g->pv_slot" : "g->pv_dslot";
    line(guard);
    line(std::string("for (int _k = 0; _k < g->pv_count; ++_k) switch (") + slots +
         "[_k]) { " + cases + "default: break; }");
    line("#endif");
}

void Emitter::emitShader() {
    bool light = m_sh.kind == ShaderKind::Light;
    std::string fn = m_out.functionName;
    if (light)
        m_body << "RSL_LIGHT_FUNCTION void " << fn << "(RslGlobals* g, RSL_LIGHT_PARAMS params) {\n";
    else
        m_body << "RSL_SHADER_FUNCTION void " << fn << "(RslGlobals* g, __global const float* params, RslEval* ev) {\n";
    m_indent = 1;
    if (light) {
        line("RslEval _ev; _ev.deriv = 0; _ev.tex = g->texctx; _ev.mode_light = -1; _ev.mode_trace = -1; _ev.trace_count = 0;");
        line("RslEval* ev = &_ev;");
        line("g->Cl = rsl_f2c(0.0f);");
    } else {
        line("ev->trace_count = 0;");
        if (m_coefs) coefZero("ev->Ci_light", BaseType::Color);
    }
    line("float _g_alpha = 0.0f, _g_dtime = 0.0f; float4 _g_dPdtime = rsl_f2v(0.0f);");
    line("(void)params; (void)_g_alpha; (void)_g_dtime; (void)_g_dPdtime;");
    if (m_sh.kind == ShaderKind::Imager)
        line("_g_alpha = RSL_CW(g->Ol); /* rsl_abi.h, IMAGER */");
    // the spaces are read only when used: insert them here once the body is emitted
    std::string head = m_body.str();
    m_body.str("");
    m_usesSpaces = false;
    emitParamReads(true);
    emitPointParams();
    for (const StmtPtr& s : m_sh.body->stmts) stmt(*s);
    if (!light) writeOutputs();
    m_body << "}\n";
    std::string body = m_body.str(), so = std::to_string(m_out.spaceOffset);
    m_body.str("");
    m_body << head;
    if (m_usesSpaces)
        line("RslSpaces _sp; _sp.spaces = params + " + so +
             "; _sp.scene = g->scene_params;");
    line(m_usesSpaces ? "const RslSpaces* sp = &_sp;" : "const RslSpaces* sp = 0; (void)sp;");
    m_body << body;
}

void Emitter::run() {
    const char* kind = shaderKindName(m_sh.kind);
    m_out.name = m_sh.name;
    m_out.kind = kind;
    m_out.functionName = std::string("rsl_") + kind + "_" + m_sh.name;
    m_out.ambientLight = m_sh.kind == ShaderKind::Light && !hasLightStatement(*m_sh.body);
    layoutParams();
    std::vector<bool> computed;  // (lights' too: their blocks are data, as surfaces')
    for (const ParamSlot& p : m_out.params) computed.push_back(!p.constantDefault);
    m_hoist = planHoisting(m_sh, computed, m_colorSlots);
    m_out.prepOffset = m_out.spaceOffset + kSpaceFloats;
    m_out.prepFloats = m_hoist.floats;
    if (m_hoist.floats > 0) m_out.prepFunction = std::string("rsl_prep_") + kind + "_" + m_sh.name;
    for (const VarDecl* d : m_hoist.decls) m_out.hoisted.push_back(d->name);
    for (const VarDecl& p : m_sh.params)
        if (p.init) collectCalls(*p.init);
    collectCallsStmt(*m_sh.body);
    m_captures = functionCaptures(m_fnOrder);
    for (const FunctionDecl* f : m_fnOrder) emitFunction(*f, true);
    if (!m_fnOrder.empty()) m_body << "\n";
    for (const FunctionDecl* f : m_fnOrder) emitFunction(*f, false);
    emitShader();
    emitPrepare();
}

EmittedShader emitOpenCL(const ShaderDecl& shader, const Program& prog, Diagnostics& diag,
                         int colorChannels) {
    EmittedShader out;
    int before = diag.errorCount();
    LightTaint taint;
    bool affine = shader.kind == ShaderKind::Light || checkAffine(shader, prog, diag, &taint);
    Emitter em(shader, prog, diag, out);
    em.m_colorSlots = std::max(3, colorChannels);
    if (affine && !taint.nonAffine && coefsSupported(shader, taint)) em.m_coefs = &taint;
    em.run();
    out.lightCoefs = em.m_coefs != nullptr;
    if (out.usesTrace)
        out.traceBound = em.m_traceRepeats
                             ? EmittedShader::kMaxTrace
                             : std::min(EmittedShader::kMaxTrace, em.traceRaysSoFar());
    std::ostringstream src;
    src << "/* Generated by rsl2cl from " << shader.loc.file << ": " << out.kind << " "
        << out.name << ".\n   Compile after rsl2cl/runtime/rsl_abi.h and rsl_stdlib.clh; "
        << "the contract is in rsl_abi.h.\n   Parameters (" << out.paramFloats
        << " floats, then the shader and object matrices and their inverses at "
        << out.spaceOffset << "):\n";
    for (const ParamSlot& p : out.params) {
        src << "     " << p.offset << ": " << (p.output ? "output " : "") << p.typeName
            << (p.arraySize ? "[" + std::to_string(p.arraySize) + "]" : "") << " " << p.name
            << (p.constantDefault ? "" : " (computed default when NaN)")
            << (p.outputOffset >= 0 ? " -> ev->outputs[" + std::to_string(p.outputOffset) + "]" : "")
            << "\n";
    }
    src << "   Services:" << (out.usesTrace ? " trace (at most " + std::to_string(out.traceBound) + " a run)" : std::string()) << (out.usesLighting ? " lighting" : "")
        << (out.usesTexture ? " texture" : "") << (out.usesDerivatives ? " derivatives" : "")
        << (out.ambientLight ? " ambient-light" : "")
        << (out.lightCoefs ? " light-coefficients" : "") << "\n*/\n";
    src << em.m_body.str();
    out.source = src.str();
    out.ok = affine && diag.errorCount() == before;
    return out;
}

}  // namespace rsl
