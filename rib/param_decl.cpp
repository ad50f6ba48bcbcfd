// param_decl.cpp: parsing of RenderMan parameter declarations and the table of predefined
// parameter names. Kept apart from the reader so the declaration grammar can be tested
// and reused (a RIB writer needs the same spellings).
#include "param_decl.h"

#include <cstdlib>
#include <unordered_map>
#include <vector>

namespace rib {

namespace {

std::vector<std::string> splitDecl(const std::string& text) {
    // "float[2]", "float [2]" and "float [ 2 ]" all mean the same, so brackets are
    // tokens of their own.
    std::vector<std::string> words;
    std::string cur;
    auto flush = [&] {
        if (!cur.empty()) words.push_back(cur);
        cur.clear();
    };
    for (char c : text) {
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            flush();
        } else if (c == '[' || c == ']') {
            flush();
            words.push_back(std::string(1, c));
        } else {
            cur += c;
        }
    }
    flush();
    return words;
}

bool storageFromWord(const std::string& w, StorageClass& s) {
    static const std::unordered_map<std::string, StorageClass> table = {
        {"constant", StorageClass::Constant},
        {"uniform", StorageClass::Uniform},
        {"varying", StorageClass::Varying},
        {"vertex", StorageClass::Vertex},
        {"facevarying", StorageClass::FaceVarying},
        {"facevertex", StorageClass::FaceVarying},
    };
    auto it = table.find(w);
    if (it == table.end()) return false;
    s = it->second;
    return true;
}

bool typeFromWord(const std::string& w, ParamType& t) {
    static const std::unordered_map<std::string, ParamType> table = {
        {"float", ParamType::Float},   {"integer", ParamType::Integer},
        {"int", ParamType::Integer},   {"string", ParamType::String},
        {"point", ParamType::Point},   {"vector", ParamType::Vector},
        {"normal", ParamType::Normal}, {"color", ParamType::Color},
        {"hpoint", ParamType::HPoint}, {"matrix", ParamType::Matrix},
    };
    auto it = table.find(w);
    if (it == table.end()) return false;
    t = it->second;
    return true;
}

}  // namespace

bool parseParamDecl(const std::string& text, bool wantName, ParamDecl& decl,
                    std::string& name) {
    std::vector<std::string> w = splitDecl(text);
    size_t i = 0;
    ParamDecl d;
    if (i < w.size() && storageFromWord(w[i], d.storage)) ++i;
    if (i >= w.size() || !typeFromWord(w[i], d.type)) return false;
    ++i;
    if (i < w.size() && w[i] == "[") {
        if (i + 2 >= w.size() || w[i + 2] != "]") return false;
        const std::string& n = w[i + 1];
        if (n.empty() || n.size() > 9 ||
            n.find_first_not_of("0123456789") != std::string::npos)
            return false;
        d.arraySize = std::atoi(n.c_str());
        if (d.arraySize < 1) return false;
        i += 3;
    }
    if (wantName) {
        if (i + 1 != w.size()) return false;
        name = w[i];
    } else if (i != w.size()) {
        return false;
    }
    decl = d;
    return true;
}

bool predefinedParamDecl(const std::string& name, ParamDecl& decl) {
    using T = ParamType;
    using S = StorageClass;
    static const std::unordered_map<std::string, ParamDecl> table = {
        {"P", {T::Point, S::Vertex, 1}},
        {"Pw", {T::HPoint, S::Vertex, 1}},
        {"Pz", {T::Float, S::Vertex, 1}},
        {"N", {T::Normal, S::Varying, 1}},
        {"Np", {T::Normal, S::Uniform, 1}},
        {"Cs", {T::Color, S::Varying, 1}},
        {"Os", {T::Color, S::Varying, 1}},
        {"s", {T::Float, S::Varying, 1}},
        {"t", {T::Float, S::Varying, 1}},
        {"st", {T::Float, S::Varying, 2}},
        // Standard light shader parameters that are points or colors, not floats: a
        // scene builder must transform "from"/"to" as points.
        {"from", {T::Point, S::Uniform, 1}},
        {"to", {T::Point, S::Uniform, 1}},
        {"lightcolor", {T::Color, S::Uniform, 1}},
        {"specularcolor", {T::Color, S::Uniform, 1}},
        // The other standard shader parameters and primitive widths RI 3.2 predeclares
        // (the Ri API sizes a C caller's values by them)
        {"Ka", {T::Float, S::Uniform, 1}},
        {"Kd", {T::Float, S::Uniform, 1}},
        {"Ks", {T::Float, S::Uniform, 1}},
        {"Kr", {T::Float, S::Uniform, 1}},
        {"roughness", {T::Float, S::Uniform, 1}},
        {"intensity", {T::Float, S::Uniform, 1}},
        {"coneangle", {T::Float, S::Uniform, 1}},
        {"conedeltaangle", {T::Float, S::Uniform, 1}},
        {"beamdistribution", {T::Float, S::Uniform, 1}},
        {"mindistance", {T::Float, S::Uniform, 1}},
        {"maxdistance", {T::Float, S::Uniform, 1}},
        {"distance", {T::Float, S::Uniform, 1}},
        {"amplitude", {T::Float, S::Uniform, 1}},
        {"fov", {T::Float, S::Uniform, 1}},
        {"background", {T::Color, S::Uniform, 1}},
        {"texturename", {T::String, S::Uniform, 1}},
        {"width", {T::Float, S::Varying, 1}},
        {"constantwidth", {T::Float, S::Constant, 1}},
    };
    auto it = table.find(name);
    if (it == table.end()) return false;
    decl = it->second;
    return true;
}

}  // namespace rib
