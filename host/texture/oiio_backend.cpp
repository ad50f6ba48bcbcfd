// oiio_backend.cpp: the texture backend (texture_backend.h) on OpenImageIO, built as the
// module libraydrive_oiio.so: texture making through make_texture (maketx): tiled
// (RT_TEX_TILE), mip-mapped, float, OpenEXR, with the wrap modes in its metadata; and
// describing and reading images through a private ImageCache.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cl/include/texture.h"
#include "texture_backend.h"
#include "texture_maker.h"

namespace rd {
namespace {

namespace OIIO = OIIO_NAMESPACE;

// The most pixels a picture made into a texture may have: as many as a frame (Format's
// 2^28). The header is read first: a 436-byte PNG may claim 60000 x 60000 pixels, and its
// read then asked for 43 GB.
constexpr uint64_t kMaxPicturePixels = uint64_t(1) << 28;

// OpenImageIO's errors, which may span lines (each library's own), as one line.
std::string oneLine(std::string e) {
    while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
    for (size_t i = 0; (i = e.find('\n', i)) != std::string::npos;) e.replace(i, 1, "; ");
    return e;
}

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
                                 oneLine(OIIO::geterror() + log.str()));
}

OIIO::ImageBuf readPicture(const std::string& picture) {
    OIIO::ImageBuf in(picture);
    if (!in.init_spec(picture, 0, 0))
        throw std::runtime_error("cannot read image \"" + picture + "\": " + oneLine(in.geterror()));
    const OIIO::ImageSpec& s = in.spec();
    if (s.width <= 0 || s.height <= 0 || uint64_t(s.width) * uint64_t(s.height) > kMaxPicturePixels)
        throw std::runtime_error("image \"" + picture + "\" is " + std::to_string(s.width) + " x " +
                                 std::to_string(s.height) +
                                 " pixels: a texture may have at most 2^28 (16384 x 16384)");
    if (!in.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error("cannot read image \"" + picture + "\": " + oneLine(in.geterror()));
    return in;
}

}  // namespace

class OiioBackend : public TextureBackend {
public:
    OiioBackend() { m_ic->attribute("max_memory_MB", 512.0f); }
    ~OiioBackend() override { OIIO::ImageCache::destroy(m_ic); }

    bool describe(const std::string& file, ImageInfo& info, std::string* error) override {
        OIIO::ImageSpec spec;
        if (!m_ic->get_imagespec(OIIO::ustring(file), spec, 0, 0)) {
            if (error) *error = oneLine(m_ic->geterror());
            return false;
        }
        info.width = spec.width;
        info.height = spec.height;
        info.channels = spec.nchannels;
        info.tiled = spec.tile_width > 0;
        info.levels = 1;
        for (OIIO::ImageSpec s; info.levels < 16 &&
                                m_ic->get_imagespec(OIIO::ustring(file), s, 0, info.levels);)
            ++info.levels;
        (void)m_ic->geterror();  // the probe past the last level leaves an error behind
        info.wrapmodes = spec.get_string_attribute("wrapmodes", "");
        info.textureformat = spec.get_string_attribute("textureformat", "");
        const OIIO::ParamValue* ms = spec.find_attribute("worldtoscreen", OIIO::TypeMatrix);
        const OIIO::ParamValue* mc = spec.find_attribute("worldtocamera", OIIO::TypeMatrix);
        info.hasMatrices = ms && mc;
        if (info.hasMatrices) {
            const float* s = static_cast<const float*>(ms->data());
            const float* c = static_cast<const float*>(mc->data());
            std::copy(s, s + 16, info.worldToScreen.begin());
            std::copy(c, c + 16, info.worldToCamera.begin());
        }
        return true;
    }

    bool read(const std::string& file, int level, int x0, int x1, int y0, int y1, int channels,
              float* out, size_t xstride, size_t ystride, std::string* error) override {
        if (m_ic->get_pixels(OIIO::ustring(file), 0, level, x0, x1, y0, y1, 0, 1, 0, channels,
                             OIIO::TypeFloat, out, OIIO::stride_t(xstride), OIIO::stride_t(ystride)))
            return true;
        if (error) *error = oneLine(m_ic->geterror());
        return false;
    }

    void makeTexture(const std::string& picture, const std::string& texture,
                     const MakeTextureOptions& opts) override;
    void makeLatLongEnvironment(const std::string& picture, const std::string& texture,
                                const MakeTextureOptions& opts) override;
    void makeCubeFaceEnvironment(const std::array<std::string, 6>& faces,
                                 const std::string& texture, float fovDegrees,
                                 const MakeTextureOptions& opts) override;
    void makeShadow(const std::string& picture, const std::string& texture) override;
    void writePicture(const std::string& file, int width, int height, int channels,
                      const float* pixels, int bits) override {
        OIIO::ImageSpec spec(width, height, channels,
                             bits == 8    ? OIIO::TypeDesc::UINT8
                             : bits == 16 ? OIIO::TypeDesc::UINT16
                                          : OIIO::TypeDesc::FLOAT);
        if (channels == 4) spec.alpha_channel = 3;
        auto out = OIIO::ImageOutput::create(file);
        if (!out)
            throw std::runtime_error("cannot write \"" + file +
                                     "\": " + oneLine(OIIO::geterror()));
        if (!out->open(file, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels) ||
            !out->close())
            throw std::runtime_error("cannot write \"" + file +
                                     "\": " + oneLine(out->geterror()));
    }

private:
    OIIO::ImageCache* m_ic = OIIO::ImageCache::create(false);  // a private cache
};

void OiioBackend::makeTexture(const std::string& picture, const std::string& texture,
                 const MakeTextureOptions& opts) {
    make(OIIO::ImageBufAlgo::MakeTxTexture, readPicture(picture), texture, config(opts));
}

void OiioBackend::makeLatLongEnvironment(const std::string& picture, const std::string& texture,
                            const MakeTextureOptions& opts) {
    MakeTextureOptions o = opts;
    o.swrap = "periodic";
    o.twrap = "clamp";
    make(OIIO::ImageBufAlgo::MakeTxEnvLatl, readPicture(picture), texture, config(o));
}

void OiioBackend::makeCubeFaceEnvironment(const std::array<std::string, 6>& faces, const std::string& texture,
                             float fovDegrees, const MakeTextureOptions& opts) {
    std::vector<OIIO::ImageBuf> in;
    for (const std::string& f : faces) in.push_back(readPicture(f));
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

void OiioBackend::makeShadow(const std::string& picture, const std::string& texture) {
    OIIO::ImageBuf in = readPicture(picture);
    if (!in.spec().find_attribute("worldtoscreen") || !in.spec().find_attribute("worldtocamera"))
        throw std::runtime_error("depth map \"" + picture + "\" has no \"worldtoscreen\" and "
                                 "\"worldtocamera\" matrices: not a shadow depth map");
    MakeTextureOptions o;
    o.swrap = o.twrap = "clamp";
    make(OIIO::ImageBufAlgo::MakeTxShadow, in, texture, config(o));
}

}  // namespace rd

extern "C" rd::TextureBackend* raydrive_texture_backend() {
    static rd::OiioBackend backend;
    return &backend;
}
