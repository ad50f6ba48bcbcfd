// texture_maker.cpp: texture making through the texture backend, and the backend's
// loading: the module libraydrive_oiio.so from the folder of the running binary (or the
// library search path), opened once, when a texture is first made or opened.
#include "texture_maker.h"

#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "texture_backend.h"

namespace rd {

TextureBackend& textureBackend() {
    static TextureBackend* backend = nullptr;
    static std::string failure;
    static std::once_flag once;
    std::call_once(once, [] {
        std::string here;
        char buf[4096];
        ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
        if (n > 0) here = std::filesystem::path(std::string(buf, size_t(n))).parent_path().string();
        const char* env = std::getenv("RAYDRIVE_TEXTURE_MODULE");
        std::string tried;
        for (const std::string& path :
             {std::string(env ? env : ""), here + "/libraydrive_oiio.so",
              here + "/../lib/libraydrive_oiio.so", std::string("libraydrive_oiio.so")}) {
            if (path.empty() || path == "/libraydrive_oiio.so") continue;
            void* h = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
            if (!h) {
                tried += std::string("\n  ") + ::dlerror();
                continue;
            }
            using Entry = TextureBackend* (*)();
            auto entry = reinterpret_cast<Entry>(::dlsym(h, "raydrive_texture_backend"));
            if (entry) {
                backend = entry();
                return;
            }
            tried += "\n  " + path + ": no raydrive_texture_backend";
        }
        failure = "the texture module (OpenImageIO) could not be loaded:" + tried;
    });
    if (!backend) throw std::runtime_error(failure);
    return *backend;
}

void makeTexture(const std::string& picture, const std::string& texture,
                 const MakeTextureOptions& opts) {
    textureBackend().makeTexture(picture, texture, opts);
}

void makeLatLongEnvironment(const std::string& picture, const std::string& texture,
                            const MakeTextureOptions& opts) {
    textureBackend().makeLatLongEnvironment(picture, texture, opts);
}

void makeCubeFaceEnvironment(const std::array<std::string, 6>& faces, const std::string& texture,
                             float fovDegrees, const MakeTextureOptions& opts) {
    textureBackend().makeCubeFaceEnvironment(faces, texture, fovDegrees, opts);
}

void makeShadow(const std::string& picture, const std::string& texture) {
    textureBackend().makeShadow(picture, texture);
}

}  // namespace rd
