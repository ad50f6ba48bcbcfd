// shader_path.h: where RSL shaders are looked for, shared by the renderer's ShaderSet and
// the Ri API (which reads a shader's parameter declarations for an RiSurface call): the
// path `Option "searchpath" "shader"` sets, then the scene file's folder, the current
// folder, $RAYDRIVE_SHADER_PATH and the standard shaders RayDrive ships.
#pragma once
#include <string>
#include <vector>

namespace rd {

// A search path after `Option "searchpath"` gives `value` ("dir:dir:&"; '&' stands for
// the path so far).
std::vector<std::string> updatedSearchPath(const std::vector<std::string>& old,
                                           const std::string& value);

// The whole shader path of a scene whose option path is `optionPath`, read from a file
// in `sceneDir` ("" for the current folder).
std::vector<std::string> shaderSearchPath(const std::vector<std::string>& optionPath,
                                          const std::string& sceneDir);

// NAME.sl in the first folder of `path` that has one; "" when none has.
std::string findShaderFile(const std::vector<std::string>& path, const std::string& name);

}  // namespace rd
