// texture_maker.cpp: texture making through OpenImageIO's make_texture (maketx): tiled
// (RT_TEX_TILE), mip-mapped, float, OpenEXR, with the wrap modes in its metadata.
#include "texture_maker.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "cl/include/texture.h"

namespace rd {
namespace {

namespace OIIO = OIIO_NAMESPACE;

OIIO::ImageSpec config(const MakeTextureOptions& o) {
    if (wrapModeOf(o.swrap) < 0 || wrapModeOf(o.twrap) < 0)
        throw std::runtime_error("wrap mode \"" + (wrapModeOf(o.swrap) < 0 ? o.swrap : o.twrap) +
                                 "\" is not black, periodic or clamp");
    OIIO::ImageSpec c;
    c.tile_width = c.tile_height = RT_TEX_TILE;
    c.set_format(OIIO::TypeDesc::FLOAT);
    c.attribute("maketx:fileformatname", "openexr");
    c.attribute("wrapmodes", o.swrap + "," + o.twrap);
    // RI filter names that OpenImageIO knows by the same name; others fall back to box
    static const char* known[] = {"box", "triangle", "gaussian", "catmull-rom", "sinc",
                                  "mitchell", "blackman-harris", "lanczos3"};
    std::string f = "box";
    for (const char* k : known)
        if (o.filter == k) f = k;
    c.attribute("maketx:filtername", f);
    c.attribute("maketx:forcefloat", 1);
    return c;
}

void make(OIIO::ImageBufAlgo::MakeTextureMode mode, const OIIO::ImageBuf& in,
          const std::string& out, const OIIO::ImageSpec& c) {
    std::ostringstream log;
    if (!OIIO::ImageBufAlgo::make_texture(mode, in, out, c, &log))
        throw std::runtime_error("cannot make texture \"" + out + "\": " +
                                 OIIO::geterror() + log.str());
}

OIIO::ImageBuf read(const std::string& picture) {
    OIIO::ImageBuf in(picture);
    if (!in.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error("cannot read image \"" + picture + "\": " + in.geterror());
    return in;
}

}  // namespace

int wrapModeOf(const std::string& name) {
    if (name == "black") return int(RT_WRAP_BLACK);
    if (name == "periodic") return int(RT_WRAP_PERIODIC);
    if (name == "clamp") return int(RT_WRAP_CLAMP);
    return -1;
}

void makeTexture(const std::string& picture, const std::string& texture,
                 const MakeTextureOptions& opts) {
    make(OIIO::ImageBufAlgo::MakeTxTexture, read(picture), texture, config(opts));
}

void makeLatLongEnvironment(const std::string& picture, const std::string& texture,
                            const MakeTextureOptions& opts) {
    MakeTextureOptions o = opts;
    o.swrap = "periodic";
    o.twrap = "clamp";
    make(OIIO::ImageBufAlgo::MakeTxEnvLatl, read(picture), texture, config(o));
}

void makeCubeFaceEnvironment(const std::array<std::string, 6>& faces, const std::string& texture,
                             float fovDegrees, const MakeTextureOptions& opts) {
    std::vector<OIIO::ImageBuf> in;
    for (const std::string& f : faces) in.push_back(read(f));
    const int size = std::max(1, in[0].spec().width);
    const int nch = std::min(4, in[0].spec().nchannels);
    OIIO::ImageSpec spec(4 * size, 2 * size, nch, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf latlong(spec);
    // A face's field of view above 90 degrees leaves a border the cube does not need.
    const float scale = 1.0f / std::tan(0.5f * fovDegrees * 3.14159265f / 180.0f);
    std::vector<float> px(static_cast<size_t>(nch), 0.0f);
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x) {
            // the lat-long direction of this texel (environment(): +y up, s = 0.5 along -z)
            float s = (x + 0.5f) / float(spec.width), t = (y + 0.5f) / float(spec.height);
            float phi = (s - 0.5f) * 2.0f * 3.14159265f, theta = t * 3.14159265f;
            float dx = std::sin(theta) * std::sin(phi), dy = std::cos(theta),
                  dz = -std::sin(theta) * std::cos(phi);
            float ax = std::fabs(dx), ay = std::fabs(dy), az = std::fabs(dz);
            // the face it leaves through, and where on it (u right, v down as an image)
            int face;
            float u, v, m;
            if (ax >= ay && ax >= az) face = dx > 0 ? 0 : 1, m = ax, u = dx > 0 ? -dz : dz, v = -dy;
            else if (ay >= az) face = dy > 0 ? 2 : 3, m = ay, u = dx, v = dy > 0 ? dz : -dz;
            else face = dz > 0 ? 4 : 5, m = az, u = dz > 0 ? dx : -dx, v = -dy;
            u = 0.5f + 0.5f * u / m * scale;
            v = 0.5f + 0.5f * v / m * scale;
            const OIIO::ImageBuf& f = in[size_t(face)];
            f.interppixel_NDC(u, v, px.data(), OIIO::ImageBuf::WrapClamp);
            latlong.setpixel(x, y, px.data(), nch);
        }
    MakeTextureOptions o = opts;
    o.swrap = "periodic";
    o.twrap = "clamp";
    make(OIIO::ImageBufAlgo::MakeTxEnvLatl, latlong, texture, config(o));
}

void makeShadow(const std::string& picture, const std::string& texture) {
    OIIO::ImageBuf in = read(picture);
    if (!in.spec().find_attribute("worldtoscreen") || !in.spec().find_attribute("worldtocamera"))
        throw std::runtime_error("depth map \"" + picture + "\" has no \"worldtoscreen\" and "
                                 "\"worldtocamera\" matrices: not a shadow depth map");
    MakeTextureOptions o;
    o.swrap = o.twrap = "clamp";
    make(OIIO::ImageBufAlgo::MakeTxShadow, in, texture, config(o));
}

}  // namespace rd
