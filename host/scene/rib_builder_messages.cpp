// rib_builder_messages.cpp: the Attribute and Option values shaders read by attribute()
// and option() (rsl_abi.h, MESSAGE PASSING): kept as "category:name" with their floats,
// each material pointing at its set of attribute values.
#include <algorithm>
#include <glm/gtc/matrix_inverse.hpp>

#include "emit_cl.h"
#include "rib_builder.h"

namespace rd {

namespace {
// A value larger than this many floats is not kept: attribute blocks are per material.
constexpr size_t kMaxMessageFloats = 64;
}  // namespace

void RibBuilder::setMessageValues(L loc, const std::string& category,
                                  const rib::ParamList& params, MessageValues& into,
                                  const glm::mat4* ctm) {
    for (const rib::Param& p : params.params) {
        MessageValue v;
        v.name = category + ":" + p.name;
        if (p.type == rib::ParamType::String)
            for (const std::string& s : p.strings)
                v.values.push_back(float(rsl::stringId(s)));
        else if (p.type == rib::ParamType::Integer)
            v.values.assign(p.ints.begin(), p.ints.end());
        else
            v.values = p.floats;
        if (v.values.size() > kMaxMessageFloats) {
            m_diag.warning(loc,
                           "\"" + v.name + "\" has " + std::to_string(v.values.size()) +
                               " floats; attribute() and option() find only values of "
                               "at most " +
                               std::to_string(kMaxMessageFloats));
            continue;
        }
        const bool pointLike = p.type == rib::ParamType::Point ||
                               p.type == rib::ParamType::Vector ||
                               p.type == rib::ParamType::Normal;
        if (ctm && pointLike) {
            const glm::mat4 m = eyeRelative(*ctm, glm::mat4(1.0f));
            const glm::mat3 normalMap = glm::inverseTranspose(glm::mat3(m));
            for (size_t i = 0; i + 2 < v.values.size(); i += 3) {
                const glm::vec3 x(v.values[i], v.values[i + 1], v.values[i + 2]);
                const glm::vec3 y = p.type == rib::ParamType::Point
                                        ? glm::vec3(m * glm::vec4(x, 1.0f))
                                    : p.type == rib::ParamType::Vector ? glm::mat3(m) * x
                                                                       : normalMap * x;
                v.values[i] = y.x, v.values[i + 1] = y.y, v.values[i + 2] = y.z;
            }
        }
        auto at = std::lower_bound(
            into.begin(), into.end(), v,
            [](const MessageValue& a, const MessageValue& b) { return a.name < b.name; });
        if (at != into.end() && at->name == v.name)
            *at = std::move(v);
        else
            into.insert(at, std::move(v));
    }
}

uint32_t RibBuilder::attributeSetIndex(const MessageValues& set) {
    if (set.empty()) return 0;
    auto [it, added] =
        m_attributeSetIndex.emplace(set, uint32_t(m_world.attributeSets.size()));
    if (added) m_world.attributeSets.push_back(set);
    return it->second;
}

}  // namespace rd
