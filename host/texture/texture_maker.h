// texture_maker.h: RI texture making (MakeTexture, MakeLatLongEnvironment,
// MakeCubeFaceEnvironment, MakeShadow, and `raydrive txmake`): any image OpenImageIO
// reads (TIFF, PNG, JPEG, OpenEXR, HDR, ...) becomes a tiled, mip-mapped float OpenEXR
// file that carries its wrap modes, which is what the renderer's texture tiles stream
// from. Errors are exceptions (std::runtime_error) naming the file. The work is done by
// the texture backend (texture_backend.h), loaded on first use.
#pragma once
#include <array>
#include <string>

namespace rd {

struct MakeTextureOptions {
    std::string swrap = "black", twrap = "black";  // "black" | "periodic" | "clamp"
    std::string filter = "box";                     // RI filter name for the mip levels
    float swidth = 1.0f, twidth = 1.0f;             // filter widths (RI; box uses 1)
};

// A 2D texture.
void makeTexture(const std::string& picture, const std::string& texture,
                 const MakeTextureOptions& opts);
// A lat-long environment map (longitude along s from -x, latitude along t from +y).
void makeLatLongEnvironment(const std::string& picture, const std::string& texture,
                            const MakeTextureOptions& opts);
// Six cube faces (+x -x +y -y +z -z, each seen with field of view fov degrees)
// resampled into a lat-long environment map.
void makeCubeFaceEnvironment(const std::array<std::string, 6>& faces, const std::string& texture,
                             float fovDegrees, const MakeTextureOptions& opts);
// A depth map (one channel of camera-space z, with the light's "worldtocamera" and
// "worldtoscreen" matrices in its metadata, as zfiles and OpenEXR depth renders carry)
// into a shadow map.
void makeShadow(const std::string& picture, const std::string& texture);

// The wrap mode a name stands for (RT_WRAP_*: black 0, periodic 1, clamp 2), or -1.
inline int wrapModeOf(const std::string& name) {
    return name == "black" ? 0 : name == "periodic" ? 1 : name == "clamp" ? 2 : -1;
}

}  // namespace rd
