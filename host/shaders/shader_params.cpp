// shader_params.cpp: a shader call's parameter block: the defaults, then the RIB's
// values by name (checked against the declared types), points, vectors and normals
// moved to world space, colours in the scene's channels; and where each per-point value
// of the call goes in the block.
#include <algorithm>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "emit_cl.h"
#include "shader_set.h"

namespace rd {

namespace {

// Moves a triple of a point/vector/normal parameter from a space to world space.
void toWorld(rsl::BaseType base, const glm::mat4& m, float* v) {
    glm::vec3 p(v[0], v[1], v[2]), out;
    if (base == rsl::BaseType::Point)
        out = glm::vec3(m * glm::vec4(p, 1.0f));
    else if (base == rsl::BaseType::Vector)
        out = glm::mat3(m) * p;
    else
        out = glm::transpose(glm::inverse(glm::mat3(m))) * p;  // normal
    v[0] = out.x, v[1] = out.y, v[2] = out.z;
}

bool isTripleType(rib::ParamType t) {
    return t == rib::ParamType::Point || t == rib::ParamType::Vector ||
           t == rib::ParamType::Normal || t == rib::ParamType::Color;
}

}  // namespace

std::vector<float> bindParameters(const rsl::EmittedShader& sh, const ShaderRef& call,
                                  rib::Diagnostics& diag, const ColorSamples& colors) {
    std::vector<float> block(size_t(sh.paramFloats), 0.0f);
    const bool imager = sh.kind == "imager";  // it works on the film's RGB
    for (const rsl::ParamSlot& slot : sh.params) {
        const rsl::BaseType base = slot.type.base;
        const bool pointLike = base == rsl::BaseType::Point ||
                               base == rsl::BaseType::Vector ||
                               base == rsl::BaseType::Normal;
        const int elem = std::max(1, slot.arraySize);
        const int per = slot.size / elem;
        // Defaults, moved out of the space they were written in.
        for (int i = 0; i < slot.size && i < int(slot.defaults.size()); ++i)
            block[size_t(slot.offset + i)] = slot.defaults[size_t(i)];
        if (slot.rgbDefault && !colors.isRgb() &&
            !imager)  // RIB colours are in the channels
            for (int e = 0; e < elem; ++e)
                colors.fromRgbValues(&block[size_t(slot.offset + e * per)]);
        if (!slot.constantDefault) block[size_t(slot.offset)] = NAN;
        if (pointLike && slot.constantDefault && slot.space == "shader")
            for (int e = 0; e < elem; ++e)
                toWorld(base, call.shaderToWorld, &block[size_t(slot.offset + e * per)]);
        // The RIB's value, if it gives one.
        const rib::Param* p = call.params.find(slot.name);
        if (!p) continue;
        const std::string what =
            "parameter \"" + slot.name + "\" of shader \"" + call.name + "\"";
        if (base == rsl::BaseType::String) {
            if (p->type != rib::ParamType::String || p->strings.size() != size_t(elem)) {
                diag.warning(call.loc, what + " wants " + std::to_string(elem) +
                                           " string(s); ignored");
                continue;
            }
            for (int e = 0; e < elem; ++e)
                block[size_t(slot.offset + e)] =
                    float(rsl::stringId(p->strings[size_t(e)]));
            continue;
        }
        bool numeric = p->type == rib::ParamType::Float ||
                       p->type == rib::ParamType::Integer || isTripleType(p->type) ||
                       p->type == rib::ParamType::Matrix;
        std::vector<float> values = p->floats;
        if (p->type == rib::ParamType::Integer)
            values.assign(p->ints.begin(), p->ints.end());
        // A single number for a colour or point fills all its components (RSL promotion).
        if (numeric && values.size() == 1 && per > 1 && base != rsl::BaseType::Matrix)
            values.assign(size_t(per), values[0]);
        if (!numeric || values.size() != size_t(slot.size)) {
            diag.warning(call.loc, what + " is a " + slot.typeName + " of " +
                                       std::to_string(slot.size) + " float(s), got " +
                                       std::to_string(values.size()) + "; ignored");
            continue;
        }
        for (int i = 0; i < slot.size; ++i)
            block[size_t(slot.offset + i)] = values[size_t(i)];
        if (base == rsl::BaseType::Color && imager && !colors.isRgb())
            for (int e = 0; e < elem; ++e) {  // RGB, then zeros (rsl_abi.h, COLOURS)
                float* c = &block[size_t(slot.offset + e * per)];
                colors.toRgbValues(c);
                std::fill(c + 3, c + per, 0.0f);
            }
        // RIB values are in the coordinate system current at the call: "shader" space.
        if (pointLike)
            for (int e = 0; e < elem; ++e)
                toWorld(base, call.shaderToWorld, &block[size_t(slot.offset + e * per)]);
    }
    // After the parameters: the instance's "shader" and "object" spaces (rsl_abi.h,
    // SPACES), RSL row-vector matrices, which are glm's column-major arrays as they are.
    // Object space is the primitive's when the shader reads it (the builder made the
    // instance for it: ShaderRef::objectToWorld), else the space it was declared in.
    // Then their inverses (in double: exact where the device's 4x4 inverse at every
    // point was not, and was half of a solid-texture shader's time).
    const glm::dmat4 m(call.shaderToWorld),
        o(call.objectToWorld.value_or(call.shaderToWorld));
    block.resize(size_t(sh.spaceOffset) + rsl::kSpaceFloats);
    // then the slots its prepare function fills once per instance (rsl::HoistPlan)
    block.resize(size_t(sh.prepOffset) + size_t(sh.prepFloats), 0.0f);
    const glm::dmat4 spaces[4] = {m, o, glm::inverse(m), glm::inverse(o)};
    for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 16; ++i)
            block[size_t(sh.spaceOffset + 16 * k + i)] = float((&spaces[k][0][0])[i]);
    return block;
}

std::vector<int32_t> pointParamOffsets(const rsl::EmittedShader& sh,
                                       const ShaderRef& call, rib::Diagnostics& diag) {
    std::vector<int32_t> out;
    for (const auto& [name, floats] : call.pointParams) {
        int32_t offset = -1;  // not a parameter of this shader: RI ignores it
        for (const rsl::ParamSlot& slot : sh.params) {
            if (slot.name != name) continue;
            const bool fits = slot.size == floats;
            if (slot.arraySize == 0 && fits && slot.type.base != rsl::BaseType::String)
                offset = slot.offset;
            else
                diag.warning(call.loc, "primitive variable \"" + name + "\" of " +
                                           std::to_string(floats) +
                                           " float(s) per point does not "
                                           "fit parameter \"" +
                                           name + "\" (a " + slot.typeName +
                                           ") of shader \"" + call.name + "\"; ignored");
        }
        out.push_back(offset);
        // a colour's further pieces (rsl_abi.h, PER-POINT PARAMETERS)
        out.insert(out.end(), size_t(pointParamEntries(floats) - 1), -1);
    }
    return out;
}

}  // namespace rd
