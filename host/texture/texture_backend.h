// texture_backend.h: what RayDrive asks of an image library for textures: making them
// (maketx), describing them and reading their texels; and for a Display that is not
// OpenEXR, writing its picture. OpenImageIO does it, in a module
// (libraydrive_oiio.so beside the binaries) loaded the first time a texture is made or
// opened: OpenImageIO brings ~200 shared libraries, whose loading would otherwise cost
// every render 0.1 s and 150 MB before it starts.
#pragma once
#include <array>
#include <string>

namespace rd {

struct MakeTextureOptions;

struct ImageInfo {
    int width = 0, height = 0, channels = 0;
    int levels = 1;        // mip levels
    bool tiled = false;
    std::string wrapmodes;      // "black,periodic", ... ("" none)
    std::string textureformat;  // "Plain Texture", "LatLong Environment", "Shadow" ("" none)
    bool hasMatrices = false;   // worldtoscreen and worldtocamera (row-major, p' = p M)
    std::array<float, 16> worldToScreen{}, worldToCamera{};
};

class TextureBackend {
public:
    virtual ~TextureBackend() = default;
    // false with *error set when the file cannot be read
    virtual bool describe(const std::string& file, ImageInfo& info, std::string* error) = 0;
    // Channels [0, channels) of [x0, x1) x [y0, y1) of mip level `level` as floats, a texel
    // every xstride bytes and a row every ystride bytes.
    virtual bool read(const std::string& file, int level, int x0, int x1, int y0, int y1,
                      int channels, float* out, size_t xstride, size_t ystride,
                      std::string* error) = 0;
    // Texture making (texture_maker.h); they throw std::runtime_error naming the file.
    virtual void makeTexture(const std::string& picture, const std::string& texture,
                             const MakeTextureOptions& opts) = 0;
    virtual void makeLatLongEnvironment(const std::string& picture, const std::string& texture,
                                        const MakeTextureOptions& opts) = 0;
    virtual void makeCubeFaceEnvironment(const std::array<std::string, 6>& faces,
                                         const std::string& texture, float fovDegrees,
                                         const MakeTextureOptions& opts) = 0;
    virtual void makeShadow(const std::string& picture, const std::string& texture) = 0;
    // Writes a picture in the format its name's extension says (TIFF, PNG, JPEG, ...):
    // `channels` floats a pixel, row by row, stored as `bits` 8 or 16 bit integers of
    // full scale 1 (values already quantized) or 32 bit floats. Throws
    // std::runtime_error naming the file.
    virtual void writePicture(const std::string& file, int width, int height,
                              int channels, const float* pixels, int bits) = 0;
};

// The backend, its module loaded on first use; throws std::runtime_error when the module
// cannot be loaded (it names the file and why).
TextureBackend& textureBackend();

}  // namespace rd

// The module's one entry point.
extern "C" rd::TextureBackend* raydrive_texture_backend();
