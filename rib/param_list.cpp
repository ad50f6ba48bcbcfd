// param_list.cpp: element sizes of the RenderMan parameter types and the lookup helpers a
// Target uses to pull typed values out of a ParamList. Accessors are lenient on purpose:
// a shader parameter given as an int or a float should read the same either way.
#include "param_list.h"

#include <climits>
#include <cmath>

namespace rib {

int Param::components() const {
    switch (type) {
        case ParamType::Point:
        case ParamType::Vector:
        case ParamType::Normal:
            return 3;
        case ParamType::Color:
            return colorComponents;
        case ParamType::HPoint:
            return 4;
        case ParamType::Matrix:
            return 16;
        case ParamType::Float:
        case ParamType::Integer:
        case ParamType::String:
            break;
    }
    return 1;
}

const char* paramTypeName(ParamType type) {
    switch (type) {
        case ParamType::Float:
            return "float";
        case ParamType::Integer:
            return "integer";
        case ParamType::String:
            return "string";
        case ParamType::Point:
            return "point";
        case ParamType::Vector:
            return "vector";
        case ParamType::Normal:
            return "normal";
        case ParamType::Color:
            return "color";
        case ParamType::HPoint:
            return "hpoint";
        case ParamType::Matrix:
            return "matrix";
    }
    return "?";
}

const char* storageClassName(StorageClass storage) {
    switch (storage) {
        case StorageClass::Constant:
            return "constant";
        case StorageClass::Uniform:
            return "uniform";
        case StorageClass::Varying:
            return "varying";
        case StorageClass::Vertex:
            return "vertex";
        case StorageClass::FaceVarying:
            return "facevarying";
    }
    return "?";
}

const Param* ParamList::find(const std::string& name) const {
    for (const Param& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

float ParamList::getFloat(const std::string& name, float def) const {
    const Param* p = find(name);
    if (!p) return def;
    if (!p->floats.empty()) return p->floats[0];
    if (!p->ints.empty()) return static_cast<float>(p->ints[0]);
    return def;
}

int ParamList::getInt(const std::string& name, int def) const {
    const Param* p = find(name);
    if (!p) return def;
    if (!p->ints.empty()) return p->ints[0];
    if (!p->floats.empty()) {
        // Undeclared numbers arrive as floats; convert only when the value fits.
        float f = p->floats[0];
        if (std::isfinite(f) && f >= static_cast<float>(INT_MIN) &&
            f < static_cast<float>(INT_MAX))
            return static_cast<int>(std::lround(f));
    }
    return def;
}

std::string ParamList::getString(const std::string& name, const std::string& def) const {
    const Param* p = find(name);
    if (!p || p->strings.empty()) return def;
    return p->strings[0];
}

void ParamList::get3(const std::string& name, float out[3], const float def[3]) const {
    const Param* p = find(name);
    std::vector<float> vals;
    if (p) {
        vals = p->floats;
        if (vals.empty())
            for (int i : p->ints) vals.push_back(static_cast<float>(i));
    }
    if (vals.size() >= 3) {
        for (int i = 0; i < 3; ++i) out[i] = vals[i];
    } else if (vals.size() == 1) {
        // A single value for a color ("lightcolor" 1) means grey, the common RIB idiom.
        for (int i = 0; i < 3; ++i) out[i] = vals[0];
    } else {
        for (int i = 0; i < 3; ++i) out[i] = def[i];
    }
}

}  // namespace rib
