// emit_cl.h: the OpenCL C code generator of rsl2cl. One typed shader in, one OpenCL C
// function (rsl_surface_<name>, rsl_light_<name>, ...) plus its parameter layout out.
// The generated code includes nothing: compile it after rsl2cl/runtime/rsl_abi.h and
// rsl_stdlib.clh (see rsl_abi.h for the contract with the renderer).
#pragma once
#include <set>
#include <string>
#include <vector>

#include "ast.h"
#include "diagnostics.h"

namespace rsl {

// One parameter's place in the float block `params`.
struct ParamSlot {
    std::string name;
    TypeSpec type;           // element type + arraySize (resolved for unsized arrays)
    std::string typeName;    // "float", "color", "string", ...
    int arraySize = 0;       // 0: not an array
    int offset = 0;          // first float slot
    int size = 0;            // slots in all
    bool output = false;
    int outputOffset = -1;   // output params: first float of RslEval::outputs, else -1
    bool constantDefault = true;     // false: the host leaves slot `offset` NaN
    std::vector<float> defaults;     // `size` values (string ids for strings)
    std::vector<std::string> stringDefaults;  // string parameters: the text
    std::string space;       // space/colour space the default is written in ("" none)
    // a colour default written as RGB triples (not a float promoted to every channel):
    // a renderer shading in other colour channels converts it (rsl_abi.h, COLOURS)
    bool rgbDefault = false;
};

// The floats after each parameter block: four matrices (rsl_abi.h, RSL_SPACE_FLOATS).
constexpr int kSpaceFloats = 64;

struct EmittedShader {
    std::string name, kind, functionName, source;
    std::vector<ParamSlot> params;
    int paramFloats = 0;
    // The kSpaceFloats floats of the "shader" then "object" to current matrices, then
    // their inverses, follow the parameters at this offset (== paramFloats); the host
    // writes them (rsl_abi.h, SPACES).
    int spaceOffset = 0;
    int outputFloats = 0;       // RslEval::outputs used by output parameters
    // Uniform work done once per instance (hoist.h): prepFunction (empty: none) fills
    // prepFloats floats at prepOffset (after the space matrices) from the parameters;
    // the host runs it once per bound block before shading.
    int prepOffset = 0, prepFloats = 0;
    std::string prepFunction;
    std::vector<std::string> hoisted;  // the variables it computes, for --info
    bool usesTrace = false, usesDerivatives = false, usesTexture = false;
    // Reads "object" space (or a space named at run time, which may be it): each
    // primitive's own object space then needs an instance of its own (rsl_abi.h, SPACES).
    bool usesObjectSpace = false;
    // assigns Oi something other than Os or 1: it may let rays through where Os is 1
    bool writesOpacity = false;
    // Reads "screen", "raster", "NDC", a named coordinate system or a space named at run
    // time: the renderer's table of those spaces (rsl_abi.h, SPACES)
    bool usesSpaceTable = false;
    std::vector<std::string> namedSpaces;  // the names of the last kind it uses
    // The most trace() calls one evaluation can make: one per call site in the shader's
    // body outside loops; kMaxTrace (RSL_MAX_TRACE's default) when a call may repeat (in
    // a loop, an illuminance loop or a user function). The renderer sizes its spawned
    // rays by it (rsl_abi.h RSL_MAX_TRACE).
    int traceBound = 0;
    static constexpr int kMaxTrace = 8;
    bool usesRandom = false;  // calls random(): with trace(), rays in sampled directions
    // calls occlusion(): rays that only ask whether they escape (rsl_abi.h TRACE)
    bool usesVisibility = false;
    bool usesLighting = false;  // illuminance, diffuse, specular, phong, ambient
    bool ambientLight = false;  // a light shader with no illuminate/solar
    // A surface whose base evaluation also gives Ci's coefficient of every light's Cl
    // (RslEval::Ci_light, rsl_abi.h LIGHT COEFFICIENTS), so the renderer needs no
    // evaluation per light (emit_coefs.cpp).
    bool lightCoefs = false;
    bool ok = false;            // false when errors were reported
    std::vector<std::string> strings;  // string literals used (id = stringId(text))
};

// The id a string has in generated code and parameter blocks (see rsl_abi.h).
int stringId(const std::string& s);

// Generates OpenCL C for `shader` (of prog, already type-checked without errors).
// Errors (non-affine Ci, unsupported constructs) and warnings go to diag.
// colorChannels: the renderer's colour channels n (rsl_abi.h, COLOURS); a colour takes
// max(3, n) parameter slots.
EmittedShader emitOpenCL(const ShaderDecl& shader, const Program& prog, Diagnostics& diag,
                         int colorChannels = 3);

// What depends on the lights' Cl in an affine shader (affine.cpp).
struct LightTaint {
    std::set<const Symbol*> symbols;  // variables (and Ci) whose value depends on some Cl
    std::set<const FunctionDecl*> functions;  // user functions returning such values
    // Ci depends on some Cl otherwise than affinely (a light's luminance, one channel
    // of it, a test on it): no light coefficients; each light is evaluated on its own
    // (its light mode), and its shadow ray scales that light's whole part (a warning)
    bool nonAffine = false;
};

// Static affinity check of Ci in trace() results and light Cl (affine.cpp); reports
// errors to diag and returns false when the shader is not affine in trace() results (or
// Oi depends on either). Not affine in Cl alone is a warning (LightTaint::nonAffine).
// *taint (optional): what depends on the lights.
bool checkAffine(const ShaderDecl& shader, const Program& prog, Diagnostics& diag,
                 LightTaint* taint = nullptr);

// Whether a surface's light coefficients are carried (EmittedShader::lightCoefs, without
// generating code); *why: the first reason they are not ("file:line:col: ...").
bool lightCoefsSupported(const ShaderDecl& shader, std::string* why);

// Directory of rsl_abi.h and rsl_stdlib.clh in the source tree (for tests/tools).
std::string runtimeDir();
// rsl_abi.h then rsl_stdlib.clh with the runtime files it includes inlined: what generated
// code compiles after, as one text (for tests/tools that build it themselves).
std::string runtimeSource();

}  // namespace rsl
