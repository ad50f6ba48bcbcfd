// shader_path.cpp: the shader search path (shader_path.h).
#include "shader_path.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace rd {

std::vector<std::string> updatedSearchPath(const std::vector<std::string>& old,
                                           const std::string& value) {
    std::vector<std::string> out;
    size_t start = 0;
    while (start <= value.size()) {
        size_t end = value.find(':', start);
        if (end == std::string::npos) end = value.size();
        const std::string dir = value.substr(start, end - start);
        if (dir == "&")
            out.insert(out.end(), old.begin(), old.end());
        else if (!dir.empty())
            out.push_back(dir);
        start = end + 1;
    }
    return out;
}

std::vector<std::string> shaderSearchPath(const std::vector<std::string>& optionPath,
                                          const std::string& sceneDir) {
    std::vector<std::string> path = optionPath;
    path.push_back(sceneDir.empty() ? "." : sceneDir);
    path.push_back(".");
    if (const char* env = std::getenv("RAYDRIVE_SHADER_PATH")) {
        std::stringstream ss(env);
        for (std::string d; std::getline(ss, d, ':');)
            if (!d.empty()) path.push_back(d);
    }
    path.push_back(RAYDRIVE_SHADER_DIR);
    return path;
}

std::string findShaderFile(const std::vector<std::string>& path,
                           const std::string& name) {
    for (const std::string& dir : path) {
        const std::filesystem::path candidate =
            std::filesystem::path(dir) / (name + ".sl");
        std::error_code ec;
        if (std::filesystem::exists(candidate, ec)) return candidate.string();
    }
    return "";
}

}  // namespace rd
