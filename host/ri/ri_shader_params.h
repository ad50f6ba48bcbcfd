// ri_shader_params.h: the declarations of a shader's own parameters, for the Ri calls
// that name a shader (RiSurface, RiLightSource, ...): C passes a value as a bare pointer,
// so a parameter RiDeclare and RI's standard names do not cover is sized from the
// shader's source (NAME.sl on the shader search path, read by rsl2cl's front end once
// per shader), as PRMan reads a compiled shader's declarations.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace rd::ri {

class ShaderParams {
public:
    // After `Option "searchpath" "shader"` gives `value`.
    void setSearchPath(const std::string& value);
    // The declaration of parameter `param` of shader `shader` ("uniform float",
    // "varying color", "uniform float[3]"); "" when the shader or the parameter is not
    // found (or the shader does not compile).
    std::string declaration(const std::string& shader, const std::string& param);

private:
    std::vector<std::string> m_optionPath;
    // by shader name: its parameters' declarations by name (empty: not found)
    std::map<std::string, std::map<std::string, std::string>> m_shaders;
};

}  // namespace rd::ri
