// message_services.cpp: rsl_attribute, rsl_option and rsl_shader_param (surface(),
// displacement(), atmosphere(), incident(), opposite()), and what they read from the
// parameter buffer (Attribute and Option values, the materials' shader blocks).
// A value is data: editing it keeps the program; only the set of names and sizes
// is in the code.
#include "message_services.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <sstream>

#include "emit_cl.h"

namespace rd {

namespace {

// A value's place in a block: its found flag, then its floats.
struct Slot {
    int id = 0;
    size_t size = 0, offset = 0;
};

// The names (by id) and sizes the values give, each with its offset in a block.
std::vector<Slot> layout(const std::vector<const MessageValues*>& sets,
                         size_t& blockFloats) {
    std::map<std::pair<int, size_t>, size_t> at;
    blockFloats = 0;
    for (const MessageValues* set : sets)
        for (const MessageValue& v : *set) {
            auto [it, added] =
                at.emplace(std::pair{rsl::stringId(v.name), v.values.size()}, 0);
            if (added) it->second = blockFloats, blockFloats += 1 + v.values.size();
        }
    std::vector<Slot> slots;
    for (const auto& [key, offset] : at) slots.push_back({key.first, key.second, offset});
    return slots;
}

// One block: each slot's flag and floats where the set gives that name and size.
void writeBlock(const MessageValues& set, const std::vector<Slot>& slots,
                size_t blockFloats, std::vector<float>& params) {
    const size_t base = params.size();
    params.resize(base + blockFloats, 0.0f);
    for (const MessageValue& v : set)
        for (const Slot& s : slots)
            if (s.id == rsl::stringId(v.name) && s.size == v.values.size()) {
                params[base + s.offset] = 1.0f;
                std::copy(v.values.begin(), v.values.end(),
                          params.begin() + long(base + s.offset + 1));
            }
}

// `switch (nameId)` over the slots: at = the slot's offset where n is its size.
std::string findSlot(const std::vector<Slot>& slots, const std::string& extra) {
    std::ostringstream s;
    s << "    int at = -1;\n    switch (nameId) {\n" << extra;
    for (size_t i = 0; i < slots.size();) {
        const int id = slots[i].id;
        s << "    case " << id << ":";
        for (; i < slots.size() && slots[i].id == id; ++i)
            s << " if (n == " << slots[i].size << ") at = " << slots[i].offset << ";";
        s << " break;\n";
    }
    s << "    default: return 0;\n    }\n    if (at < 0) return 0;\n";
    return s.str();
}

const char* kCopy =
    "    if (b[0] == 0.0f) return 0;\n"
    "    for (int k = 0; k < n; ++k) out[k] = b[1 + k];\n"
    "    return 1;\n}\n";

}  // namespace

// An int (an offset into the buffer, a shader's index) as a float's bits: exact however
// large, read by as_int.
float intBits(int64_t value) {
    const int32_t i = int32_t(value);
    float f;
    std::memcpy(&f, &i, sizeof f);
    return f;
}

std::string messageServices(const Scene& scene, bool attributesUsed,
                            const MessageSlots& slots, std::vector<float>& params,
                            rib::Diagnostics& diag) {
    std::ostringstream src;
    // attribute(): a block per set, the table of each material's block
    std::vector<const MessageValues*> sets;
    if (attributesUsed)
        for (const MessageValues& s : scene.attributeSets) sets.push_back(&s);
    size_t blockFloats = 0;
    std::vector<Slot> attrSlots = layout(sets, blockFloats);
    constexpr size_t kMostFloats = size_t(1) << 24;
    if (blockFloats * sets.size() > kMostFloats) {
        diag.warning(rib::SourceLoc{scene.sourceFile, 0},
                     std::to_string(sets.size()) + " sets of attribute values of " +
                         std::to_string(blockFloats) +
                         " floats each are too many to lay out; attribute() finds none");
        attrSlots.clear();
    }
    if (attrSlots.empty()) {
        src << "int rsl_attribute(const RslGlobals* g, int nameId, float* out, int n) {\n"
               "    (void)g; (void)nameId; (void)out; (void)n;\n    return 0;\n}\n";
    } else {
        std::vector<size_t> blockAt;
        for (const MessageValues* set : sets) {
            blockAt.push_back(params.size());
            writeBlock(*set, attrSlots, blockFloats, params);
        }
        params[slots.attributeTable] = intBits(int64_t(params.size()));
        for (size_t m = 0; m < scene.materials.size(); ++m) {
            const uint32_t set =
                m < scene.materialAttributes.size() ? scene.materialAttributes[m] : 0;
            params.push_back(intBits(int64_t(blockAt[set < blockAt.size() ? set : 0])));
        }
        src << "int rsl_attribute(const RslGlobals* g, int nameId, float* out, int n) {\n"
            << findSlot(attrSlots, "")
            << "    if (g->material < 0) return 0;\n"
               "    __global const float* s = g->scene_params;\n"
               "    __global const float* b = s + as_int(s[as_int(s["
            << slots.attributeTable << "]) + g->material]) + at;\n"
            << kCopy;
    }
    // option(): Format and Clipping from the scene block, the rest from the option block
    size_t optionFloats = 0;
    std::vector<Slot> optionSlots = layout({&scene.optionValues}, optionFloats);
    // (a name whose id is Format's or Clipping's would be a second case of theirs)
    const int format = rsl::stringId("Format"), clipping = rsl::stringId("Clipping");
    optionSlots.erase(
        std::remove_if(optionSlots.begin(), optionSlots.end(),
                       [&](const Slot& o) { return o.id == format || o.id == clipping; }),
        optionSlots.end());
    params[slots.optionBlock] = intBits(int64_t(params.size()));
    writeBlock(scene.optionValues, optionSlots, optionFloats, params);
    std::ostringstream known;
    known << "    case " << format << ": if (n != 3) return 0;\n"
          << "        for (int k = 0; k < n; ++k) out[k] = sp->scene[" << slots.format
          << " + k];\n        return 1;\n"
          << "    case " << clipping << ": if (n != 2) return 0;\n"
          << "        for (int k = 0; k < n; ++k) out[k] = sp->scene[" << slots.clipping
          << " + k];\n        return 1;\n";
    src << "int rsl_option(const RslSpaces* sp, int nameId, float* out, int n) {\n"
        << findSlot(optionSlots, known.str())
        << "    __global const float* b = sp->scene + as_int(sp->scene["
        << slots.optionBlock << "]) + at;\n"
        << kCopy;
    return src.str();
}

std::string shaderParamService(const ShaderBlocks& blocks, bool used, size_t tableSlot,
                               std::vector<float>& params) {
    std::ostringstream src;
    src << "int rsl_shader_param(const RslGlobals* g, int kind, int nameId, float* out, "
           "int n) {\n";
    if (!used || blocks.materials.empty()) {
        src << "    (void)g; (void)kind; (void)nameId; (void)out; (void)n;\n    return "
               "0;\n}\n";
        return src.str();
    }
    params[tableSlot] = intBits(int64_t(params.size()));
    for (const auto& m : blocks.materials)
        for (int32_t v : m) params.push_back(intBits(v));
    // incident() (kind 5) and opposite() (6): the interior (3) on the side a ray hitting
    // the back came from (I . Ng > 0, the renderer's test for entering the Interior
    // shader, shade_rsl.cl), else the exterior (4), or where none is bound the atmosphere
    // (2), the volume an eye ray crosses to reach the surface
    constexpr int kStride = 2 * ShaderBlocks::kKinds;
    src << "    if (g->material < 0 || kind < 0 || kind > 6) return 0;\n"
           "    __global const float* s = g->scene_params;\n"
           "    const int row = as_int(s["
        << tableSlot << "]) + " << kStride
        << " * g->material;\n"
           "    if (kind >= 5) {\n"
           "        const int back = dot(g->I.xyz, g->Ng.xyz) > 0.0f;\n"
           "        kind = (kind == 5) == back ? 3 : 4;\n"
           "        if (kind == 4 && as_int(s[row + "
        << 2 * 4
        << "]) < 0) kind = 2;\n"
           "    }\n"
           "    const int at = row + 2 * kind;\n"
           "    const int shader = as_int(s[at]), block = as_int(s[at + 1]);\n"
           "    if (shader < 0) return 0;\n    int off = -1;\n    switch (kind * 4096 + "
           "shader) {\n";
    for (int kind = 0; kind < ShaderBlocks::kKinds; ++kind)
        for (size_t i = 0; i < blocks.shaders[kind].size(); ++i) {
            src << "    case " << kind * 4096 + int(i) << ":";
            // (parameters: an output variable's current value is not in the block)
            for (const rsl::ParamSlot& slot : blocks.shaders[kind][i]->params)
                if (!slot.output)
                    src << "\n        if (nameId == " << rsl::stringId(slot.name)
                        << " && n == " << slot.size << ") off = " << slot.offset << ";";
            src << "\n        break;\n";
        }
    src << "    default: return 0;\n    }\n    if (off < 0) return 0;\n"
           "    for (int k = 0; k < n; ++k) out[k] = s[block + off + k];\n    return "
           "1;\n}\n";
    return src.str();
}

}  // namespace rd
