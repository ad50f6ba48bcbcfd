// message_services.h: the services behind attribute(), option(), surface(),
// displacement() and atmosphere() (rsl_abi.h, MESSAGE PASSING): the Attribute and Option
// values the scene gives (Scene::attributeSets, optionValues) and each material's shader
// blocks laid out in the parameter buffer, and the OpenCL source that finds them by name
// id and size.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "rib/diagnostics.h"
#include "scene/scene.h"

namespace rsl {
struct EmittedShader;
}

namespace rd {

// Where the services find the data and the options they always know, float offsets into
// the parameter buffer's scene block (RslGlobals::scene_params).
struct MessageSlots {
    size_t format = 0, clipping = 0;  // Format (3 floats), Clipping (2)
    size_t attributeTable = 0;        // the table's start (an int's bits)
    size_t optionBlock = 0;           // the option block's start (an int's bits)
};

// Appends the attribute blocks (one per set, every name the sets give laid out alike;
// a found flag then the values each), the per-material table of block offsets and the
// option block to `params`, writes their starts into the scene block's slots, and
// returns rsl_attribute and rsl_option. `attributesUsed`: some shader calls attribute()
// (else rsl_attribute finds nothing and no attribute data is laid out).
// An int (an offset into the parameter buffer, an index) as a float's bits: exact however
// large; the device reads it with as_int.
float intBits(int64_t value);

std::string messageServices(const Scene& scene, bool attributesUsed,
                            const MessageSlots& slots, std::vector<float>& params,
                            rib::Diagnostics& diag);

// surface(), displacement(), atmosphere(), incident() and opposite() (rsl_abi.h, MESSAGE
// PASSING): a parameter of the shaded material's surface, displacement, atmosphere,
// interior or exterior shader, from its bound block.
struct ShaderBlocks {
    // surface, displacement, atmosphere, interior, exterior
    static constexpr int kKinds = 5;
    // per kind: the shaders, each once
    std::vector<const rsl::EmittedShader*> shaders[kKinds];
    // per material and kind: (index into shaders[kind], or -1 for none; its block's
    // start)
    std::vector<std::array<int32_t, 2 * kKinds>> materials;
};
// Appends the per-material table to `params` (its start into params[tableSlot]) and
// returns rsl_shader_param; when `used` is false (no shader calls it) the function finds
// nothing and no table is laid out.
std::string shaderParamService(const ShaderBlocks& blocks, bool used, size_t tableSlot,
                               std::vector<float>& params);

}  // namespace rd
