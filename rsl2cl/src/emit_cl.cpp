// emit_cl.cpp: the code generator driver: parameter layout, user functions, shader
// function, statements and the light loops (illuminance, illuminate, solar).
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

void Emitter::decl(const VarDecl& d) {
    if (d.isExtern) return;
    std::string t = clType(d.type), name = "v_" + d.name;
    if (auto h = m_hoist.slot.find(&d); h != m_hoist.slot.end() && !m_func) {
        std::string once = blockRead(d.type.base, std::to_string(m_out.prepOffset + h->second));
        if (const char* guard = pointParamsGuard()) {
            // an instance whose parameters vary per point: the prepared value was made
            // from the block's values, not the point's, so compute it here instead
            line(guard);
            line(t + " " + name + " = g->pv_count > 0 ? " + exprAs(*d.init, d.type) + " : " +
                 once + ";");
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
        line("for (int _i = 0; _i < " + std::to_string(n) + "; ++_i) " + name + "[_i] = " +
             clZero(d.type) + ";");
        if (d.init) error(d.loc, "array initialisers other than {...} lists are not supported");
        return;
    }
    const bool coefs = m_coefs && m_coefs->symbols.count(d.symbol);
    if (coefs && d.init) hoistOperands(*d.init);
    line(t + " " + name + " = " + (d.init ? exprAs(*d.init, d.type) : clZero(d.type)) + ";");
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
    if (m_breakTargets.count(m_loops.back())) line("_brk" + std::to_string(m_loops.back()) + ": ;");
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
             (cone ? exprAs(*s.args[first + 1], BaseType::Vector) : "rsl_f2v(0.0f)") + ";");
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
        line("g->L = " + (s.args.size() == 2 ? "rsl_w0(" + exprAs(*s.args[0], BaseType::Vector) + ")"
                                              : std::string("rsl_f2v(0.0f)")) + ";");
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
    case StmtKind::Empty: break;
    case StmtKind::Expr:
        if (s.expr->kind == ExprKind::Assign && s.expr->text == "=" &&
            s.expr->args[0]->type.isArray()) {
            arrayAssign(*s.expr);
            break;
        }
        if (coefTarget(*s.expr)) hoistAssign(*s.expr);
        {
            // a builtin the renderer answers at compile time (an unknown lightsource() or
            // textureinfo() name is 0) leaves a bare constant: the OpenCL compiler would
            // warn "expression result unused" to the user
            const std::string code = expr(*s.expr);
            const bool constant = !code.empty() && code.find_first_not_of("0123456789.f-") ==
                                                       std::string::npos;
            line((constant ? "(void)" : "") + code + ";");
        }
        if (coefTarget(*s.expr)) coefAssign(*s.expr);
        m_exprTemps.clear();
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
    case StmtKind::While: {
        line("{");
        ++m_indent;
        const std::string passes = loopGuardCounter();
        line("while ((" + expr(*s.expr) + ") != 0.0f) {");
        ++m_indent;
        line("RSL_LOOP_GUARD(" + passes + ")");
        loopBody(*s.body);
        --m_indent;
        line("}");
        loopEnd();
        --m_indent;
        line("}");
        break;
    }
    case StmtKind::For: {
        line("{");
        ++m_indent;
        if (s.init) stmt(*s.init);
        const std::string passes = loopGuardCounter();
        line("for (; " + (s.expr ? "(" + expr(*s.expr) + ") != 0.0f" : std::string("1")) + "; " +
             (s.step ? expr(*s.step) : std::string()) + ") {");
        ++m_indent;
        line("RSL_LOOP_GUARD(" + passes + ")");
        loopBody(*s.body);
        --m_indent;
        line("}");
        loopEnd();
        --m_indent;
        line("}");
        break;
    }
    case StmtKind::Break:
    case StmtKind::Continue: {
        // break N / continue N leave or continue the N-th enclosing loop: a goto to the
        // label after that loop, or at the end of its body (where a for loop's step follows)
        int n = s.level;
        if (n < 1 || n > int(m_loops.size())) {
            error(s.loc, std::string(s.kind == StmtKind::Break ? "break" : "continue") + " " +
                             std::to_string(n) + " outside of " + std::to_string(n) +
                             " enclosing loop(s)");
            break;
        }
        if (n == 1) {
            line(s.kind == StmtKind::Break ? "break;" : "continue;");
            break;
        }
        int id = m_loops[m_loops.size() - size_t(n)];
        (s.kind == StmtKind::Break ? m_breakTargets : m_continueTargets).insert(id);
        line(std::string("goto ") + (s.kind == StmtKind::Break ? "_brk" : "_cont") +
             std::to_string(id) + ";");
        break;
    }
    case StmtKind::Return:
        if (m_func && s.expr && coefFunction(m_func)) coefReturn(*s.expr, m_func->returnType);
        else if (m_func && s.expr) line("return " + exprAs(*s.expr, m_func->returnType) + ";");
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
        break;
    case StmtKind::Illuminance:
    case StmtKind::Illuminate:
    case StmtKind::Solar: lightLoop(s); break;
    case StmtKind::Function: break;  // emitted before the shader when called
    }
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
