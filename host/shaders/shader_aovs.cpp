// shader_aovs.cpp: the AOVs shaders write, laid out, and the code that writes them
// (shader_aovs.h).
#include "shader_aovs.h"

#include <algorithm>
#include <set>

#include "emit_cl.h"

namespace rd {

namespace {

// The globals an AOV may name when no shader has an output variable of that name.
struct GlobalAov {
    const char* name;
    const char* type;
};
constexpr GlobalAov kGlobals[] = {{"Cs", "color"}, {"Os", "color"}, {"Oi", "color"},
                                  {"P", "point"},  {"Ng", "normal"}, {"s", "float"},
                                  {"t", "float"},  {"u", "float"},  {"v", "float"}};

const GlobalAov* globalAov(const std::string& name) {
    for (const GlobalAov& g : kGlobals)
        if (name == g.name) return &g;
    return nullptr;
}

bool isTriple(const std::string& type) {
    return type == "point" || type == "vector" || type == "normal";
}

// Whether an output variable of `type` (non-array) fills an AOV of `aovType`.
bool fits(const std::string& type, const std::string& aovType) {
    return type == aovType || (isTriple(type) && isTriple(aovType));
}

int floatsOf(const std::string& type, const ColorSamples& colors) {
    return type == "float" ? 1 : type == "color" ? colors.slots() : 3;
}

const rsl::ParamSlot* outputNamed(const rsl::EmittedShader& sh, const std::string& name) {
    for (const rsl::ParamSlot& p : sh.params)
        if (p.output && p.name == name) return &p;
    return nullptr;
}

}  // namespace

bool isRendererAov(const std::string& name) {
    return name == "z" || name == "N" || name == "samples" || name == "error" ||
           name == "filled";
}

std::vector<ShaderAov> layoutShaderAovs(const std::vector<std::string>& names,
                                        const Scene& scene,
                                        const std::vector<const rsl::EmittedShader*>& surfaces,
                                        rib::Diagnostics& diag) {
    std::vector<ShaderAov> out;
    int offset = 0;
    const rib::SourceLoc loc{scene.sourceFile, 0};
    for (const std::string& name : names) {
        if (isRendererAov(name)) continue;
        ShaderAov a;
        a.name = name;
        bool written = false;
        for (const rsl::EmittedShader* sh : surfaces)
            if (const rsl::ParamSlot* p = sh ? outputNamed(*sh, name) : nullptr;
                p && p->arraySize == 0 && p->outputOffset >= 0) {
                if (!written) a.type = p->typeName;  // (the first one's, unless declared)
                written = true;
            }
        const GlobalAov* g = globalAov(name);
        if (auto it = scene.aovTypes.find(name); it != scene.aovTypes.end())
            a.type = it->second;
        else if (!written && g)
            a.type = g->type;
        if (a.type != "float" && a.type != "color" && !isTriple(a.type)) {
            diag.warning(loc, "AOV \"" + name + "\": a shader output of type " + a.type +
                                  " is not an image channel (float, color, point, vector, "
                                  "normal); written as 0");
            a.type = "float";
            written = false;
        }
        if (!written && !g)
            diag.warning(loc, "AOV \"" + name +
                                  "\": no surface shader in the scene has an output "
                                  "variable of that name, and it is not a global (Cs, Os, "
                                  "Oi, P, Ng, s, t, u, v): its channels are 0");
        a.floats = floatsOf(a.type, scene.colors);
        a.offset = offset;
        offset += a.floats;
        out.push_back(a);
    }
    return out;
}

int shaderAovFloats(const std::vector<ShaderAov>& aovs) {
    int n = 0;
    for (const ShaderAov& a : aovs) n += a.floats;
    return n;
}

std::string shaderAovChannels(const std::vector<ShaderAov>& aovs) {
    std::string out;
    for (const ShaderAov& a : aovs)
        for (int k = 0; k < a.floats; ++k)
            out += (out.empty() ? "" : ",") + std::to_string(a.type == "color"   ? k
                                                             : a.type == "float" ? -1
                                                                                 : -2);
    return out;
}

std::string shaderAovMacros(const rsl::EmittedShader& sh, const std::vector<ShaderAov>& aovs,
                            rib::Diagnostics& diag,
                            const rib::SourceLoc& loc) {
    std::string outputs, light, trace;
    for (const ShaderAov& a : aovs) {
        const std::string o = std::to_string(a.offset);
        const rsl::ParamSlot* p = outputNamed(sh, a.name);
        if (p && (p->arraySize != 0 || p->outputOffset < 0 || !fits(p->typeName, a.type))) {
            if (p->outputOffset >= 0)  // (one that did not fit was reported by rsl2cl)
                diag.warning(loc, "surface shader \"" + sh.name + "\": output variable \"" +
                                      a.name + "\" is a " + p->typeName +
                                      (p->arraySize ? " array" : "") + ", the AOV a " +
                                      a.type + ": not written");
            continue;
        }
        // Points are in RayDrive's world, whose origin is the eye (Scene::worldOrigin):
        // the AOV gives them in RIB world space.
        const bool point = a.type == "point";
        auto origin = [&](int k) {
            return point ? std::string(" + (RD_SCENE_WORLD_ORIGIN((g).scene_params)).s") +
                               char('0' + k)
                         : std::string();
        };
        if (p) {
            const std::string q = std::to_string(p->outputOffset);
            for (int k = 0; k < a.floats; ++k) {
                const std::string d = o + " + " + std::to_string(k), s = q + " + " +
                                                                         std::to_string(k);
                outputs += "(dst)[" + d + "] = (ev).outputs[" + s + "]" + origin(k) + "; ";
                light += "(dst)[" + d + "] = (le).outputs[" + s + "] - (ev).outputs[" + s +
                         "]; ";
            }
            // A trace() call's part (ray_aovs.clh): a colour's channel k weighs channel
            // k of what the ray brings back, a float the channels' mean.
            const std::string q0 = std::to_string(p->outputOffset);
            const std::string part0 =
                "((te).outputs[" + q0 + "] - (ev).outputs[" + q0 + "])";
            if (a.type == "color")
                for (int k = 0; k < a.floats; ++k) {
                    const std::string q = std::to_string(p->outputOffset + k);
                    trace += "(A)[(" + o + " + " + std::to_string(k) +
                             ") * RSL_CHANNELS + " + std::to_string(k) +
                             "] = (te).outputs[" + q + "] - (ev).outputs[" + q + "]; ";
                }
            else if (a.type == "float")
                trace += "for (int k_ = 0; k_ < RSL_CHANNELS; ++k_) (A)[" + o +
                         " * RSL_CHANNELS + k_] = " + part0 + " / (float)RSL_CHANNELS; ";
            continue;
        }
        const GlobalAov* g = globalAov(a.name);
        if (!g || std::string(g->type) != a.type) continue;  // (no shader writes it: 0)
        const std::string v = std::string("(g).") + g->name;
        for (int k = 0; k < a.floats; ++k) {
            const std::string d = "(dst)[" + o + " + " + std::to_string(k) + "] = ";
            if (a.type == "float")
                outputs += d + v + "; ";
            else if (a.type == "color")
                outputs += d + "rsl_comp(" + v + ", " + std::to_string(k) + "); ";
            else
                outputs += d + v + ".s" + char('0' + k) + origin(k) + "; ";
        }
    }
    return "#define RD_AOV_OUTPUTS_" + sh.name + "(dst, ev, g) do { " + outputs +
           "} while (0)\n#define RD_AOV_LIGHT_" + sh.name + "(dst, le, ev) do { " +
           light + "} while (0)\n#define RD_AOV_TRACE_" + sh.name + "(A, te, ev) do { " +
           trace + "} while (0)\n";
}

}  // namespace rd
