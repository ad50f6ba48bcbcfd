// emit_internal.h: the Emitter shared by emit_cl.cpp (driver, statements),
// emit_expr.cpp (expressions) and emit_builtins.cpp (builtin calls).
#pragma once
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "builtins.h"
#include "emit_cl.h"
#include "call_graph.h"
#include "hoist.h"

namespace rsl {

// element C type: float, float4, rsl_color, RslMatrix, int
const char* clType(const TypeSpec& t);
std::string clZero(const TypeSpec& t);          // zero of the element type
std::string clNumber(double v);                 // 1.0f
int spaceIdOf(const std::string& name);         // RSL_SPACE_* value or -1
constexpr int kObjectSpaceId = 3;               // spaceIdOf("object")
constexpr int kScreenSpaceId = 5;  // spaceIdOf("screen"), then raster and NDC
int colorIdOf(const std::string& name);         // RSL_COLOR_* value or -1
int slotsOf(BaseType b, int colorSlots);        // float slots of one value in a block
// Light coefficients (emit_coefs.cpp): whether e depends on some light's Cl, and whether
// the shader's light-dependent values are all of the kinds the code generator carries.
bool lightDependent(const Expr& e, const LightTaint& t);
bool coefsSupported(const ShaderDecl& sh, const LightTaint& t, std::string* why = nullptr);

class Emitter {
public:
    Emitter(const ShaderDecl& sh, const Program& prog, Diagnostics& diag, EmittedShader& out)
        : m_sh(sh), m_prog(prog), m_diag(diag), m_out(out) {}
    void run();

    // ---- expressions (emit_expr.cpp) ----
    std::string expr(const Expr& e);
    std::string exprAs(const Expr& e, const TypeSpec& to);
    std::string tupleOf(const Expr& e);  // a Tuple's components as written (colours: not converted)
    // What a shader writes as RGB (a colour literal, a texel) in the renderer's colour
    // channels, and the ctransform that does the same; in an imager, which works on the
    // film's RGB, colours stay RGB (rsl_abi.h, COLOURS).
    bool rgbShader() const { return m_sh.kind == ShaderKind::Imager; }
    std::string rgbIn(const std::string& rgb) const {
        return (rgbShader() ? "rsl_c3(" : "rsl_rgb_color(") + rgb + ")";
    }
    int slots(BaseType b) const { return slotsOf(b, m_colorSlots); }
    const char* ctransformFn() const { return rgbShader() ? "rsl_ctransform_rgb(" : "rsl_ctransform("; }
    std::string coerce(const std::string& code, const TypeSpec& from, const TypeSpec& to);
    std::string binop(const std::string& op, const std::string& a, const TypeSpec& ta,
                      const std::string& b, const TypeSpec& tb, const SourceLoc& loc);
    std::string lvalue(const Expr& e);
    std::string varName(const Symbol* s);
    std::string userCall(const Expr& e);
    std::string stringLiteral(const std::string& s);
    // ---- builtins (emit_builtins.cpp) ----
    std::string builtin(const Expr& e);
    // A builtin call being emitted, with what its families read of its signature.
    struct BuiltinCall {
        const Expr& e;
        const BuiltinSig& sig;
        TypeSpec ret;
        std::string vf;     // the return's suffix of the runtime's names: _f, _v, _c
        std::string codes;  // the signature's argument codes, without & markers
        size_t count;       // the call's arguments
    };
    std::string arg(const BuiltinCall& c, size_t i);  // as its signature types it
    std::string intArg(const BuiltinCall& c, size_t i);
    // fn(its arguments [from, to))
    std::string callOf(const BuiltinCall& c, const std::string& fn, size_t from = 0,
                       size_t to = size_t(-1));
    std::string mathBuiltin(const BuiltinCall& c);
    std::string geometryBuiltin(const BuiltinCall& c);
    std::string componentOrStringBuiltin(const BuiltinCall& c);
    std::string shadingBuiltin(const BuiltinCall& c);
    std::string spaceArg(const Expr& e);
    std::string spaceOfName(const std::string& name);
    std::string colorSpaceArg(const Expr& e);
    std::string message(const Expr& e);  // lightsource(), attribute(), option(), ...
    std::string textureCall(const Expr& e, bool vret);  // texture, environment, shadow, bump
    std::string hemisphereCall(const Expr& e);          // occlusion, indirectdiffuse
    std::string gatherCall(const Expr& e);  // the gather() loop's (gather.cpp)
    void traceSite(const Expr& e,
                   int rays = 1);  // trace, occlusion, indirectdiffuse, transmission
    std::string textureInfo(const Expr& e);

    // ---- light coefficients (emit_coefs.cpp) ----
    std::string lin(const Expr& e, const std::string& k);  // light k's part of e ("": 0)
    std::string linAs(const Expr& e, const TypeSpec& to, const std::string& k);
    std::string coefName(const Symbol* s);  // the array of a variable's parts per light
    void coefDecl(const VarDecl& d);
    void coefAssign(const Expr& e);
    void coefLines(const std::vector<std::string>& lines);  // under #ifdef RSL_LIGHT_COEFS
    void coefZero(const std::string& array, const TypeSpec& type);  // every light's part 0
    std::string coefCallArg(const Expr& e);  // a light-dependent user call's extra argument
    void coefReturn(const Expr& e, const TypeSpec& type);
    void hoistOnce(const Expr& op);      // an impure operand into a temporary
    void hoistOperands(const Expr& e);   // impure operands the parts read, computed once
    void hoistAssign(const Expr& assign);
    bool coefFunction(const FunctionDecl* f) const {
        return m_coefs && f && m_coefs->functions.count(f);
    }
    bool coefTarget(const Expr& e) const {  // an assignment to a light-dependent variable
        return m_coefs && e.kind == ExprKind::Assign &&
               e.args[0]->kind == ExprKind::Ident && m_coefs->symbols.count(e.args[0]->symbol);
    }

    void error(const SourceLoc& loc, const std::string& msg) { m_diag.error(loc, msg); }

private:
    // ---- driver and statements (emit_cl.cpp) ----
    void collectFunctions(const Stmt& s);
    void collectCalls(const Expr& e);
    void collectCallsStmt(const Stmt& s);
    void layoutParams();
    void emitFunction(const FunctionDecl& f, bool prototypeOnly);
    void emitShader();
    void emitParamReads(bool computedDefaults);  // p_<name> locals from `params`
    void emitPrepare();  // the uniform work of one instance (hoist.h)
    std::string coneCos(const Stmt& s);  // a cone statement's cosine (rsl_cone_cos)
    void emitPointParams();  // per-point parameter values (rsl_abi.h, PER-POINT PARAMETERS)
    const char* pointParamsGuard() const;  // their #if line; null: the kind takes none
    std::string blockRead(BaseType base, const std::string& offset) const;
    void stmt(const Stmt& s);
    void exprStatement(const Expr& e);
    void loop(const Stmt& s);  // while, for
    void jump(const Stmt& s);  // break N, continue N
    void returnStatement(const Stmt& s);
    void decl(const VarDecl& d);
    void arrayAssign(const Expr& e);  // `a = b;` of whole arrays
    void lightLoop(const Stmt& s);
    void loopBody(const Stmt& body);  // a loop's body; its labels for break/continue N
    void loopEnd();
    std::string loopGuardCounter();  // declares a loop's pass counter (RSL_LOOP_GUARD)
    void writeOutputs();  // output parameters -> ev->outputs (shader body only)
    void line(const std::string& s) {
        for (const std::string& p : m_pre) m_body << std::string(2 * m_indent, ' ') << p << "\n";
        m_pre.clear();
        m_body << std::string(2 * m_indent, ' ') << s << "\n";
    }

public:
    const ShaderDecl& m_sh;
    const Program& m_prog;
    Diagnostics& m_diag;
    EmittedShader& m_out;
    std::ostringstream m_body;
    int m_indent = 1;
    int m_tmp = 0;
    int m_randomSite = 0;
    int m_colorSlots = 3;  // a colour's parameter slots: max(3, colour channels)
    const FunctionDecl* m_func = nullptr;                    // function being emitted
    std::map<const FunctionDecl*, std::string> m_fnNames;    // reachable user functions
    std::vector<const FunctionDecl*> m_fnOrder;
    std::set<const Symbol*> m_pointerParams;                 // output params: (*v_x)
    std::set<const Symbol*> m_fnLocals;  // symbols declared in the function being emitted
    FunctionCaptures m_captures;  // each function's variables of enclosing scopes (extern)
    std::string captureName(const Symbol* s);  // in the function being emitted, or ""
    std::string addressOf(const Symbol* s);    // what a call passes for a captured variable
    std::vector<std::string> m_pre;  // temporaries declared before the current line
    std::vector<std::string> m_lightVars;  // light index of each enclosing illuminance
    std::vector<std::string> m_lightRaw;   // ... and its light's unshadowed Cl
    const LightTaint* m_coefs = nullptr;   // emit light coefficients (emit_coefs.cpp)
    std::map<const Expr*, std::string> m_callCoefs;  // a user call's parts per light
    std::map<const Expr*, std::string> m_exprTemps;  // hoisted operands, this statement
    bool m_usesSpaces = false;  // the code being emitted uses sp (shader/object spaces)
    std::set<const FunctionDecl*> m_fnUsesSpaces;
    HoistPlan m_hoist;  // declarations computed once per instance
    std::vector<int> m_loops;  // ids of the enclosing loops, innermost last
    // Calls that ask for rays, met once per evaluation, and how many rays each asks for
    std::map<const Expr*, int> m_traceSites;
    struct GatherSites {
        // directions, their random site, sites each, the distance ray's among them
        int most = 1, randomSite = 0, per = 2, lengthOffset = 2;
    };
    std::map<int, GatherSites> m_gather;  // gather() id -> its trace sites
    int m_gathersLeft = -1;  // gather() loops not emitted yet (-1: not counted)
    int traceRaysSoFar() const;
    bool m_traceRepeats = false;         // a trace() call that may run more than once
    std::set<int> m_breakTargets, m_continueTargets;  // loops a break/continue N names
};

}  // namespace rsl
