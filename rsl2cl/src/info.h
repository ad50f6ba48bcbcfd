// info.h: per-shader metadata (like sloinfo): parameters, globals read and written,
// services used; for the scheduler, the host and `rsl2cl --info`.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "ast.h"
#include "constfold.h"

namespace rsl {

struct ParamInfo {
    std::string name;
    TypeSpec type;
    bool varying = false;
    bool output = false;
    bool hasDefault = false;
    bool constantDefault = false;
    ConstValue value;         // when constantDefault
    std::string defaultText;  // the default as source when not constant
};

struct ShaderInfo {
    ShaderKind kind = ShaderKind::Surface;
    std::string name;
    std::vector<ParamInfo> params;
    std::set<std::string> globalsRead;
    std::set<std::string> globalsWritten;
    std::set<std::string> services;   // trace, texture, environment, shadow, lighting,
                                      // illuminance, derivatives, message
    std::set<std::string> textures;   // literal map names given to texture() & co
    std::set<std::string> derivatives;  // Du Dv Deriv area calculatenormal filterstep
    std::vector<std::string> oncePerInstance;  // hoisted uniform variables (hoist.h)
    // Surfaces: "yes" when one evaluation gives every light's coefficient (rsl_abi.h LIGHT
    // COEFFICIENTS), else "no (file:line:col: why)": the renderer then runs it per light.
    std::string lightCoefficients;
};

// Walks the typed shader (and the user functions it calls).
ShaderInfo collectInfo(const ShaderDecl& shader);
std::string formatInfo(const ShaderInfo& info);

}  // namespace rsl
