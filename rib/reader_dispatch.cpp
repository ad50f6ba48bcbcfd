// reader_dispatch.cpp: the last step of reading a request: hand it to the family that
// owns it (blocks in reader_scope.cpp, geometry in reader_geometry.cpp), or here for
// options, attributes, shaders, transformations and declarations, with their own checks
// (Format limits, ColorSamples shapes, Basis names). A request that fails a check is
// reported and not forwarded, so a Target only ever sees well-formed data.
#include "reader_impl.h"

namespace rib {
namespace detail {

namespace {

struct NamedBasis {
    const char* name;
    float m[16];
    int step;
};

const float kSixth = 1.0f / 6.0f;
const NamedBasis kBases[] = {
    {"bezier", {-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0}, 3},
    {"b-spline",
     {-kSixth, 3 * kSixth, -3 * kSixth, kSixth, 3 * kSixth, -6 * kSixth, 3 * kSixth, 0,
      -3 * kSixth, 0, 3 * kSixth, 0, kSixth, 4 * kSixth, kSixth, 0},
     1},
    {"catmull-rom",
     {-0.5f, 1.5f, -1.5f, 0.5f, 1, -2.5f, 2, -0.5f, -0.5f, 0, 0.5f, 0, 0, 1, 0, 0},
     1},
    {"hermite", {2, 1, -2, 1, -3, -2, 3, -1, 0, 1, 0, 0, 1, 0, 0, 0}, 2},
    {"power", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, 4},
};

}  // namespace

bool Reader::basisMatrix(const std::string& name, const double* nums, float m[16],
                         const SourceLoc& loc) {
    if (name.empty()) {
        for (int i = 0; i < 16; ++i) m[i] = static_cast<float>(nums[i]);
        return true;
    }
    for (const NamedBasis& b : kBases) {
        if (name == b.name) {
            for (int i = 0; i < 16; ++i) m[i] = b.m[i];
            return true;
        }
    }
    error(loc, "Basis: unknown basis \"" + name +
                   "\" (bezier, b-spline, catmull-rom, hermite, power)");
    return false;
}

void Reader::dispatch(const RequestInfo& info, const Args& a, const SourceLoc& loc) {
    if (dispatchBlock(info, a, loc)) return;
    if (dispatchGeometry(info, a, loc)) return;
    if (dispatchOption(info, a, loc)) return;
    if (dispatchShading(info, a, loc)) return;
    if (dispatchAttribute(info, a, loc)) return;
    dispatchTransformOrTexture(info, a, loc);
}

// Options: the camera, the image, the display, Option itself.
bool Reader::dispatchOption(const RequestInfo& info, const Args& a,
                            const SourceLoc& loc) {
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    switch (info.req) {
        case Req::Format:
            // (a pixel aspect of -1 is the default, 1: RI 3.2, the RenderMan Companion)
            if (v.n(0) < 1 || v.n(1) < 1 || v.n(0) > m_opts.maxResolution ||
                v.n(1) > m_opts.maxResolution || !(v.f(2) > 0 || v.f(2) == -1.0f)) {
                error(loc, "Format " + std::to_string(v.n(0)) + "x" +
                               std::to_string(v.n(1)) + " is out of range (1.." +
                               std::to_string(m_opts.maxResolution) +
                               " pixels, positive pixel aspect or -1)");
                break;
            }
            t.format(loc, v.n(0), v.n(1), v.f(2));
            break;
        case Req::FrameAspectRatio:
            t.frameAspectRatio(loc, v.f(0));
            break;
        case Req::ScreenWindow:
            t.screenWindow(loc, v.f(0), v.f(1), v.f(2), v.f(3));
            break;
        case Req::CropWindow:
            t.cropWindow(loc, v.f(0), v.f(1), v.f(2), v.f(3));
            break;
        case Req::Projection:
            t.projection(loc, v.s(0), P);
            break;
        case Req::Clipping:
            t.clipping(loc, v.f(0), v.f(1));
            break;
        case Req::ClippingPlane:
            t.clippingPlane(loc, v.f(0), v.f(1), v.f(2), v.f(3), v.f(4), v.f(5));
            break;
        case Req::Camera:
            t.camera(loc, v.s(0), P);
            break;
        case Req::DepthOfField:
            if (a.optionalMissing)
                t.depthOfField(loc, HUGE_VALF, 0.f, 0.f);
            else
                t.depthOfField(loc, v.f(0), v.f(1), v.f(2));
            break;
        case Req::Shutter:
            t.shutter(loc, v.f(0), v.f(1));
            break;
        case Req::PixelVariance:
            t.pixelVariance(loc, v.f(0));
            break;
        case Req::PixelSamples:
            t.pixelSamples(loc, v.f(0), v.f(1));
            break;
        case Req::PixelFilter:
            t.pixelFilter(loc, v.s(0), v.f(0), v.f(1));
            break;
        case Req::Exposure:
            t.exposure(loc, v.f(0), v.f(1));
            break;
        case Req::Imager:
            t.imager(loc, v.s(0), P);
            break;
        case Req::Quantize:
            t.quantize(loc, v.s(0), v.n(0), v.n(1), v.n(2), v.f(3));
            break;
        case Req::Display:
            t.display(loc, v.s(0), v.s(1), v.s(2), P);
            break;
        case Req::DisplayChannel:
            t.displayChannel(loc, v.s(0), P);
            break;
        case Req::Hider:
            t.hider(loc, v.s(0), P);
            break;
        case Req::ColorSamples: {
            const std::vector<float> nRGB = v.fa(0), RGBn = v.fa(1);
            if (nRGB.empty() || nRGB.size() % 3 != 0 || nRGB.size() != RGBn.size()) {
                error(loc, "ColorSamples needs two arrays of 3n numbers (nRGB, RGBn), got " +
                               std::to_string(nRGB.size()) + " and " +
                               std::to_string(RGBn.size()));
                break;
            }
            m_nColor = static_cast<int>(nRGB.size() / 3);
            m_nRGB = nRGB;
            t.colorSamples(loc, nRGB, RGBn);
            break;
        }
        case Req::RelativeDetail:
            t.relativeDetail(loc, v.f(0));
            break;
        case Req::Option:
            noteOption(v.s(0), P);
            noteCondValues(false, v.s(0), P);
            t.option(loc, v.s(0), P);
            break;
        case Req::ErrorHandler: {
            const std::string h = v.s(0);
            if (h == "print" || h == "ignore" || h == "abort") {
                t.errorHandler(loc, h);
                m_diag.setMode(h == "print"    ? ErrorMode::Print
                               : h == "ignore" ? ErrorMode::Ignore
                                               : ErrorMode::Abort);
            } else {
                error(loc, "ErrorHandler: unknown handler \"" + h +
                               "\" (print, ignore, abort)");
            }
            break;
        }
        case Req::ReadArchive:
            if (m_opts.expandArchives)
                readArchive(v.s(0), P, loc);
            else
                t.readArchive(loc, v.s(0), P);
            break;
        default:
            return false;
    }
    return true;
}

// The shading attributes: colours, shaders and lights.
bool Reader::dispatchShading(const RequestInfo& info, const Args& a,
                             const SourceLoc& loc) {
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    switch (info.req) {
        case Req::Color:
            t.color(loc, v.fa(0));
            break;
        case Req::Opacity:
            t.opacity(loc, v.fa(0));
            break;
        case Req::TextureCoordinates:
            t.textureCoordinates(loc, v.f(0), v.f(1), v.f(2), v.f(3), v.f(4), v.f(5),
                                 v.f(6), v.f(7));
            break;
        case Req::Surface:
            t.surface(loc, v.s(0), P);
            break;
        case Req::Displacement:
            t.displacement(loc, v.s(0), P);
            break;
        case Req::Atmosphere:
            t.atmosphere(loc, v.s(0), P);
            break;
        case Req::Interior:
            t.interior(loc, v.s(0), P);
            break;
        case Req::Exterior:
            t.exterior(loc, v.s(0), P);
            break;
        case Req::Deformation:
            t.deformation(loc, v.s(0), P);
            break;
        case Req::LightSource:
            t.lightSource(loc, v.s(0), v.s(1), P);
            break;
        case Req::AreaLightSource:
            t.areaLightSource(loc, v.s(0), v.s(1), P);
            break;
        case Req::Illuminate:
            t.illuminate(loc, v.s(0), v.n(0) != 0);
            break;
        case Req::ShadingRate:
            t.shadingRate(loc, v.f(0));
            break;
        case Req::ShadingInterpolation:
            if (v.s(0) != "constant" && v.s(0) != "smooth") {
                error(
                    loc,
                    "ShadingInterpolation: expected \"constant\" or \"smooth\", got \"" +
                        v.s(0) + "\"");
                break;
            }
            t.shadingInterpolation(loc, v.s(0));
            break;
        case Req::Matte:
            t.matte(loc, v.n(0) != 0);
            break;
        default:
            return false;
    }
    return true;
}

// The other attributes, and declarations.
bool Reader::dispatchAttribute(const RequestInfo& info, const Args& a,
                               const SourceLoc& loc) {
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    float m[16], m2[16];
    switch (info.req) {
        case Req::Resource:
            resource(a, loc);
            break;
        case Req::Attribute:
            noteCondValues(true, v.s(0), P);
            t.attribute(loc, v.s(0), P);
            break;
        case Req::GeometricRepresentation:
            t.geometricRepresentation(loc, v.s(0));
            break;
        case Req::Bound:
        case Req::Detail:
            for (size_t i = 0; i < 6; ++i) m[i] = v.f(i);
            if (info.req == Req::Bound)
                t.bound(loc, m);
            else
                t.detail(loc, m);
            break;
        case Req::DetailRange:
            t.detailRange(loc, v.f(0), v.f(1), v.f(2), v.f(3));
            break;
        case Req::GeometricApproximation:
            t.geometricApproximation(loc, v.s(0), v.f(0));
            break;
        case Req::Sides:
            if (v.n(0) != 1 && v.n(0) != 2) {
                error(loc, "Sides must be 1 or 2, got " + std::to_string(v.n(0)));
                break;
            }
            t.sides(loc, v.n(0));
            break;
        case Req::Orientation:
            t.orientation(loc, v.s(0));
            break;
        case Req::ReverseOrientation:
            t.reverseOrientation(loc);
            break;
        case Req::Basis: {
            // nums: 16 (u basis), ustep, 16 (v basis), vstep; strs: the two names.
            if (a.nums.size() != 34 || a.strs.size() != 2) break;
            if (!basisMatrix(v.s(0), &a.nums[0], m, loc) ||
                !basisMatrix(v.s(1), &a.nums[17], m2, loc))
                break;
            if (v.n(16) < 1 || v.n(33) < 1) {
                error(loc, "Basis steps must be at least 1");
                break;
            }
            m_ustep = v.n(16);
            m_vstep = v.n(33);
            t.basis(loc, v.s(0), m, v.n(16), v.s(1), m2, v.n(33));
            break;
        }
        case Req::Declare: {
            ParamDecl decl;
            std::string unused;
            if (!parseParamDecl(v.s(1), false, decl, unused)) {
                error(loc, "Declare: bad declaration \"" + v.s(1) + "\" for \"" + v.s(0) +
                               "\"");
                break;
            }
            m_declared[v.s(0)] = decl;
            t.declare(loc, v.s(0), v.s(1));
            break;
        }
        default:
            return false;
    }
    return true;
}

// Transformations and coordinate systems; texture making (strs and nums in signature
// order).
bool Reader::dispatchTransformOrTexture(const RequestInfo& info, const Args& a,
                                        const SourceLoc& loc) {
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    float m[16];
    switch (info.req) {
        case Req::Identity:
            t.identity(loc);
            break;
        case Req::Transform:
        case Req::ConcatTransform:
            for (size_t i = 0; i < 16; ++i) m[i] = v.f(i);
            if (info.req == Req::Transform)
                t.transform(loc, m);
            else
                t.concatTransform(loc, m);
            break;
        case Req::Perspective:
            t.perspective(loc, v.f(0));
            break;
        case Req::Translate:
            t.translate(loc, v.f(0), v.f(1), v.f(2));
            break;
        case Req::Rotate:
            t.rotate(loc, v.f(0), v.f(1), v.f(2), v.f(3));
            break;
        case Req::Scale:
            t.scale(loc, v.f(0), v.f(1), v.f(2));
            break;
        case Req::Skew:
            t.skew(loc, v.f(0), v.f(1), v.f(2), v.f(3), v.f(4), v.f(5), v.f(6));
            break;
        case Req::CoordinateSystem:
            t.coordinateSystem(loc, v.s(0));
            break;
        case Req::ScopedCoordinateSystem:
            t.scopedCoordinateSystem(loc, v.s(0));
            break;
        case Req::CoordSysTransform:
            t.coordSysTransform(loc, v.s(0));
            break;

        // Texture making
        case Req::MakeTexture:
            t.makeTexture(loc, v.s(0), v.s(1), v.s(2), v.s(3), v.s(4), v.f(0), v.f(1), P);
            break;
        case Req::MakeBump:
            t.makeBump(loc, v.s(0), v.s(1), v.s(2), v.s(3), v.s(4), v.f(0), v.f(1), P);
            break;
        case Req::MakeLatLongEnvironment:
            t.makeLatLongEnvironment(loc, v.s(0), v.s(1), v.s(2), v.f(0), v.f(1), P);
            break;
        case Req::MakeCubeFaceEnvironment:
            t.makeCubeFaceEnvironment(loc,
                                      {v.s(0), v.s(1), v.s(2), v.s(3), v.s(4), v.s(5)},
                                      v.s(6), v.f(0), v.s(7), v.f(1), v.f(2), P);
            break;
        case Req::MakeShadow:
            t.makeShadow(loc, v.s(0), v.s(1), P);
            break;
        default:
            return false;
    }
    return true;
}

void Reader::resource(const Args& a, const SourceLoc& loc) {
    const std::string name = a.strs[0], type = a.strs[1];
    if (type != "attributes") {
        m_diag.warning(
            loc, "Resource type \"" + type + "\" is not supported (attributes); ignored");
        return;
    }
    const std::string op = a.params.getString("operation", "");
    const std::string subset = a.params.getString("subset", "all");
    if (op != "save" && op != "restore") {
        error(loc, "Resource \"" + name +
                       "\": \"string operation\" must be \"save\" or \"restore\"");
        return;
    }
    if (subset != "all" && subset != "shading" && subset != "transform") {
        error(loc, "Resource \"" + name + "\": unknown subset \"" + subset +
                       "\" (all, shading, transform)");
        return;
    }
    if (op == "save") {
        m_resources.back()[name] = ReaderAttributes{m_ustep, m_vstep, m_condAttributes};
    } else {
        const ReaderAttributes* saved = nullptr;
        for (auto it = m_resources.rbegin(); it != m_resources.rend() && !saved; ++it)
            if (auto found = it->find(name); found != it->end()) saved = &found->second;
        if (!saved) {
            error(loc, "Resource \"" + name +
                           "\" restored but never saved (or its "
                           "ResourceBegin block has ended)");
            return;
        }
        if (subset !=
            "transform") {  // (the Basis and user values are shading attributes)
            m_ustep = saved->ustep, m_vstep = saved->vstep;
            m_condAttributes = std::const_pointer_cast<CondValues>(saved->condAttributes);
        }
    }
    m_target.resource(loc, name, type, a.params);
}

}  // namespace detail
}  // namespace rib
