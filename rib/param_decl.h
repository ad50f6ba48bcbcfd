// param_decl.h: RenderMan parameter declarations ("uniform color Kd", "float[2] st") as
// the reader resolves them: parsing the declaration syntax shared by inline declarations
// and Declare, and the types of the names the RI spec predefines (P, N, Cs, ...).
#pragma once
#include <string>

#include "param_list.h"

namespace rib {

struct ParamDecl {
    ParamType type = ParamType::Float;
    StorageClass storage = StorageClass::Uniform;
    int arraySize = 1;
};

// Parses "[class] type[[n]] [name]". With wantName the text must end in a parameter name
// (an inline declaration) and `name` receives it; without, it must not (a Declare).
bool parseParamDecl(const std::string& text, bool wantName, ParamDecl& decl,
                    std::string& name);

// The declaration of a name the RI spec (or the standard shaders) predefine, if any.
bool predefinedParamDecl(const std::string& name, ParamDecl& decl);

}  // namespace rib
