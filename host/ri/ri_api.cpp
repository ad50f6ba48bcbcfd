// ri_api.cpp: the Ri calls of ri.h other than geometry (ri_geometry.cpp): the frame and
// world blocks, options, attributes, shaders and lights, transformations, solids, objects
// and motion blocks, textures, archives and errors. Each becomes its RIB request's values
// and goes through the context (ri_context.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "ri.h"
#include "ri_context.h"
#include "ri_params.h"
#include "scene/pixel_filter.h"

using namespace rd::ri;

namespace {

// The RIB name of a standard filter (RiPixelFilter, RiMake*); nullptr for another.
const char* filterName(RtFilterFunc f) {
    if (f == RiBoxFilter) return "box";
    if (f == RiTriangleFilter) return "triangle";
    if (f == RiCatmullRomFilter) return "catmull-rom";
    if (f == RiGaussianFilter) return "gaussian";
    if (f == RiSincFilter) return "sinc";
    if (f == RiSeparableCatmullRomFilter) return "separable-catmull-rom";
    if (f == RiMitchellFilter) return "mitchell";
    if (f == RiBlackmanHarrisFilter) return "blackman-harris";
    if (f == RiLanczosFilter) return "lanczos";
    if (f == RiDiskFilter) return "disk";
    if (f == RiBesselFilter) return "bessel";
    return nullptr;
}

// A filter argument; an error (and "box") for a function of the program's own.
rib::RequestValue filterValue(Context* c, const char* call, RtFilterFunc f) {
    if (const char* name = filterName(f)) return string(name);
    c->error(RIE_UNIMPLEMENT,
             std::string(call) +
                 ": only the standard filters (RiBoxFilter, "
                 "RiTriangleFilter, RiCatmullRomFilter, RiGaussianFilter, "
                 "RiSincFilter) and PRMan's (RiSeparableCatmullRomFilter, "
                 "RiMitchellFilter, RiBlackmanHarrisFilter, RiLanczosFilter, "
                 "RiDiskFilter, RiBesselFilter) are supported; box used");
    return string("box");
}

rib::RequestValue matrix(RtMatrix m) {
    return floats(&m[0][0], 16);
}

// A basis by its RIB name when it is a standard one, else its sixteen numbers.
rib::RequestValue basis(RtBasis b) {
    if (b == RiBezierBasis) return string("bezier");
    if (b == RiBSplineBasis) return string("b-spline");
    if (b == RiCatmullRomBasis) return string("catmull-rom");
    if (b == RiHermiteBasis) return string("hermite");
    if (b == RiPowerBasis) return string("power");
    return floats(&b[0][0], 16);
}

rib::RequestValue handle(RtPointer h) {
    return integer((long long)(uintptr_t)h);
}

}  // namespace

extern "C" {

RtToken RI_FRAMEBUFFER = "framebuffer", RI_FILE = "file", RI_RGB = "rgb",
        RI_RGBA = "rgba", RI_RGBZ = "rgbz", RI_RGBAZ = "rgbaz", RI_A = "a", RI_Z = "z",
        RI_AZ = "az", RI_PERSPECTIVE = "perspective", RI_ORTHOGRAPHIC = "orthographic",
        RI_HIDDEN = "hidden", RI_PAINT = "paint", RI_CONSTANT = "constant",
        RI_SMOOTH = "smooth", RI_FLATNESS = "flatness", RI_FOV = "fov",
        RI_AMBIENTLIGHT = "ambientlight", RI_POINTLIGHT = "pointlight",
        RI_DISTANTLIGHT = "distantlight", RI_SPOTLIGHT = "spotlight",
        RI_INTENSITY = "intensity", RI_LIGHTCOLOR = "lightcolor", RI_FROM = "from",
        RI_TO = "to", RI_CONEANGLE = "coneangle", RI_CONEDELTAANGLE = "conedeltaangle",
        RI_BEAMDISTRIBUTION = "beamdistribution", RI_MATTE = "matte", RI_METAL = "metal",
        RI_SHINYMETAL = "shinymetal", RI_PLASTIC = "plastic",
        RI_PAINTEDPLASTIC = "paintedplastic", RI_KA = "Ka", RI_KD = "Kd", RI_KS = "Ks",
        RI_ROUGHNESS = "roughness", RI_KR = "Kr", RI_TEXTURENAME = "texturename",
        RI_SPECULARCOLOR = "specularcolor", RI_DEPTHCUE = "depthcue", RI_FOG = "fog",
        RI_BUMPY = "bumpy", RI_MINDISTANCE = "mindistance",
        RI_MAXDISTANCE = "maxdistance", RI_BACKGROUND = "background",
        RI_DISTANCE = "distance", RI_AMPLITUDE = "amplitude", RI_RASTER = "raster",
        RI_SCREEN = "screen", RI_CAMERA = "camera", RI_WORLD = "world",
        RI_OBJECT = "object", RI_INSIDE = "inside", RI_OUTSIDE = "outside", RI_LH = "lh",
        RI_RH = "rh", RI_P = "P", RI_PZ = "Pz", RI_PW = "Pw", RI_N = "N", RI_NP = "Np",
        RI_CS = "Cs", RI_OS = "Os", RI_S = "s", RI_T = "t", RI_ST = "st",
        RI_BILINEAR = "bilinear", RI_BICUBIC = "bicubic", RI_LINEAR = "linear",
        RI_CUBIC = "cubic", RI_PRIMITIVE = "primitive", RI_INTERSECTION = "intersection",
        RI_UNION = "union", RI_DIFFERENCE = "difference", RI_PERIODIC = "periodic",
        RI_NONPERIODIC = "nonperiodic", RI_CLAMP = "clamp", RI_BLACK = "black",
        RI_IGNORE = "ignore", RI_PRINT = "print", RI_ABORT = "abort",
        RI_HANDLER = "handler", RI_WIDTH = "width", RI_CONSTANTWIDTH = "constantwidth",
        RI_COMMENT = "comment", RI_STRUCTURE = "structure", RI_VERBATIM = "verbatim";

RtBasis RiBezierBasis = {{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}};
RtBasis RiBSplineBasis = {{-1.0f / 6, 3.0f / 6, -3.0f / 6, 1.0f / 6},
                          {3.0f / 6, -6.0f / 6, 3.0f / 6, 0},
                          {-3.0f / 6, 0, 3.0f / 6, 0},
                          {1.0f / 6, 4.0f / 6, 1.0f / 6, 0}};
RtBasis RiCatmullRomBasis = {
    {-0.5f, 1.5f, -1.5f, 0.5f}, {1, -2.5f, 2, -0.5f}, {-0.5f, 0, 0.5f, 0}, {0, 1, 0, 0}};
RtBasis RiHermiteBasis = {{2, 1, -2, 1}, {-3, -2, 3, -1}, {0, 1, 0, 0}, {1, 0, 0, 0}};
RtBasis RiPowerBasis = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

// The filters' values are the RI 3.2 definitions; the renderer filters by name.
RtFloat RiBoxFilter(RtFloat, RtFloat, RtFloat, RtFloat) {
    return 1.0f;
}
RtFloat RiTriangleFilter(RtFloat x, RtFloat y, RtFloat xw, RtFloat yw) {
    const float fx = 1.0f - std::fabs(2 * x / xw), fy = 1.0f - std::fabs(2 * y / yw);
    return fx > 0 && fy > 0 ? fx * fy : 0.0f;
}
RtFloat RiCatmullRomFilter(RtFloat x, RtFloat y, RtFloat, RtFloat) {
    auto k = [](float t) {
        t = std::fabs(t);
        return t < 1   ? 1.5f * t * t * t - 2.5f * t * t + 1
               : t < 2 ? -0.5f * t * t * t + 2.5f * t * t - 4 * t + 2
                       : 0.0f;
    };
    return k(x) * k(y);
}
RtFloat RiGaussianFilter(RtFloat x, RtFloat y, RtFloat xw, RtFloat yw) {
    x *= 2 / xw, y *= 2 / yw;
    return std::exp(-2 * (x * x + y * y));
}
RtFloat RiSincFilter(RtFloat x, RtFloat y, RtFloat, RtFloat) {
    auto s = [](float t) {
        t *= 3.14159265f;
        return t == 0 ? 1.0f : std::sin(t) / t;
    };
    return s(x) * s(y);
}

// PRMan's further filters, as the renderer defines them (scene/pixel_filter.h).
#define RD_RI_FILTER(function, name)                                 \
    RtFloat function(RtFloat x, RtFloat y, RtFloat xw, RtFloat yw) { \
        return RtFloat(rd::pixelFilter2D(name, x, y, xw, yw));       \
    }
RD_RI_FILTER(RiSeparableCatmullRomFilter, "separable-catmull-rom")
RD_RI_FILTER(RiMitchellFilter, "mitchell")
RD_RI_FILTER(RiBlackmanHarrisFilter, "blackman-harris")
RD_RI_FILTER(RiLanczosFilter, "lanczos")
RD_RI_FILTER(RiDiskFilter, "disk")
RD_RI_FILTER(RiBesselFilter, "bessel")
#undef RD_RI_FILTER

RtVoid RiProcDelayedReadArchive(RtPointer, RtFloat) {}
RtVoid RiProcRunProgram(RtPointer, RtFloat) {}
RtVoid RiProcDynamicLoad(RtPointer, RtFloat) {}
RtVoid RiProcFree(RtPointer data) {
    std::free(data);
}

RtToken RiDeclare(RtString name, RtString declaration) {
    if (Context* c = Context::current("RiDeclare"))
        c->send("Declare", {string(name), string(declaration)});
    return name;
}

RtVoid RiBegin(RtToken name) {
    Context::begin(name);
}
RtVoid RiEnd(void) {
    Context::end();
}
RtContextHandle RiGetContext(void) {
    return Context::handle();
}
RtVoid RiContext(RtContextHandle handle) {
    Context::makeCurrent(handle);
}

#define RI_BARE(Fn, Req)                                                \
    RtVoid Ri##Fn(void) {                                               \
        if (Context* c = Context::current("Ri" #Fn)) c->send(#Req, {}); \
    }
RI_BARE(FrameEnd, FrameEnd)
RI_BARE(WorldBegin, WorldBegin)
RI_BARE(WorldEnd, WorldEnd)
RI_BARE(AttributeBegin, AttributeBegin)
RI_BARE(AttributeEnd, AttributeEnd)
RI_BARE(TransformBegin, TransformBegin)
RI_BARE(TransformEnd, TransformEnd)
RI_BARE(ReverseOrientation, ReverseOrientation)
RI_BARE(Identity, Identity)
RI_BARE(SolidEnd, SolidEnd)
RI_BARE(ObjectEnd, ObjectEnd)
RI_BARE(MotionEnd, MotionEnd)
RI_BARE(Else, Else)
RI_BARE(ResourceBegin, ResourceBegin)
RI_BARE(ResourceEnd, ResourceEnd)
RI_BARE(IfEnd, IfEnd)
#undef RI_BARE

// Requests of a name and a parameter list.
#define RI_NAMED(Fn)                                                                \
    RtVoid Ri##Fn##V(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]) { \
        if (Context* c = Context::current("Ri" #Fn))                                \
            c->send(#Fn, {string(name)}, {n, tokens, values});                      \
    }                                                                               \
    RtVoid Ri##Fn(RtToken name, ...) {                                              \
        RI_VARARGS(name, Ri##Fn##V(name, vp.n(), vp.t(), vp.v()));                  \
    }
RI_NAMED(Projection)
RI_NAMED(Camera)
RI_NAMED(Imager)
RI_NAMED(DisplayChannel)
RI_NAMED(Hider)
RI_NAMED(Option)
RI_NAMED(Surface)
RI_NAMED(Displacement)
RI_NAMED(Atmosphere)
RI_NAMED(Interior)
RI_NAMED(Exterior)
RI_NAMED(Attribute)
RI_NAMED(Deformation)
#undef RI_NAMED

// Requests of one string.
#define RI_STRING(Fn)                                                           \
    RtVoid Ri##Fn(RtToken s) {                                                  \
        if (Context* c = Context::current("Ri" #Fn)) c->send(#Fn, {string(s)}); \
    }
RI_STRING(ShadingInterpolation)
RI_STRING(GeometricRepresentation)
RI_STRING(Orientation)
RI_STRING(CoordinateSystem)
RI_STRING(ScopedCoordinateSystem)
RI_STRING(CoordSysTransform)
RI_STRING(SolidBegin)
RI_STRING(IfBegin)
RI_STRING(ElseIf)
#undef RI_STRING

// Points from one coordinate system to another in the current state (RI 3.2 section
// 4.3.4): the points themselves, moved, or RI_NULL when a space is unknown or the calls
// are written to a RIB file (which keeps no state).
RtPoint* RiTransformPoints(RtToken fromspace, RtToken tospace, RtInt npoints,
                           RtPoint* points) {
    Context* c = Context::current("RiTransformPoints");
    if (!c || !fromspace || !tospace || npoints < 0 || (npoints > 0 && !points))
        return nullptr;
    if (!c->transformPoints(fromspace, tospace, &points[0][0], npoints)) return nullptr;
    return points;
}

// Requests of n numbers.
#define RI_NUMBERS(Fn, ...) \
    if (Context* c = Context::current("Ri" #Fn)) c->send(#Fn, {__VA_ARGS__})
RtVoid RiFrameBegin(RtInt frame) {
    RI_NUMBERS(FrameBegin, integer(frame));
}
RtVoid RiFormat(RtInt x, RtInt y, RtFloat aspect) {
    RI_NUMBERS(Format, integer(x), integer(y), number(aspect));
}
RtVoid RiFrameAspectRatio(RtFloat r) {
    RI_NUMBERS(FrameAspectRatio, number(r));
}
RtVoid RiScreenWindow(RtFloat l, RtFloat r, RtFloat b, RtFloat t) {
    RI_NUMBERS(ScreenWindow, number(l), number(r), number(b), number(t));
}
RtVoid RiCropWindow(RtFloat x0, RtFloat x1, RtFloat y0, RtFloat y1) {
    RI_NUMBERS(CropWindow, number(x0), number(x1), number(y0), number(y1));
}
RtVoid RiClipping(RtFloat hither, RtFloat yon) {
    RI_NUMBERS(Clipping, number(hither), number(yon));
}
RtVoid RiClippingPlane(RtFloat x, RtFloat y, RtFloat z, RtFloat nx, RtFloat ny,
                       RtFloat nz) {
    RI_NUMBERS(ClippingPlane, number(x), number(y), number(z), number(nx), number(ny),
               number(nz));
}
RtVoid RiDepthOfField(RtFloat fstop, RtFloat focallength, RtFloat focaldistance) {
    if (Context* c = Context::current("RiDepthOfField")) {
        if (fstop >= RI_INFINITY)  // (a pinhole: the bare request)
            c->send("DepthOfField", {});
        else
            c->send("DepthOfField",
                    {number(fstop), number(focallength), number(focaldistance)});
    }
}
RtVoid RiShutter(RtFloat open, RtFloat close) {
    RI_NUMBERS(Shutter, number(open), number(close));
}
RtVoid RiPixelVariance(RtFloat v) {
    RI_NUMBERS(PixelVariance, number(v));
}
RtVoid RiPixelSamples(RtFloat x, RtFloat y) {
    RI_NUMBERS(PixelSamples, number(x), number(y));
}
RtVoid RiExposure(RtFloat gain, RtFloat gamma) {
    RI_NUMBERS(Exposure, number(gain), number(gamma));
}
RtVoid RiRelativeDetail(RtFloat d) {
    RI_NUMBERS(RelativeDetail, number(d));
}
RtVoid RiTextureCoordinates(RtFloat s1, RtFloat t1, RtFloat s2, RtFloat t2, RtFloat s3,
                            RtFloat t3, RtFloat s4, RtFloat t4) {
    RI_NUMBERS(TextureCoordinates, number(s1), number(t1), number(s2), number(t2),
               number(s3), number(t3), number(s4), number(t4));
}
RtVoid RiShadingRate(RtFloat size) {
    RI_NUMBERS(ShadingRate, number(size));
}
RtVoid RiMatte(RtBoolean onoff) {
    RI_NUMBERS(Matte, integer(onoff ? 1 : 0));
}
RtVoid RiBound(RtBound b) {
    RI_NUMBERS(Bound, number(b[0]), number(b[1]), number(b[2]), number(b[3]),
               number(b[4]), number(b[5]));
}
RtVoid RiDetail(RtBound b) {
    RI_NUMBERS(Detail, number(b[0]), number(b[1]), number(b[2]), number(b[3]),
               number(b[4]), number(b[5]));
}
RtVoid RiDetailRange(RtFloat a, RtFloat b, RtFloat c2, RtFloat d) {
    RI_NUMBERS(DetailRange, number(a), number(b), number(c2), number(d));
}
RtVoid RiSides(RtInt sides) {
    RI_NUMBERS(Sides, integer(sides));
}
RtVoid RiPerspective(RtFloat fov) {
    RI_NUMBERS(Perspective, number(fov));
}
RtVoid RiTranslate(RtFloat dx, RtFloat dy, RtFloat dz) {
    RI_NUMBERS(Translate, number(dx), number(dy), number(dz));
}
RtVoid RiRotate(RtFloat angle, RtFloat dx, RtFloat dy, RtFloat dz) {
    RI_NUMBERS(Rotate, number(angle), number(dx), number(dy), number(dz));
}
RtVoid RiScale(RtFloat sx, RtFloat sy, RtFloat sz) {
    RI_NUMBERS(Scale, number(sx), number(sy), number(sz));
}
RtVoid RiSkew(RtFloat angle, RtFloat dx1, RtFloat dy1, RtFloat dz1, RtFloat dx2,
              RtFloat dy2, RtFloat dz2) {
    RI_NUMBERS(Skew, number(angle), number(dx1), number(dy1), number(dz1), number(dx2),
               number(dy2), number(dz2));
}
RtVoid RiTransform(RtMatrix m) {
    RI_NUMBERS(Transform, matrix(m));
}
RtVoid RiConcatTransform(RtMatrix m) {
    RI_NUMBERS(ConcatTransform, matrix(m));
}
RtVoid RiGeometricApproximation(RtToken type, RtFloat value) {
    RI_NUMBERS(GeometricApproximation, string(type), number(value));
}
RtVoid RiQuantize(RtToken type, RtInt one, RtInt min, RtInt max, RtFloat ampl) {
    RI_NUMBERS(Quantize, string(type), integer(one), integer(min), integer(max),
               number(ampl));
}
#undef RI_NUMBERS

RtVoid RiPixelFilter(RtFilterFunc f, RtFloat xwidth, RtFloat ywidth) {
    if (Context* c = Context::current("RiPixelFilter"))
        c->send("PixelFilter",
                {filterValue(c, "RiPixelFilter", f), number(xwidth), number(ywidth)});
}

RtVoid RiDisplayV(RtToken name, RtToken type, RtToken mode, RtInt n, RtToken tokens[],
                  RtPointer values[]) {
    if (Context* c = Context::current("RiDisplay"))
        c->send("Display", {string(name), string(type), string(mode)},
                {n, tokens, values});
}
RtVoid RiDisplay(RtToken name, RtToken type, RtToken mode, ...) {
    RI_VARARGS(mode, RiDisplayV(name, type, mode, vp.n(), vp.t(), vp.v()));
}

RtVoid RiColorSamples(RtInt n, RtFloat nRGB[], RtFloat RGBn[]) {
    if (Context* c = Context::current("RiColorSamples"))
        c->send("ColorSamples", {floats(nRGB, 3LL * n), floats(RGBn, 3LL * n)});
}

RtVoid RiColor(RtColor color) {
    if (Context* c = Context::current("RiColor"))
        c->send("Color", {floats(color, c->feed().colorSamples())});
}
RtVoid RiOpacity(RtColor color) {
    if (Context* c = Context::current("RiOpacity"))
        c->send("Opacity", {floats(color, c->feed().colorSamples())});
}

RtLightHandle RiLightSourceV(RtToken name, RtInt n, RtToken tokens[],
                             RtPointer values[]) {
    Context* c = Context::current("RiLightSource");
    if (!c) return nullptr;
    const uintptr_t h = c->nextLight();
    c->send("LightSource", {string(name), integer((long long)h)}, {n, tokens, values});
    return reinterpret_cast<RtLightHandle>(h);
}
RtLightHandle RiLightSource(RtToken name, ...) {
    RI_VARARGS(name, RiLightSourceV(name, vp.n(), vp.t(), vp.v()));
}
RtLightHandle RiAreaLightSourceV(RtToken name, RtInt n, RtToken tokens[],
                                 RtPointer values[]) {
    Context* c = Context::current("RiAreaLightSource");
    if (!c) return nullptr;
    const uintptr_t h = c->nextLight();
    c->send("AreaLightSource", {string(name), integer((long long)h)},
            {n, tokens, values});
    return reinterpret_cast<RtLightHandle>(h);
}
RtLightHandle RiAreaLightSource(RtToken name, ...) {
    RI_VARARGS(name, RiAreaLightSourceV(name, vp.n(), vp.t(), vp.v()));
}
RtVoid RiIlluminate(RtLightHandle light, RtBoolean onoff) {
    if (Context* c = Context::current("RiIlluminate"))
        c->send("Illuminate", {handle(light), integer(onoff ? 1 : 0)});
}

RtVoid RiBasis(RtBasis ubasis, RtInt ustep, RtBasis vbasis, RtInt vstep) {
    if (Context* c = Context::current("RiBasis"))
        c->send("Basis", {basis(ubasis), integer(ustep), basis(vbasis), integer(vstep)});
}

RtObjectHandle RiObjectBegin(void) {
    Context* c = Context::current("RiObjectBegin");
    if (!c) return nullptr;
    const uintptr_t h = c->nextObject();
    c->send("ObjectBegin", {integer((long long)h)});
    return reinterpret_cast<RtObjectHandle>(h);
}
RtVoid RiObjectInstance(RtObjectHandle h) {
    if (Context* c = Context::current("RiObjectInstance"))
        c->send("ObjectInstance", {handle(h)});
}

RtVoid RiMotionBeginV(RtInt n, RtFloat times[]) {
    if (Context* c = Context::current("RiMotionBegin"))
        c->send("MotionBegin", {floats(times, n)});
}
RtVoid RiMotionBegin(RtInt n, ...) {
    std::vector<RtFloat> times;
    va_list ap;
    va_start(ap, n);
    for (RtInt i = 0; i < n && i < 4096; ++i)
        times.push_back(RtFloat(va_arg(ap, double)));
    va_end(ap);
    RiMotionBeginV(RtInt(times.size()), times.data());
}

RtVoid RiMakeTextureV(RtString pic, RtString tex, RtToken swrap, RtToken twrap,
                      RtFilterFunc f, RtFloat sw, RtFloat tw, RtInt n, RtToken tokens[],
                      RtPointer values[]) {
    if (Context* c = Context::current("RiMakeTexture"))
        c->send("MakeTexture",
                {string(pic), string(tex), string(swrap), string(twrap),
                 filterValue(c, "RiMakeTexture", f), number(sw), number(tw)},
                {n, tokens, values});
}
RtVoid RiMakeTexture(RtString pic, RtString tex, RtToken swrap, RtToken twrap,
                     RtFilterFunc f, RtFloat sw, RtFloat tw, ...) {
    RI_VARARGS(tw,
               RiMakeTextureV(pic, tex, swrap, twrap, f, sw, tw, vp.n(), vp.t(), vp.v()));
}
RtVoid RiMakeLatLongEnvironmentV(RtString pic, RtString tex, RtFilterFunc f, RtFloat sw,
                                 RtFloat tw, RtInt n, RtToken tokens[],
                                 RtPointer values[]) {
    if (Context* c = Context::current("RiMakeLatLongEnvironment"))
        c->send("MakeLatLongEnvironment",
                {string(pic), string(tex), filterValue(c, "RiMakeLatLongEnvironment", f),
                 number(sw), number(tw)},
                {n, tokens, values});
}
RtVoid RiMakeLatLongEnvironment(RtString pic, RtString tex, RtFilterFunc f, RtFloat sw,
                                RtFloat tw, ...) {
    RI_VARARGS(tw,
               RiMakeLatLongEnvironmentV(pic, tex, f, sw, tw, vp.n(), vp.t(), vp.v()));
}
RtVoid RiMakeCubeFaceEnvironmentV(RtString px, RtString nx, RtString py, RtString ny,
                                  RtString pz, RtString nz, RtString tex, RtFloat fov,
                                  RtFilterFunc f, RtFloat sw, RtFloat tw, RtInt n,
                                  RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiMakeCubeFaceEnvironment"))
        c->send("MakeCubeFaceEnvironment",
                {string(px), string(nx), string(py), string(ny), string(pz), string(nz),
                 string(tex), number(fov), filterValue(c, "RiMakeCubeFaceEnvironment", f),
                 number(sw), number(tw)},
                {n, tokens, values});
}
RtVoid RiMakeCubeFaceEnvironment(RtString px, RtString nx, RtString py, RtString ny,
                                 RtString pz, RtString nz, RtString tex, RtFloat fov,
                                 RtFilterFunc f, RtFloat sw, RtFloat tw, ...) {
    RI_VARARGS(tw, RiMakeCubeFaceEnvironmentV(px, nx, py, ny, pz, nz, tex, fov, f, sw, tw,
                                              vp.n(), vp.t(), vp.v()));
}
RtVoid RiMakeShadowV(RtString pic, RtString tex, RtInt n, RtToken tokens[],
                     RtPointer values[]) {
    if (Context* c = Context::current("RiMakeShadow"))
        c->send("MakeShadow", {string(pic), string(tex)}, {n, tokens, values});
}
RtVoid RiMakeShadow(RtString pic, RtString tex, ...) {
    RI_VARARGS(tex, RiMakeShadowV(pic, tex, vp.n(), vp.t(), vp.v()));
}

// (the callback sees RIB comments and structure lines, which the reader skips)
RtVoid RiReadArchiveV(RtToken name, RtArchiveCallback, RtInt n, RtToken tokens[],
                      RtPointer values[]) {
    if (Context* c = Context::current("RiReadArchive"))
        c->send("ReadArchive", {string(name)}, {n, tokens, values});
}
RtVoid RiReadArchive(RtToken name, RtArchiveCallback callback, ...) {
    RI_VARARGS(callback, RiReadArchiveV(name, callback, vp.n(), vp.t(), vp.v()));
}

RtVoid RiResourceV(RtToken handle, RtToken type, RtInt n, RtToken tokens[],
                   RtPointer values[]) {
    if (Context* c = Context::current("RiResource"))
        c->send("Resource", {string(handle), string(type)}, {n, tokens, values});
}
RtVoid RiResource(RtToken handle, RtToken type, ...) {
    RI_VARARGS(type, RiResourceV(handle, type, vp.n(), vp.t(), vp.v()));
}

RtVoid RiArchiveRecord(RtToken type, const char* format, ...) {
    Context* c = Context::current("RiArchiveRecord");
    if (!c) return;
    char text[65536];  // (a longer record is cut there)
    va_list ap;
    va_start(ap, format);
    std::vsnprintf(text, sizeof text, format ? format : "", ap);
    va_end(ap);
    c->record(type ? type : "", text);
}

RtVoid RiErrorHandler(RtErrorHandler handler) {
    Context::setHandler(handler);
    // The standard ones are also RIB's ErrorHandler (a RIB file written says so; "abort"
    // also stops the reading of archives at their first error).
    const char* name = handler == RiErrorIgnore  ? "ignore"
                       : handler == RiErrorAbort ? "abort"
                                                 : "print";
    if (Context::active())
        Context::current("RiErrorHandler")->send("ErrorHandler", {string(name)});
}

}  // extern "C"
