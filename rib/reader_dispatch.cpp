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
    dispatchOptionOrAttribute(info, a, loc);
}

bool Reader::dispatchOptionOrAttribute(const RequestInfo& info, const Args& a,
                                       const SourceLoc& loc) {
    // parseArgs guarantees the counts; the accessors are checked anyway so a table typo
    // can never index out of range.
    auto f = [&](size_t i) {
        return i < a.nums.size() ? static_cast<float>(a.nums[i]) : 0.f;
    };
    auto n = [&](size_t i) {
        return i < a.nums.size() ? static_cast<int>(a.nums[i]) : 0;
    };
    auto s = [&](size_t i) { return i < a.strs.size() ? a.strs[i] : std::string(); };
    auto fa = [&](size_t i) {
        return i < a.floatArrays.size() ? a.floatArrays[i] : std::vector<float>();
    };
    const std::string req = info.name;
    const ParamList& P = a.params;
    Target& t = m_target;
    float m[16], m2[16];
    switch (info.req) {
        // Options
        case Req::Format:
            // (a pixel aspect of -1 is the default, 1: RI 3.2, the RenderMan Companion)
            if (n(0) < 1 || n(1) < 1 || n(0) > m_opts.maxResolution ||
                n(1) > m_opts.maxResolution || !(f(2) > 0 || f(2) == -1.0f)) {
                error(loc, "Format " + std::to_string(n(0)) + "x" + std::to_string(n(1)) +
                               " is out of range (1.." +
                               std::to_string(m_opts.maxResolution) +
                               " pixels, positive pixel aspect or -1)");
                break;
            }
            t.format(loc, n(0), n(1), f(2));
            break;
        case Req::FrameAspectRatio:
            t.frameAspectRatio(loc, f(0));
            break;
        case Req::ScreenWindow:
            t.screenWindow(loc, f(0), f(1), f(2), f(3));
            break;
        case Req::CropWindow:
            t.cropWindow(loc, f(0), f(1), f(2), f(3));
            break;
        case Req::Projection:
            t.projection(loc, s(0), P);
            break;
        case Req::Clipping:
            t.clipping(loc, f(0), f(1));
            break;
        case Req::ClippingPlane:
            t.clippingPlane(loc, f(0), f(1), f(2), f(3), f(4), f(5));
            break;
        case Req::Camera:
            t.camera(loc, s(0), P);
            break;
        case Req::DepthOfField:
            if (a.optionalMissing)
                t.depthOfField(loc, HUGE_VALF, 0.f, 0.f);
            else
                t.depthOfField(loc, f(0), f(1), f(2));
            break;
        case Req::Shutter:
            t.shutter(loc, f(0), f(1));
            break;
        case Req::PixelVariance:
            t.pixelVariance(loc, f(0));
            break;
        case Req::PixelSamples:
            t.pixelSamples(loc, f(0), f(1));
            break;
        case Req::PixelFilter:
            t.pixelFilter(loc, s(0), f(0), f(1));
            break;
        case Req::Exposure:
            t.exposure(loc, f(0), f(1));
            break;
        case Req::Imager:
            t.imager(loc, s(0), P);
            break;
        case Req::Quantize:
            t.quantize(loc, s(0), n(0), n(1), n(2), f(3));
            break;
        case Req::Display:
            t.display(loc, s(0), s(1), s(2), P);
            break;
        case Req::DisplayChannel:
            t.displayChannel(loc, s(0), P);
            break;
        case Req::Hider:
            t.hider(loc, s(0), P);
            break;
        case Req::ColorSamples: {
            const std::vector<float> nRGB = fa(0), RGBn = fa(1);
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
            t.relativeDetail(loc, f(0));
            break;
        case Req::Option:
            noteOption(s(0), P);
            noteCondValues(false, s(0), P);
            t.option(loc, s(0), P);
            break;
        case Req::ErrorHandler: {
            const std::string h = s(0);
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
                readArchive(s(0), P, loc);
            else
                t.readArchive(loc, s(0), P);
            break;

        // Attributes
        case Req::Resource:
            resource(a, loc);
            break;
        case Req::Attribute:
            noteCondValues(true, s(0), P);
            t.attribute(loc, s(0), P);
            break;
        case Req::Color:
            t.color(loc, fa(0));
            break;
        case Req::Opacity:
            t.opacity(loc, fa(0));
            break;
        case Req::TextureCoordinates:
            t.textureCoordinates(loc, f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7));
            break;
        case Req::Surface:
            t.surface(loc, s(0), P);
            break;
        case Req::Displacement:
            t.displacement(loc, s(0), P);
            break;
        case Req::Atmosphere:
            t.atmosphere(loc, s(0), P);
            break;
        case Req::Interior:
            t.interior(loc, s(0), P);
            break;
        case Req::Exterior:
            t.exterior(loc, s(0), P);
            break;
        case Req::Deformation:
            t.deformation(loc, s(0), P);
            break;
        case Req::LightSource:
            t.lightSource(loc, s(0), s(1), P);
            break;
        case Req::AreaLightSource:
            t.areaLightSource(loc, s(0), s(1), P);
            break;
        case Req::Illuminate:
            t.illuminate(loc, s(0), n(0) != 0);
            break;
        case Req::ShadingRate:
            t.shadingRate(loc, f(0));
            break;
        case Req::ShadingInterpolation:
            if (s(0) != "constant" && s(0) != "smooth") {
                error(loc, "ShadingInterpolation: expected \"constant\" or \"smooth\", got \"" +
                               s(0) + "\"");
                break;
            }
            t.shadingInterpolation(loc, s(0));
            break;
        case Req::Matte:
            t.matte(loc, n(0) != 0);
            break;
        case Req::GeometricRepresentation:
            t.geometricRepresentation(loc, s(0));
            break;
        case Req::Bound:
        case Req::Detail:
            for (size_t i = 0; i < 6; ++i) m[i] = f(i);
            if (info.req == Req::Bound)
                t.bound(loc, m);
            else
                t.detail(loc, m);
            break;
        case Req::DetailRange:
            t.detailRange(loc, f(0), f(1), f(2), f(3));
            break;
        case Req::GeometricApproximation:
            t.geometricApproximation(loc, s(0), f(0));
            break;
        case Req::Sides:
            if (n(0) != 1 && n(0) != 2) {
                error(loc, "Sides must be 1 or 2, got " + std::to_string(n(0)));
                break;
            }
            t.sides(loc, n(0));
            break;
        case Req::Orientation:
            t.orientation(loc, s(0));
            break;
        case Req::ReverseOrientation:
            t.reverseOrientation(loc);
            break;
        case Req::Basis: {
            // nums: 16 (u basis), ustep, 16 (v basis), vstep; strs: the two names.
            if (a.nums.size() != 34 || a.strs.size() != 2) break;
            if (!basisMatrix(s(0), &a.nums[0], m, loc) ||
                !basisMatrix(s(1), &a.nums[17], m2, loc))
                break;
            if (n(16) < 1 || n(33) < 1) {
                error(loc, "Basis steps must be at least 1");
                break;
            }
            m_ustep = n(16);
            m_vstep = n(33);
            t.basis(loc, s(0), m, n(16), s(1), m2, n(33));
            break;
        }
        case Req::Declare: {
            ParamDecl decl;
            std::string unused;
            if (!parseParamDecl(s(1), false, decl, unused)) {
                error(loc, "Declare: bad declaration \"" + s(1) + "\" for \"" + s(0) +
                               "\"");
                break;
            }
            m_declared[s(0)] = decl;
            t.declare(loc, s(0), s(1));
            break;
        }

        // Transformations
        case Req::Identity:
            t.identity(loc);
            break;
        case Req::Transform:
        case Req::ConcatTransform:
            for (size_t i = 0; i < 16; ++i) m[i] = f(i);
            if (info.req == Req::Transform)
                t.transform(loc, m);
            else
                t.concatTransform(loc, m);
            break;
        case Req::Perspective:
            t.perspective(loc, f(0));
            break;
        case Req::Translate:
            t.translate(loc, f(0), f(1), f(2));
            break;
        case Req::Rotate:
            t.rotate(loc, f(0), f(1), f(2), f(3));
            break;
        case Req::Scale:
            t.scale(loc, f(0), f(1), f(2));
            break;
        case Req::Skew:
            t.skew(loc, f(0), f(1), f(2), f(3), f(4), f(5), f(6));
            break;
        case Req::CoordinateSystem:
            t.coordinateSystem(loc, s(0));
            break;
        case Req::ScopedCoordinateSystem:
            t.scopedCoordinateSystem(loc, s(0));
            break;
        case Req::CoordSysTransform:
            t.coordSysTransform(loc, s(0));
            break;

        // Texture making: strs and nums in signature order
        case Req::MakeTexture:
            t.makeTexture(loc, s(0), s(1), s(2), s(3), s(4), f(0), f(1), P);
            break;
        case Req::MakeBump:
            t.makeBump(loc, s(0), s(1), s(2), s(3), s(4), f(0), f(1), P);
            break;
        case Req::MakeLatLongEnvironment:
            t.makeLatLongEnvironment(loc, s(0), s(1), s(2), f(0), f(1), P);
            break;
        case Req::MakeCubeFaceEnvironment:
            t.makeCubeFaceEnvironment(loc, {s(0), s(1), s(2), s(3), s(4), s(5)}, s(6), f(0),
                                      s(7), f(1), f(2), P);
            break;
        case Req::MakeShadow:
            t.makeShadow(loc, s(0), s(1), P);
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
