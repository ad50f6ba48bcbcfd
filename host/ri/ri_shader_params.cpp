// ri_shader_params.cpp: a shader's parameter declarations from its source.
#include "ri_shader_params.h"

#include <sstream>

#include "compiler.h"
#include "shaders/shader_path.h"

namespace rd::ri {
namespace {

const char* typeName(rsl::BaseType t) {
    switch (t) {
        case rsl::BaseType::Float:
            return "float";
        case rsl::BaseType::Point:
            return "point";
        case rsl::BaseType::Vector:
            return "vector";
        case rsl::BaseType::Normal:
            return "normal";
        case rsl::BaseType::Color:
            return "color";
        case rsl::BaseType::Matrix:
            return "matrix";
        case rsl::BaseType::String:
            return "string";
        default:
            return nullptr;
    }
}

}  // namespace

void ShaderParams::setSearchPath(const std::string& value) {
    m_optionPath = updatedSearchPath(m_optionPath, value);
    m_shaders.clear();  // (another folder may hold another shader of a name)
}

std::string ShaderParams::declaration(const std::string& shader,
                                      const std::string& param) {
    auto it = m_shaders.find(shader);
    if (it == m_shaders.end()) {
        std::map<std::string, std::string>& decls = m_shaders[shader];
        const std::vector<std::string> path = shaderSearchPath(m_optionPath, "");
        const std::string file = findShaderFile(path, shader);
        std::ostringstream quiet;  // (the renderer reports a bad shader where it is used)
        rsl::Diagnostics diag(&quiet);
        rsl::Program prog;
        rsl::PreprocessOptions opts;
        opts.includeDirs = path;
        if (!file.empty() && rsl::compileFile(file, opts, prog, diag))
            for (const auto& sh : prog.shaders) {
                if (sh->name != shader && prog.shaders.size() != 1) continue;
                for (const rsl::ParamInfo& p : rsl::collectInfo(*sh).params) {
                    const char* type = typeName(p.type.base);
                    if (!type || p.type.arraySize < 0) continue;  // (unsized: no count)
                    std::string decl =
                        std::string(p.varying ? "varying " : "uniform ") + type;
                    if (p.type.arraySize > 0)
                        decl += "[" + std::to_string(p.type.arraySize) + "]";
                    decls[p.name] = decl;
                }
            }
        it = m_shaders.find(shader);
    }
    auto found = it->second.find(param);
    return found == it->second.end() ? std::string() : found->second;
}

}  // namespace rd::ri
