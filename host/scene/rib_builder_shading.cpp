// rib_builder_shading.cpp: the shading attributes (Color, Opacity, Surface, the volume,
// displacement and imager shaders, lights and Illuminate) and the material each surface
// gets from them: its shader instance (one per object space where the shader reads it),
// its volumes, displacement and flags, shared between surfaces whose attributes agree.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "rib_builder.h"
#include "rib_builder_util.h"
#include "shaders/shader_path.h"
#include "shaders/shader_set.h"

namespace rd {

void RibBuilder::color(L loc, const std::vector<float>& c) {
    const size_t k = size_t(m_world.colors.slots());
    if (c.size() != k) {
        m_diag.error(loc, "Color needs " + std::to_string(k) + " values (ColorSamples)");
        return;
    }
    std::copy_n(c.begin(), k, m_attrStack.back().color);
}
void RibBuilder::opacity(L loc, const std::vector<float>& c) {
    const size_t k = size_t(m_world.colors.slots());
    if (c.size() != k) {
        m_diag.error(loc,
                     "Opacity needs " + std::to_string(k) + " values (ColorSamples)");
        return;
    }
    float* o = m_attrStack.back().opacity;
    for (size_t i = 0; i < k; ++i) o[i] = std::fmin(1.0f, std::fmax(0.0f, c[i]));
}

void RibBuilder::surface(L loc, const std::string& name, const rib::ParamList& params) {
    // The shader is compiled and its parameters bound when the world is rendered; here
    // the call is kept with the transform that defines "shader" space.
    m_attrStack.back().surface = {name, params, m_attrStack.back().ctm, loc};
    m_attrStack.back().surfaceKey = ++m_surfaceCalls;
}

// A shader call the attributes keep (Atmosphere, Interior, Exterior, Displacement), in
// the space current at the call, with a number of its own; "" or "null" removes it.
void RibBuilder::keepCall(L loc, S name, P params, ShaderRef& call, uint64_t& key) {
    call = (name.empty() || name == "null")
               ? ShaderRef()
               : ShaderRef{name, params, m_attrStack.back().ctm, loc};
    key = call.name.empty() ? 0 : ++m_surfaceCalls;
}

// Atmosphere "" (or "null") removes it; the volume shader runs on each surface's Ci and
// Oi as seen from the ray's origin.
void RibBuilder::atmosphere(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.atmosphere, a.atmosphereKey);
}

// Interior "" (or "null") removes it. The volume shader runs on what a ray brings back
// from the inside of this surface (a hit on its back), over the segment from the ray's
// origin: absorption in coloured glass, fog inside an object.
void RibBuilder::interior(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.interior, a.interiorKey);
}

// Exterior "" (or "null") removes it. The volume shader runs on the segment a ray that
// left this surface travels outside it (a reflection, a refraction out of it), in place
// of the atmosphere.
void RibBuilder::exterior(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.exterior, a.exteriorKey);
}

// Deformation shaders were never carried out by any renderer: a warning.
void RibBuilder::deformation(L loc, S name, P) {
    if (!name.empty() && name != "null")
        m_diag.warning(loc, "Deformation \"" + name +
                                "\": deformation shaders are not carried out; ignored");
}

// Displacement "" (or "null") removes it. Displacements are rendered as bump maps: the
// shader's N shades the surface, rays still leave from the undisplaced one.
void RibBuilder::displacement(L loc, S name, P params) {
    Attributes& a = m_attrStack.back();
    keepCall(loc, name, params, a.displacement, a.displacementKey);
}

// Imager: an option, the shader run on every pixel of the finished image.
void RibBuilder::imager(L loc, S name, P params) {
    Scene& s = m_inWorld ? m_world : m_options;
    s.imager = (name.empty() || name == "null")
                   ? ShaderRef()
                   : ShaderRef{name, params, glm::mat4(1.0f), loc};
}

void RibBuilder::lightSource(L loc, const std::string& name, const std::string& handle,
                             const rib::ParamList& params) {
    // Before WorldBegin a light is an option of the frame, placed in camera space
    // (worldBegin() moves it into the world); the reader refuses one in an ObjectBegin
    // block.
    Scene& s = m_inWorld ? m_world : m_options;
    const uint32_t index = uint32_t(s.lights.size());
    if (!handle.empty())
        (m_inWorld ? m_lightHandles : m_optionLightHandles)[handle] = index;
    s.lights.push_back({name, params, m_attrStack.back().ctm, loc});
}

// An area light: its light shader (e.g. arealight) runs at points on the geometry that
// follows in the same attribute block, one random point per shading point and sample
// (soft shadows as the samples add up). Its quadrics are diced so they can be sampled.
void RibBuilder::areaLightSource(L loc, S name, S handle, P params) {
    const size_t before = m_world.lights.size();
    lightSource(loc, name, handle, params);
    if (m_world.lights.size() > before) m_attrStack.back().areaLight = int(before);
}

// Illuminate turns a light off (or back on) for the geometry that follows, within the
// current attribute block. (Lights are on everywhere unless turned off: a light declared
// inside an attribute block still lights what comes after it.)
void RibBuilder::illuminate(L loc, const std::string& handle, bool on) {
    auto it = m_lightHandles.find(handle);
    if (it == m_lightHandles.end()) {
        m_diag.error(loc, "Illuminate: no light with handle \"" + handle + "\"");
        return;
    }
    if (it->second >= 32) {
        m_diag.warning(loc, "Illuminate: only the first 32 lights can be turned off");
        return;
    }
    uint32_t& off = m_attrStack.back().lightsOff;
    off = on ? (off & ~(1u << it->second)) : (off | (1u << it->second));
}

// One surface reference per distinct Surface call (same name, parameters, space), and
// per distinct set of primitive variables overriding its parameters (RI: a primitive
// variable named like a shader parameter gives that parameter its value on the primitive;
// constant ones, and uniform ones of a single face, become the instance's values; the
// others, on primitives that carry them (m_carriedPointParams), are given per point:
// rib_builder_point_params.cpp).
uint32_t RibBuilder::surfaceFor(const Attributes& a) {
    rib::ParamList overrides;
    std::string signature;
    const std::vector<std::pair<std::string, int>>& perPoint = m_carriedPointParams;
    for (const rib::Param& p :
         m_primVars ? m_primVars->params : std::vector<rib::Param>{}) {
        if (isStandardPrimvar(p.name)) continue;
        if (std::find_if(perPoint.begin(), perPoint.end(), [&](const auto& q) {
                return q.first == p.name;
            }) != perPoint.end())
            continue;
        if (!givesOneValue(p)) {
            if (m_varyingPrimvarWarned.insert(p.name).second)
                m_diag.warning(
                    a.surface.loc,
                    "primitive variable \"" + p.name + "\" (" +
                        rib::storageClassName(p.storage) + " " +
                        rib::paramTypeName(p.type) +
                        ") does not reach shader parameters: per-point values are "
                        "carried for float, color, point, vector and normal "
                        "variables (8 a primitive)");
            continue;
        }
        overrides.params.push_back(p);
        signature += p.name + ":" + std::to_string(int(p.type)) + ":";
        for (float f : p.floats) signature += std::to_string(f) + ",";
        for (int v : p.ints) signature += std::to_string(v) + ",";
        for (const std::string& v : p.strings) signature += v + ",";
        signature += ";";
    }
    for (const auto& [name, floats] : perPoint)
        signature += name + ":" + std::to_string(floats) + " per point;";
    const uint32_t objectSpace = objectSpaceOf(a.surface);
    if (objectSpace != 0)
        signature += "object space " + std::to_string(objectSpace) + ";";
    auto [it, fresh] = m_surfaceVariants.emplace(std::make_pair(a.surfaceKey, signature),
                                                 uint32_t(m_world.surfaceRefs.size()));
    if (fresh) {
        ShaderRef ref = a.surface;
        if (objectSpace != 0) ref.objectToWorld = a.ctm;
        for (const rib::Param& p : overrides.params) {
            auto same =
                std::find_if(ref.params.params.begin(), ref.params.params.end(),
                             [&](const rib::Param& q) { return q.name == p.name; });
            if (same != ref.params.params.end())
                *same = p;
            else
                ref.params.params.push_back(p);
        }
        ref.pointParams = perPoint;
        int values = 0;
        for (const auto& [name, floats] : perPoint) values += pointParamEntries(floats);
        m_world.maxPointParams = std::max(m_world.maxPointParams, values);
        m_world.surfaceRefs.push_back(ref);
    }
    return it->second;
}

uint32_t RibBuilder::objectSpaceOf(const ShaderRef& call) {
    const std::string& name = call.name;
    if (name.empty()) return 0;
    auto known = m_readsObjectSpace.find(name);
    if (known == m_readsObjectSpace.end())
        known =
            m_readsObjectSpace.emplace(name, shaderReadsObjectSpace(m_world, name)).first;
    if (!known->second) return 0;
    const glm::mat4& ctm = m_attrStack.back().ctm;
    const std::string bytes(reinterpret_cast<const char*>(&ctm[0][0]), sizeof ctm);
    if (auto it = m_objectSpaces.find(bytes); it != m_objectSpaces.end())
        return it->second;
    // (each one is an instance of its own: a bound on their blocks' memory)
    if (m_objectSpaces.size() >= kMaxObjectSpaces) {
        if (m_warnedAt.insert({call.loc.file, call.loc.line}).second)
            m_diag.warning(call.loc,
                           "more than " + std::to_string(kMaxObjectSpaces) +
                               " object spaces for shaders that read \"object\" "
                               "space; the rest take the call's space as object "
                               "space");
        return 0;
    }
    return m_objectSpaces.emplace(bytes, uint32_t(m_objectSpaces.size() + 1))
        .first->second;
}

size_t RibBuilder::callIndex(uint64_t key, const ShaderRef& call, CallIndex& index,
                             std::vector<ShaderRef>& calls, size_t limit,
                             const char* request) {
    uint32_t objectSpace = objectSpaceOf(call);
    auto it = index.find({key, objectSpace});
    if (it != index.end()) return it->second;
    if (calls.size() >= limit && objectSpace != 0) {
        // past the limit, the call's own space stands for the primitive's
        if (m_warnedAt.insert({call.loc.file, call.loc.line}).second)
            m_diag.warning(
                call.loc, std::string("more than ") + std::to_string(limit) + " " +
                              request + " instances (one per object space for shader \"" +
                              call.name +
                              "\", which reads \"object\" space); "
                              "the rest take the call's space as object space");
        objectSpace = 0;
        it = index.find({key, objectSpace});
        if (it != index.end()) return it->second;
    }
    ShaderRef ref = call;
    if (objectSpace != 0) ref.objectToWorld = m_attrStack.back().ctm;
    index.emplace(std::make_pair(key, objectSpace), calls.size());
    calls.push_back(std::move(ref));
    return calls.size() - 1;
}

uint32_t RibBuilder::currentMaterial() {
    const Attributes& a = m_attrStack.back();
    const uint32_t surface = surfaceFor(a);
    Material m{};
    m.shader = surface;
    // (more than three channels: the material's RGB here, its channels beside it)
    const ColorSamples& colors = m_world.colors;
    float cs[ColorSamples::kMaxChannels], os[ColorSamples::kMaxChannels];
    std::copy_n(a.color, colors.slots(), cs);
    std::copy_n(a.opacity, colors.slots(), os);
    if (colors.n > 3) colors.toRgbValues(cs), colors.toRgbValues(os);
    m.cs = f4(cs[0], cs[1], cs[2]);
    m.os = f4(os[0], os[1], os[2], (os[0] + os[1] + os[2]) / 3.0f);
    m.lights_off = a.lightsOff;
    if (a.sides == 1) m.flags |= RT_MATERIAL_ONE_SIDED;
    // each volume or displacement call in use gets an index, 1 + it in the material's
    // bits
    auto bind = [&](uint64_t callKey, const ShaderRef& call, CallIndex& keys,
                    std::vector<ShaderRef>& calls, uint32_t shift, const char* request) {
        if (callKey == 0) return false;
        const size_t index = callIndex(callKey, call, keys, calls, 255, request);
        if (index < 255)
            m.flags |= uint32_t(index + 1) << shift;
        else
            m_diag.warning(call.loc, std::string("more than 255 ") + request +
                                         " calls; this one is not used");
        return index < 255;
    };
    bind(a.atmosphereKey, a.atmosphere, m_atmosphereKeys, m_world.atmospheres,
         RT_MATERIAL_ATMOSPHERE_SHIFT, "Atmosphere");
    bind(a.interiorKey, a.interior, m_interiorKeys, m_world.interiors,
         RT_MATERIAL_INTERIOR_SHIFT, "Interior");
    uint32_t exterior = 0;  // (in a table of its own: the material's flag bits are taken)
    if (a.exteriorKey != 0)
        exterior = uint32_t(callIndex(a.exteriorKey, a.exterior, m_exteriorKeys,
                                      m_world.exteriors, SIZE_MAX, "Exterior") +
                            1);
    if (bind(a.displacementKey, a.displacement, m_displacementKeys, m_world.displacements,
             RT_MATERIAL_DISPLACEMENT_SHIFT, "Displacement") &&
        a.displacesTruly())
        m.flags |= RT_MATERIAL_TRUE_DISPLACEMENT;
    if (a.matte) {
        m.flags |= RT_MATERIAL_MATTE;
        m_world.anyMatte = true;
    }
    m.flags |= a.visibility;
    std::string key(reinterpret_cast<const char*>(&m), sizeof m);
    if (colors.n > 3) {
        key.append(reinterpret_cast<const char*>(a.color),
                   sizeof(float) * size_t(colors.n));
        key.append(reinterpret_cast<const char*>(a.opacity),
                   sizeof(float) * size_t(colors.n));
    }
    const uint32_t attributeSet = attributeSetIndex(a.messages);
    key.append(reinterpret_cast<const char*>(&attributeSet), sizeof attributeSet);
    // a truly displaced surface's micropolygon edge, in pixels
    const float dicing =
        (m.flags & RT_MATERIAL_TRUE_DISPLACEMENT) ? std::sqrt(a.shadingRate) : 0.0f;
    key.append(reinterpret_cast<const char*>(&dicing), sizeof dicing);
    key.append(reinterpret_cast<const char*>(&exterior), sizeof exterior);
    // (the default is the world's: Option or attribute before WorldBegin)
    const int specularDepth =
        a.maxSpecularDepth >= 0 ? a.maxSpecularDepth : m_world.maxSpecularDepth;
    key.append(reinterpret_cast<const char*>(&specularDepth), sizeof specularDepth);
    if (auto it = m_materialKeys.find(key); it != m_materialKeys.end()) return it->second;
    uint32_t index = static_cast<uint32_t>(m_world.materials.size());
    m_world.materials.push_back(m);
    m_world.materialAttributes.push_back(attributeSet);
    m_world.materialDicing.push_back(dicing);
    m_world.materialExterior.push_back(exterior);
    m_world.materialSpecularDepth.push_back(specularDepth);
    if (colors.n > 3) {
        m_world.materialChannels.insert(m_world.materialChannels.end(), a.color,
                                        a.color + colors.n);
        m_world.materialChannels.insert(m_world.materialChannels.end(), a.opacity,
                                        a.opacity + colors.n);
    }
    m_materialKeys.emplace(std::move(key), index);
    return index;
}

}  // namespace rd
