// ri_api_test.cpp: the Ri C API (host/ri/ri.h). Calls written to a RIB file must be the
// RIB a reader writes back for the same scene (positional arguments, every parameter's
// values counted from its class and type); a render through RiBegin(RI_NULL) must be the
// image the same RIB renders; bad calls reach the error handler with their call number
// and are skipped.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../scratch_folder.h"
#include "film/exr_output.h"
#include "ri.h"
#include "rib/reader.h"
#include "rib/writer.h"

namespace {

std::string scratch(const std::string& name) {
    return (std::filesystem::path(rd::test::scratchFolder("ri_api")) / name).string();
}

std::string slurp(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// What RibWriter writes for `rib` read by the reader: the form the API's file must have.
std::string rewritten(const std::string& rib) {
    std::ostringstream out;
    rib::Diagnostics diag(&std::cerr);
    {
        rib::RibWriter writer(out);
        EXPECT_TRUE(rib::readString(rib, "expected.rib", writer, diag));
    }
    return out.str();
}

std::vector<std::string> g_messages;
std::vector<RtInt> g_codes;
RtVoid collect(RtInt code, RtInt, RtString message) {
    g_codes.push_back(code);
    g_messages.push_back(message);
}

// A scene of most kinds of calls, through the API.
void sceneCalls() {
    RiFormat(64, 48, 1);
    RiPixelSamples(2, 2);
    RiPixelFilter(RiGaussianFilter, 2, 2);
    RtFloat fov = 40;
    RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
    RiDeclare("bias", "uniform float");
    RiWorldBegin();
    RtPoint from = {1, 2, 3};
    RtFloat intensity = 5;
    RiLightSource(RI_POINTLIGHT, RI_FROM, from, RI_INTENSITY, &intensity, RI_NULL);
    RiAttributeBegin();
    RtColor red = {1, 0, 0};
    RiColor(red);
    RtFloat kd = 0.7f, bias = 0.25f;
    RtString texname = "grid.tx";
    RiSurface(RI_PLASTIC, RI_KD, &kd, "bias", &bias, "uniform string texname", &texname,
              RI_NULL);
    RiTranslate(0, 0, 5);
    RiRotate(30, 0, 1, 0);
    RiSphere(1, -1, 1, 360, RI_NULL);
    RiAttributeEnd();
    RtInt nverts[] = {4, 3};
    RtInt verts[] = {0, 1, 2, 3, 1, 4, 2};
    RtFloat P[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0};
    RtFloat Cs[] = {1, 0, 0, 0, 1, 0};                          // uniform: one per face
    RtFloat st[] = {0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 1, 0, 1, 1};  // facevarying: 7 corners
    RiPointsPolygons(2, nverts, verts, RI_P, (RtPointer)P, "uniform color Cs",
                     (RtPointer)Cs, "facevarying float[2] st", (RtPointer)st, RI_NULL);
    RtFloat patch[16 * 3];
    for (int i = 0; i < 16; ++i)
        patch[3 * i] = float(i % 4), patch[3 * i + 1] = float(i / 4),
                  patch[3 * i + 2] = 0;
    RiBasis(RiBSplineBasis, RI_BSPLINESTEP, RiBSplineBasis, RI_BSPLINESTEP);
    RtFloat corner[4] = {0.1f, 0.2f, 0.3f, 0.4f};  // varying: (4-3+1)+1 = 2 a direction
    RiPatchMesh(RI_BICUBIC, 4, RI_NONPERIODIC, 4, RI_NONPERIODIC, RI_P, (RtPointer)patch,
                "varying float w", (RtPointer)corner, RI_NULL);
    RtInt ncurve[] = {4};
    RtFloat widths[] = {0.1f, 0.2f};  // varying: b-spline step 1, 4 vertices: 2 values
    RiCurves(RI_CUBIC, 1, ncurve, RI_NONPERIODIC, RI_P, (RtPointer)patch, RI_WIDTH,
             (RtPointer)widths, RI_NULL);
    RtObjectHandle obj = RiObjectBegin();
    RiDisk(0, 1, 360, RI_NULL);
    RiObjectEnd();
    RiMotionBegin(2, 0.0, 1.0);
    RiTranslate(0, 0, 0);
    RiTranslate(1, 0, 0);
    RiMotionEnd();
    RiObjectInstance(obj);
    RiWorldEnd();
}

const char* kSceneRib = R"(Format 64 48 1
PixelSamples 2 2
PixelFilter "gaussian" 2 2
Projection "perspective" "fov" [40]
Declare "bias" "uniform float"
WorldBegin
LightSource "pointlight" 1 "from" [1 2 3] "intensity" [5]
AttributeBegin
Color [1 0 0]
Surface "plastic" "Kd" [0.7] "bias" [0.25] "uniform string texname" ["grid.tx"]
Translate 0 0 5
Rotate 30 0 1 0
Sphere 1 -1 1 360
AttributeEnd
PointsPolygons [4 3] [0 1 2 3 1 4 2] "P" [0 0 0 1 0 0 1 1 0 0 1 0 2 0 0]
  "uniform color Cs" [1 0 0 0 1 0] "facevarying float[2] st" [0 0 1 0 1 1 0 1 0 0 1 0 1 1]
Basis "b-spline" 1 "b-spline" 1
PatchMesh "bicubic" 4 "nonperiodic" 4 "nonperiodic"
  "P" [0 0 0 1 0 0 2 0 0 3 0 0 0 1 0 1 1 0 2 1 0 3 1 0 0 2 0 1 2 0 2 2 0 3 2 0 0 3 0 1 3 0 2 3 0 3 3 0]
  "varying float w" [0.1 0.2 0.3 0.4]
Curves "cubic" [4] "nonperiodic" "P" [0 0 0 1 0 0 2 0 0 3 0 0] "varying float width" [0.1 0.2]
ObjectBegin 1
Disk 0 1 360
ObjectEnd
MotionBegin [0 1]
Translate 0 0 0
Translate 1 0 0
MotionEnd
ObjectInstance 1
WorldEnd
)";

}  // namespace

TEST(RiApi, CallsWrittenAsRibAreTheReadersRib) {
    const std::string path = scratch("scene.rib");
    RiErrorHandler(collect);
    g_messages.clear();
    RiBegin(path.c_str());
    sceneCalls();
    RiEnd();
    RiErrorHandler(RiErrorPrint);
    EXPECT_TRUE(g_messages.empty()) << g_messages.front();
    EXPECT_EQ(RiLastError, RIE_NOERROR);
    EXPECT_EQ(slurp(path), rewritten(kSceneRib));
}

TEST(RiApi, ColorSamplesSetHowManyFloatsAColourTakes) {
    const std::string path = scratch("colors.rib");
    RiBegin(path.c_str());
    RtFloat nRGB[] = {1, 0, 0, 0, 1, 0}, RGBn[] = {1, 0, 0, 1, 0, 0};
    RiColorSamples(2, nRGB, RGBn);
    RiWorldBegin();
    RtFloat two[] = {0.5f, 0.25f};
    RiColor(two);
    RtFloat cs[] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f};  // varying: 4 x 2
    RiSphere(1, -1, 1, 360, "varying color Cs", (RtPointer)cs, RI_NULL);
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(slurp(path), rewritten(R"(ColorSamples [1 0 0 0 1 0] [1 0 0 1 0 0]
WorldBegin
Color [0.5 0.25]
Sphere 1 -1 1 360 "varying color Cs" [0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8]
WorldEnd
)"));
}

// Several contexts (RiContext, RiGetContext): two RIB files written by turns, each
// getting only its own calls; RiEnd ends the current one and leaves none current; a
// handle that is not a live context is RIE_BADHANDLE. Before, a second RiBegin was
// refused (one context at a time) and RiContext did not exist.
TEST(RiApi, ContextsTakeTheirOwnCallsByTurns) {
    const std::string a = scratch("first.rib"), b = scratch("second.rib");
    g_messages.clear();
    g_codes.clear();
    RiErrorHandler(collect);
    RiBegin(a.c_str());
    RtContextHandle first = RiGetContext();
    RiBegin(b.c_str());
    RtContextHandle second = RiGetContext();
    ASSERT_NE(first, nullptr);
    ASSERT_NE(second, nullptr);
    EXPECT_NE(first, second);
    RiWorldBegin();  // the second's
    RiContext(first);
    EXPECT_EQ(RiGetContext(), first);
    RiWorldBegin();
    RiSphere(1, -1, 1, 360, RI_NULL);
    RiContext(second);
    RiCylinder(1, -1, 1, 360, RI_NULL);
    RiWorldEnd();
    RiEnd();  // the second ends; none is current
    EXPECT_EQ(RiGetContext(), nullptr);
    RiContext(second);
    ASSERT_EQ(g_codes.size(), 1u);
    EXPECT_EQ(g_codes[0], RIE_BADHANDLE);
    RiContext(first);
    RiWorldEnd();
    RiEnd();
    RiErrorHandler(RiErrorPrint);
    EXPECT_EQ(g_messages.size(), 1u);
    const std::string one = slurp(a), two = slurp(b);
    EXPECT_NE(one.find("Sphere 1 -1 1 360"), std::string::npos) << one;
    EXPECT_EQ(one.find("Cylinder"), std::string::npos) << one;
    EXPECT_NE(two.find("Cylinder 1 -1 1 360"), std::string::npos) << two;
    EXPECT_EQ(two.find("Sphere"), std::string::npos) << two;
    EXPECT_NE(one.find("WorldEnd"), std::string::npos);
    EXPECT_NE(two.find("WorldEnd"), std::string::npos);
}

TEST(RiApi, BadCallsReachTheHandlerWithTheirCallNumberAndAreSkipped) {
    g_messages.clear();
    g_codes.clear();
    RiErrorHandler(collect);
    RiSphere(1, -1, 1, 360, RI_NULL);  // before RiBegin
    ASSERT_EQ(g_messages.size(), 1u);
    EXPECT_EQ(g_codes[0], RIE_NOTSTARTED);
    EXPECT_EQ(RiLastError, RIE_NOTSTARTED);
    const std::string path = scratch("bad.rib");
    RiBegin(path.c_str());
    EXPECT_EQ(RiLastError, RIE_NOERROR);
    RiPixelFilter([](RtFloat, RtFloat, RtFloat, RtFloat) -> RtFloat { return 1; }, 1, 1);
    RiWorldBegin();  // call 2
    RtFloat one = 1;
    RiSphere(1, -1, 1, 360, "Kq", &one, RI_NULL);  // 3: undeclared
    RiFormat(64, 64, 1);                           // 4: inside World
    RiAttributeEnd();                              // 5: no Begin
    RiEnd();                                       // 6: World open
    RiErrorHandler(RiErrorPrint);
    ASSERT_EQ(g_messages.size(), 6u);
    EXPECT_EQ(
        g_messages[1].rfind("Ri:1: error: RiPixelFilter: only the standard filters", 0),
        0u)
        << g_messages[1];
    EXPECT_EQ(g_codes[1], RIE_UNIMPLEMENT);
    EXPECT_EQ(
        g_messages[2].rfind("Ri:3: error: Sphere: parameter \"Kq\" is not declared", 0),
        0u)
        << g_messages[2];
    EXPECT_EQ(g_codes[2], RIE_BADTOKEN);
    EXPECT_EQ(g_messages[3].rfind("Ri:4: error: Format is an option", 0), 0u)
        << g_messages[3];
    EXPECT_EQ(g_messages[4].rfind("Ri:5: error: AttributeEnd without AttributeBegin", 0),
              0u)
        << g_messages[4];
    EXPECT_EQ(g_messages[5].rfind("Ri:6: error: WorldBegin at Ri:2 never closed", 0), 0u)
        << g_messages[5];
    EXPECT_NE(RiLastError, RIE_NOERROR);
    // The sphere is kept without its bad parameter; the Format is not written.
    const std::string written = slurp(path);
    EXPECT_NE(written.find("Sphere 1 -1 1 360"), std::string::npos) << written;
    EXPECT_EQ(written.find("Kq"), std::string::npos) << written;
    EXPECT_EQ(written.find("Format"), std::string::npos) << written;
}

TEST(RiApi, ACustomHandlerGetsWarningsAndIgnoreSilencesErrors) {
    g_messages.clear();
    g_codes.clear();
    RiErrorHandler(collect);
    RiBegin(RI_NULL);
    RiDisplay(scratch("never.exr").c_str(), RI_FRAMEBUFFER, RI_RGBA, RI_NULL);
    RiEnd();
    ASSERT_EQ(g_messages.size(), 1u);
    EXPECT_EQ(g_messages[0].rfind("Ri:1: warning: display type \"framebuffer\"", 0), 0u)
        << g_messages[0];
    EXPECT_EQ(RiLastError, RIE_NOERROR);  // (a warning is not an error)
    g_messages.clear();
    RiErrorHandler(RiErrorIgnore);
    RiBegin(scratch("ignored.rib").c_str());
    RiAttributeEnd();
    RiEnd();
    RiErrorHandler(collect);
    EXPECT_TRUE(g_messages.empty());
    RiErrorHandler(RiErrorPrint);
}

// The calls the scene above leaves out, each once: their RIB as the reader writes it
// back.
TEST(RiApi, EveryOtherCallWrittenAsRib) {
    const std::string path = scratch("rest.rib");
    RiErrorHandler(collect);
    g_messages.clear();
    RiBegin(path.c_str());
    RiMakeTexture("in.tif", "out.tx", RI_PERIODIC, RI_CLAMP, RiBoxFilter, 1, 1, RI_NULL);
    RiMakeLatLongEnvironment("env.tif", "env.tx", RiCatmullRomFilter, 2, 2, RI_NULL);
    RiMakeCubeFaceEnvironment("px", "nx", "py", "ny", "pz", "nz", "cube.tx", 95,
                              RiTriangleFilter, 2, 2, RI_NULL);
    RiMakeShadow("depth.z", "shadow.tx", RI_NULL);
    RiFrameBegin(3);
    RiFrameAspectRatio(1.5f);
    RiScreenWindow(-1, 1, -0.5f, 0.5f);
    RiCropWindow(0, 0.5f, 0.25f, 1);
    RiClipping(0.1f, 100);
    RiDepthOfField(8, 0.05f, 4);
    RiShutter(0, 0.5f);
    RiPixelVariance(0.02f);
    RiExposure(1.5f, 2.2f);
    RiImager("background", RI_NULL);
    RiQuantize(RI_RGBA, 255, 0, 255, 0.5f);
    RiDisplayChannel("color Ci", RI_NULL);
    RtInt one = 1;
    RiHider(RI_HIDDEN, "int jitter", &one, RI_NULL);
    RiRelativeDetail(0.5f);
    RtInt depth = 4;
    RiOption("trace", "int maxdepth", &depth, RI_NULL);
    RiErrorHandler(RiErrorIgnore);
    RiErrorHandler(collect);
    RiWorldBegin();
    RiTransformBegin();
    RiIdentity();
    RtMatrix m = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {1, 2, 3, 1}};
    RiTransform(m);
    RiConcatTransform(m);
    RiPerspective(30);
    RiScale(1, 2, 3);
    RiSkew(45, 0, 1, 0, 1, 0, 0);
    RiCoordinateSystem("mine");
    RiCoordSysTransform("mine");
    RiTransformEnd();
    RiAttributeBegin();
    RiScopedCoordinateSystem("scoped");
    RtColor half = {0.5f, 0.5f, 0.5f};
    RiOpacity(half);
    RiTextureCoordinates(0, 0, 1, 0, 0, 1, 1, 1);
    RtLightHandle area = RiAreaLightSource("arealight", RI_INTENSITY, &half[0], RI_NULL);
    RiIlluminate(area, RI_FALSE);
    RiDisplacement("bumpy", RI_AMPLITUDE, &half[0], RI_NULL);
    RiAtmosphere("fog", RI_NULL);
    RiInterior("water", RI_NULL);
    RiExterior("air", RI_NULL);
    RiShadingRate(0.5f);
    RiShadingInterpolation(RI_SMOOTH);
    RiMatte(RI_TRUE);
    RtBound b = {-1, 1, -1, 1, -1, 1};
    RiBound(b);
    RiDetail(b);
    RiDetailRange(0, 0, 10, 20);
    RiGeometricApproximation("flatness", 0.5f);
    RiOrientation(RI_RH);
    RiReverseOrientation();
    RiSides(1);
    RtString grouping = "lights";
    RiAttribute("identifier", "string name", &grouping, RI_NULL);
    RiDeformation("twist", RI_NULL);
    RtBasis mine = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 2}};
    RiBasis(mine, 4, RiCatmullRomBasis, RI_CATMULLROMSTEP);
    RiAttributeEnd();
    RtFloat sq[] = {0, 0,    0,    1, 0,    0,    1, 1,    0,    0, 1,
                    0, 0.2f, 0.2f, 0, 0.8f, 0.2f, 0, 0.5f, 0.8f, 0};
    RiPolygon(4, RI_P, sq, RI_NULL);
    RtInt loops[] = {4, 3};
    RiGeneralPolygon(2, loops, RI_P, sq, RI_NULL);
    RtInt pgLoops[] = {2}, pgVerts[] = {4, 3}, pgIdx[] = {0, 1, 2, 3, 4, 5, 6};
    RiPointsGeneralPolygons(1, pgLoops, pgVerts, pgIdx, RI_P, sq, RI_NULL);
    RtFloat bilinear[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    RtFloat cornerS[] = {0, 1, 0, 1};
    RiPatch(RI_BILINEAR, RI_P, bilinear, RI_S, cornerS, RI_NULL);
    RtFloat knots[] = {0, 0, 1, 1};
    RtFloat pw[] = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1, 1, 1, 0, 1};
    RiNuPatch(2, 2, knots, 0, 1, 2, 2, knots, 0, 1, RI_PW, pw, RI_NULL);
    RtInt ncurves[] = {1}, order[] = {2}, nn[] = {2};
    RtFloat tk[] = {0, 0, 1, 1}, tmin[] = {0}, tmax[] = {1}, tu[] = {0, 1}, tv[] = {0, 1},
            tw[] = {1, 1};
    RiTrimCurve(1, ncurves, order, tk, tmin, tmax, nn, tu, tv, tw);
    RiCylinder(1, 0, 1, 180, RI_NULL);
    RiCone(2, 1, 360, RI_NULL);
    RiParaboloid(1, 0, 2, 270, RI_NULL);
    RtPoint p1 = {1, 0, 0}, p2 = {0, 1, 1};
    RiHyperboloid(p1, p2, 360, RI_NULL);
    RiTorus(1, 0.25f, 0, 360, 360, RI_NULL);
    RtFloat widths[] = {0.1f, 0.2f, 0.3f};
    RiPoints(3, RI_P, sq, RI_WIDTH, widths, RI_NULL);
    RtInt faces[] = {4}, fv[] = {0, 1, 2, 3}, nargs[] = {0, 1};
    RtString tags[] = {"interpolateboundary"};
    RtFloat sharp[] = {2};
    RiSubdivisionMesh("catmull-clark", 1, faces, fv, 1, tags, nargs, nullptr, sharp, RI_P,
                      sq, RI_NULL);
    RtInt code[] = {1001, 0};
    RtFloat ellipsoid[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    RiBlobby(1, 2, code, 16, ellipsoid, 0, nullptr, RI_NULL);
    RiGeometry("teapot", RI_NULL);
    RtString archive[] = {"far.so", "params"};
    RtBound far = {-1, 1, -1, 1, -1, 1};
    RiProcedural(archive, far, RiProcDynamicLoad, nullptr);
    RiSolidBegin(RI_DIFFERENCE);
    RiSolidBegin(RI_PRIMITIVE);
    RiSphere(1, -1, 1, 360, RI_NULL);
    RiSolidEnd();
    RiSolidEnd();
    RtFloat times[] = {0, 0.5f, 1};
    RiMotionBeginV(3, times);
    RiRotate(0, 0, 0, 1);
    RiRotate(10, 0, 0, 1);
    RiRotate(0, 0, 0, 1);
    RiMotionEnd();
    RiWorldEnd();
    RiFrameEnd();
    RiEnd();
    RiErrorHandler(RiErrorPrint);
    for (const std::string& m : g_messages) ADD_FAILURE() << m;
    EXPECT_EQ(slurp(path),
              rewritten(R"(MakeTexture "in.tif" "out.tx" "periodic" "clamp" "box" 1 1
MakeLatLongEnvironment "env.tif" "env.tx" "catmull-rom" 2 2
MakeCubeFaceEnvironment "px" "nx" "py" "ny" "pz" "nz" "cube.tx" 95 "triangle" 2 2
MakeShadow "depth.z" "shadow.tx"
FrameBegin 3
FrameAspectRatio 1.5
ScreenWindow -1 1 -0.5 0.5
CropWindow 0 0.5 0.25 1
Clipping 0.1 100
DepthOfField 8 0.05 4
Shutter 0 0.5
PixelVariance 0.02
Exposure 1.5 2.2
Imager "background"
Quantize "rgba" 255 0 255 0.5
DisplayChannel "color Ci"
Hider "hidden" "int jitter" [1]
RelativeDetail 0.5
Option "trace" "int maxdepth" [4]
ErrorHandler "ignore"
ErrorHandler "print"
WorldBegin
TransformBegin
Identity
Transform [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1]
ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1]
Perspective 30
Scale 1 2 3
Skew 45 0 1 0 1 0 0
CoordinateSystem "mine"
CoordSysTransform "mine"
TransformEnd
AttributeBegin
ScopedCoordinateSystem "scoped"
Opacity [0.5 0.5 0.5]
TextureCoordinates 0 0 1 0 0 1 1 1
AreaLightSource "arealight" 1 "intensity" [0.5]
Illuminate 1 0
Displacement "bumpy" "amplitude" [0.5]
Atmosphere "fog"
Interior "water"
Exterior "air"
ShadingRate 0.5
ShadingInterpolation "smooth"
Matte 1
Bound [-1 1 -1 1 -1 1]
Detail [-1 1 -1 1 -1 1]
DetailRange 0 0 10 20
GeometricApproximation "flatness" 0.5
Orientation "rh"
ReverseOrientation
Sides 1
Attribute "identifier" "string name" ["lights"]
Deformation "twist"
Basis [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 2] 4 "catmull-rom" 1
AttributeEnd
Polygon "P" [0 0 0 1 0 0 1 1 0 0 1 0]
GeneralPolygon [4 3] "P" [0 0 0 1 0 0 1 1 0 0 1 0 0.2 0.2 0 0.8 0.2 0 0.5 0.8 0]
PointsGeneralPolygons [2] [4 3] [0 1 2 3 4 5 6] "P" [0 0 0 1 0 0 1 1 0 0 1 0 0.2 0.2 0 0.8 0.2 0 0.5 0.8 0]
Patch "bilinear" "P" [0 0 0 1 0 0 0 1 0 1 1 0] "s" [0 1 0 1]
NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 "Pw" [0 0 0 1 1 0 0 1 0 1 0 1 1 1 0 1]
TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]
Cylinder 1 0 1 180
Cone 2 1 360
Paraboloid 1 0 2 270
Hyperboloid 1 0 0 0 1 1 360
Torus 1 0.25 0 360 360
Points "P" [0 0 0 1 0 0 1 1 0] "varying float width" [0.1 0.2 0.3]
SubdivisionMesh "catmull-clark" [4] [0 1 2 3] ["interpolateboundary"] [0 1] [] [2] "P" [0 0 0 1 0 0 1 1 0 0 1 0]
Blobby 1 [1001 0] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] []
Geometry "teapot"
Procedural "DynamicLoad" ["far.so" "params"] [-1 1 -1 1 -1 1]
SolidBegin "difference"
SolidBegin "primitive"
Sphere 1 -1 1 360
SolidEnd
SolidEnd
MotionBegin [0 0.5 1]
Rotate 0 0 0 1
Rotate 10 0 0 1
Rotate 0 0 0 1
MotionEnd
WorldEnd
FrameEnd
)"));
}

TEST(RiApiDeathTest, AbortEndsTheProgramAtTheFirstError) {
    EXPECT_EXIT(
        {
            RiErrorHandler(RiErrorAbort);
            RiBegin(scratch("abort.rib").c_str());
            RiAttributeEnd();
            RiWorldBegin();  // never reached
        },
        testing::ExitedWithCode(1), "Ri:1: error: AttributeEnd without AttributeBegin");
}

// A shader's own parameters need no RiDeclare: their declarations come from its source,
// found on the shader search path the calls set (an array, a colour, a string); a
// parameter of a standard name keeps RI's declaration, as it does read from RIB.
TEST(RiApi, AShadersOwnParametersAreSizedFromItsSource) {
    const std::string dir = scratch("shaders");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/ri_mine.sl")
        << "surface ri_mine(float gain = 1; color tint = 1; string map = \"\";\n"
           "                float weights[3] = {1, 1, 1}; varying float Kd = 0.5;) {\n"
           "    Oi = 1;\n    Ci = tint * gain * Kd * weights[1];\n}\n";
    const std::string path = scratch("mine.rib");
    RiErrorHandler(collect);
    g_messages.clear();
    RiBegin(path.c_str());
    const std::string searchPath = dir + ":&";
    RtString sp = searchPath.c_str();
    RiOption("searchpath", "string shader", &sp, RI_NULL);
    RiWorldBegin();
    RtFloat gain = 2, kd = 0.25f, weights[3] = {0.5f, 1, 1.5f};
    RtColor tint = {1, 0.5f, 0.25f};
    RtString map = "grid.tx";
    RiSurface("ri_mine", "gain", &gain, "tint", tint, "map", &map, "weights", weights,
              RI_KD, &kd, RI_NULL);
    RiSurface("ri_missing", "gain", &gain, RI_NULL);  // not found: not declared
    RiWorldEnd();
    RiEnd();
    RiErrorHandler(RiErrorPrint);
    ASSERT_EQ(g_messages.size(), 1u);
    EXPECT_NE(
        g_messages[0].find("Ri:4: error: Surface: parameter \"gain\" is not declared"),
        std::string::npos)
        << g_messages[0];
    EXPECT_EQ(slurp(path),
              rewritten("Option \"searchpath\" \"string shader\" [\"" + searchPath +
                        "\"]\nWorldBegin\nSurface \"ri_mine\" \"uniform float "
                        "gain\" [2] \"uniform color tint\" [1 0.5 0.25] \"uniform "
                        "string map\" [\"grid.tx\"] \"uniform float[3] weights\" "
                        "[0.5 1 1.5] \"uniform float Kd\" [0.25]\nSurface "
                        "\"ri_missing\"\nWorldEnd\n"));
}

// Conditional RIB through the API: the branch the user option picks is the one written.
TEST(RiApi, ConditionalCallsKeepTheBranchTaken) {
    const std::string path = scratch("cond.rib");
    RiBegin(path.c_str());
    RtString pass = "shadow";
    RiOption("user", "string pass", &pass, RI_NULL);
    RiWorldBegin();
    RiIfBegin("$user:pass == 'beauty'");
    RiSphere(1, -1, 1, 360, RI_NULL);
    RiElseIf("$pass =~ '^sha'");
    RiSphere(2, -2, 2, 360, RI_NULL);
    RiElse();
    RiSphere(3, -3, 3, 360, RI_NULL);
    RiIfEnd();
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(slurp(path), rewritten("Option \"user\" \"string pass\" [\"shadow\"]\n"
                                     "WorldBegin\nSphere 2 -2 2 360\nWorldEnd\n"));
}

TEST(RiApi, ResourcesAreWritten) {
    const std::string path = scratch("resource.rib");
    RiBegin(path.c_str());
    RiWorldBegin();
    RiResourceBegin();
    RtString save = "save", restore = "restore", shading = "shading";
    RiResource("look", "attributes", "string operation", &save, RI_NULL);
    RiResource("look", "attributes", "string operation", &restore, "string subset",
               &shading, RI_NULL);
    RiResourceEnd();
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(
        slurp(path),
        rewritten("WorldBegin\nResourceBegin\nResource \"look\" \"attributes\" "
                  "\"string operation\" [\"save\"]\nResource \"look\" \"attributes\" "
                  "\"string operation\" [\"restore\"] \"string subset\" "
                  "[\"shading\"]\nResourceEnd\nWorldEnd\n"));
}

// RiArchiveRecord: comments, structure comments and verbatim RIB in the file written,
// each on lines of their own; the verbatim RIB reads back as the request it is. A render
// ignores comments and refuses verbatim RIB; an unknown type is an error.
TEST(RiApi, ArchiveRecordWritesLinesOfTheirOwn) {
    const std::string path = scratch("records.rib");
    g_messages.clear();
    g_codes.clear();
    RiErrorHandler(collect);
    RiBegin(path.c_str());
    RiArchiveRecord(RI_STRUCTURE, "RenderMan RIB-Structure 1.1");
    RiArchiveRecord(RI_COMMENT, "frame %d of %s\nsecond line", 3, "shot");
    RiWorldBegin();
    RiArchiveRecord(RI_VERBATIM, "Sphere 1 -1 1 360\n");
    RiWorldEnd();
    RiEnd();
    EXPECT_TRUE(g_messages.empty());
    const std::string written = slurp(path);
    EXPECT_EQ(written,
              "##RenderMan RIB-Structure 1.1\n# frame 3 of shot\n# second line\n"
              "WorldBegin\n  Sphere 1 -1 1 360\nWorldEnd\n");
    EXPECT_EQ(rewritten(written), rewritten("WorldBegin\nSphere 1 -1 1 360\nWorldEnd\n"));
    RiBegin(RI_NULL);
    RiArchiveRecord(RI_COMMENT, "ignored");
    RiArchiveRecord(RI_VERBATIM, "Sphere 1 -1 1 360");
    RiArchiveRecord("note", "x");
    RiEnd();
    RiErrorHandler(RiErrorPrint);
    ASSERT_EQ(g_codes.size(), 2u);
    EXPECT_EQ(g_codes[0], RIE_UNIMPLEMENT);
    EXPECT_EQ(g_codes[1], RIE_BADTOKEN);
}

// PRMan's further pixel filters go to the RIB by name, and their values are the
// renderer's: the disk is 1 within its radius, the bessel (jinc) 1 at the centre and 0 at
// its first zero (r = 1.2197 pixels), both stretched along y to the ellipse of the
// widths.
TEST(RiApi, PrmanFiltersGoByName) {
    const std::string path = scratch("filters.rib");
    RiBegin(path.c_str());
    RiPixelFilter(RiBesselFilter, 4, 4);
    RiPixelFilter(RiDiskFilter, 3, 3);
    RiPixelFilter(RiMitchellFilter, 4, 4);
    RiPixelFilter(RiSeparableCatmullRomFilter, 4, 4);
    RiPixelFilter(RiBlackmanHarrisFilter, 3, 3);
    RiPixelFilter(RiLanczosFilter, 6, 6);
    RiEnd();
    EXPECT_EQ(slurp(path),
              rewritten("PixelFilter \"bessel\" 4 4\nPixelFilter \"disk\" 3 3\n"
                        "PixelFilter \"mitchell\" 4 4\n"
                        "PixelFilter \"separable-catmull-rom\" 4 4\n"
                        "PixelFilter \"blackman-harris\" 3 3\n"
                        "PixelFilter \"lanczos\" 6 6\n"));
    EXPECT_EQ(RiDiskFilter(1.4f, 0, 3, 3), 1.0f);
    EXPECT_EQ(RiDiskFilter(1.6f, 0, 3, 3), 0.0f);
    EXPECT_EQ(RiDiskFilter(0, 0.8f, 3, 1.5f), 0.0f) << "half as tall";
    EXPECT_FLOAT_EQ(RiBesselFilter(0, 0, 4, 4), 1.0f);
    EXPECT_NEAR(RiBesselFilter(0.6f, 1.0619f, 4, 4), 0.0f, 1e-4f) << "r = 1.2197";
    EXPECT_LT(RiBesselFilter(1.5f, 0, 4, 4), 0.0f) << "the negative lobe";
    EXPECT_FLOAT_EQ(RiMitchellFilter(0, 0, 4, 4),
                    float((6 - 2.0 / 3) / 6 * (6 - 2.0 / 3) / 6));
}
