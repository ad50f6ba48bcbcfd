// globals.h: the standard global variables of each shader kind (RI 3.2 tables 15.x)
// with their types, uniform/varying class and whether the kind may write them.
#pragma once
#include <vector>

#include "ast.h"

namespace rsl {

struct GlobalVar {
    const char* name;
    BaseType type;
    bool varying;
    bool writable;
};

// The globals visible in shaders (and functions compiled for them) of kind k.
std::vector<GlobalVar> globalsFor(ShaderKind k);

}  // namespace rsl
