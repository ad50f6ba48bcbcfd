// globals.cpp: the per-shader-kind table of standard global variables.
#include "globals.h"

#include <cstring>

namespace rsl {
namespace {

struct GlobalDef {
    const char* name;
    BaseType type;
    bool varying;
    const char* readers;  // kinds that see it: s l d v i
    const char* writers;  // kinds that may write it
};

// P and N are written by displacement shaders, and by surface shaders that bump in
// their own body (PRMan accepts it: the RenderMan Companion's eroded.sl sets N, its
// slideprojector.sl light L), for what the rest of the shader reads.
const GlobalDef kGlobals[] = {
    {"Cs", BaseType::Color, true, "s", ""},
    {"Os", BaseType::Color, true, "s", ""},
    {"P", BaseType::Point, true, "sldvi", "sd"},
    {"dPdu", BaseType::Vector, true, "sld", ""},
    {"dPdv", BaseType::Vector, true, "sld", ""},
    {"N", BaseType::Normal, true, "sld", "sd"},
    {"Ng", BaseType::Normal, true, "sld", ""},
    {"u", BaseType::Float, true, "sld", ""},
    {"v", BaseType::Float, true, "sld", ""},
    {"du", BaseType::Float, true, "sldv", ""},
    {"dv", BaseType::Float, true, "sldv", ""},
    {"s", BaseType::Float, true, "sld", ""},
    {"t", BaseType::Float, true, "sld", ""},
    {"L", BaseType::Vector, true, "slv", "l"},
    {"Cl", BaseType::Color, true, "slv", "l"},
    {"Ol", BaseType::Color, true, "slv", "l"},
    {"Ps", BaseType::Point, true, "l", ""},
    {"E", BaseType::Point, false, "sldv", ""},
    {"I", BaseType::Vector, true, "sdv", ""},
    {"Ci", BaseType::Color, true, "svi", "svi"},
    {"Oi", BaseType::Color, true, "svi", "svi"},
    {"alpha", BaseType::Float, true, "i", "i"},
    {"ncomps", BaseType::Float, false, "sldvi", ""},
    {"time", BaseType::Float, false, "sldvi", ""},
    {"dtime", BaseType::Float, false, "sldvi", ""},
    {"dPdtime", BaseType::Vector, true, "sld", ""},
    {"PI", BaseType::Float, false, "sldvi", ""},  // a predefined constant in RSL
};

char kindLetter(ShaderKind k) {
    switch (k) {
    case ShaderKind::Surface: return 's';
    case ShaderKind::Light: return 'l';
    case ShaderKind::Displacement: return 'd';
    case ShaderKind::Volume: return 'v';
    case ShaderKind::Imager: return 'i';
    }
    return 's';
}

}  // namespace

std::vector<GlobalVar> globalsFor(ShaderKind k) {
    std::vector<GlobalVar> out;
    char c = kindLetter(k);
    for (const GlobalDef& g : kGlobals) {
        if (!std::strchr(g.readers, c)) continue;
        out.push_back({g.name, g.type, g.varying, std::strchr(g.writers, c) != nullptr});
    }
    return out;
}

}  // namespace rsl
