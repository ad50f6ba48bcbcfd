// rib_corpus.h: shared helpers for the RIB tests: RIB texts that together use every
// request in valid forms (the writer round-trip, binary and fuzz tests all start from
// them) and small functions that read RIB into a RecordingTarget.
#pragma once
#include <sstream>
#include <string>
#include <vector>

#include "recording_target.h"
#include "rib/reader.h"

namespace ribtest {

// Every RI 3.2 request, valid, in the scopes it belongs to.
inline const char* kKitchenSink = R"RIB(version 3.04
ErrorHandler "print"
Declare "Kd" "uniform float"
Declare "names" "string[2]"
ArchiveBegin "inl"
  Sphere 1 -1 1 360
ArchiveEnd
Format 320 240 1
FrameAspectRatio 1.333
ScreenWindow -1.333 1.333 -1 1
CropWindow 0 1 0 1
Projection "perspective" "fov" [45]
Clipping 0.1 1000
DepthOfField 2.8 0.05 10
DepthOfField
Shutter 0 1
PixelVariance 0.01
ClippingPlane 0 0 1 0 0 -1
Camera "main" "float shutteropening" [0 1]
PixelSamples 4 4
PixelFilter "catmull-rom" 3 3
PixelFilter "box" 1 1
Exposure 1 2.2
Imager "background" "color bgcolor" [0 0 0]
Quantize "rgba" 255 0 255 0.5
Display "out.tif" "file" "rgba" "string compression" "lzw"
Hider "hidden" "jitter" [1]
ColorSamples [1 0 0 0 1 0 0 0 1 0.5 0.5 0.5] [1 0 0 0.5 0 1 0 0.5 0 0 1 0.5]
Color [0.1 0.2 0.3 0.4]
ColorSamples [1 0 0 0 1 0 0 0 1] [1 0 0 0 1 0 0 0 1]
RelativeDetail 0.8
Option "limits" "integer bucketsize" [16 16]
MakeTexture "in.tif" "out.tex" "periodic" "clamp" "gaussian" 2 2 "float fov" 1
MakeBump "b.tif" "b.tex" "black" "black" "box" 1 1
MakeLatLongEnvironment "sky.tif" "sky.env" "box" 1 1
MakeCubeFaceEnvironment "px" "nx" "py" "ny" "pz" "nz" "cube.env" 95 "gaussian" 2 2
MakeShadow "z.zfile" "shadow.tex"
FrameBegin 1
Perspective 45
WorldBegin
  LightSource "ambientlight" 1 "intensity" 0.2
  LightSource "distantlight" "key" "from" [0 1 0] "to" [0 0 0]
  AreaLightSource "arealight" "area1" "intensity" 3
  Illuminate "area1" 0
  Illuminate 1 1
  AttributeBegin
    Attribute "identifier" "name" ["obj"]
    Attribute "visibility" "int trace" [1]
    Color 1 0 0
    Opacity [1 1 1]
    TextureCoordinates 0 0 1 0 0 1 1 1
    Surface "plastic" "Kd" 0.5 "names" ["a" "b"]
    Displacement "bumpy" "float Km" [0.1]
    Atmosphere "fog"
    Interior "water"
    Exterior "air"
    Deformation "twist" "float angle" 30
    ShadingRate 1
    ShadingInterpolation "smooth"
    Matte 0
    Bound [-1 1 -1 1 -1 1]
    Detail -1 1 -1 1 -1 1
    DetailRange [0 0 100 200]
    GeometricApproximation "flatness" 0.5
    Sides 2
    Orientation "rh"
    ReverseOrientation
    CoordinateSystem "mycs"
    ScopedCoordinateSystem "myscoped"
    ResourceBegin
      Resource "look" "attributes" "string operation" ["save"] "string subset" ["shading"]
      Resource "look" "attributes" "string operation" ["restore"]
    ResourceEnd
    CoordSysTransform "mycs"
    Skew 45 0 1 0 1 0 0
    Identity
    Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]
    ConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 1 2 3 1]
    Translate 0 0 5
    Rotate 30 0 1 0
    Scale 1 1 -1
    MotionBegin [0 1]
      Translate 0 0 0
      Translate 1 0 0
    MotionEnd
    MotionBegin [0 0.5 1]
      Sphere 1 -1 1 360
      Sphere 1.5 -1 1 360
      Sphere 2 -1 1 360
    MotionEnd
    Polygon "P" [0 0 0 1 0 0 1 1 0] "N" [0 0 1 0 0 1 0 0 1] "st" [0 0 1 0 1 1]
    GeneralPolygon [4 3] "P" [0 0 0 1 0 0 1 1 0 0 1 0 0.2 0.2 0 0.5 0.2 0 0.5 0.5 0]
    PointsPolygons [3 3] [0 1 2 0 2 3] "P" [0 0 0 1 0 0 1 1 0 0 1 0]
    PointsGeneralPolygons [2 1] [4 3 3] [0 1 2 3 4 5 6 0 1 2] "P" [0 0 0 1 0 0 1 1 0 0 1 0 0.2 0.2 0 0.5 0.2 0 0.5 0.5 0]
    Patch "bilinear" "P" [0 0 0 1 0 0 0 1 0 1 1 0]
    Basis "bezier" 3 "b-spline" 1
    Patch "bicubic" "P" [0 0 0 1 0 0 2 0 0 3 0 0 0 1 0 1 1 1 2 1 1 3 1 0 0 2 0 1 2 1 2 2 1 3 2 0 0 3 0 1 3 0 2 3 0 3 3 0]
    PatchMesh "bilinear" 3 "nonperiodic" 2 "nonperiodic" "P" [0 0 0 1 0 0 2 0 0 0 1 0 1 1 0 2 1 0]
    Basis "catmull-rom" 1 [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 4
    PatchMesh "bicubic" 4 "nonperiodic" 4 "periodic" "P" [0 0 0 1 0 0 2 0 0 3 0 0 0 1 0 1 1 1 2 1 1 3 1 0 0 2 0 1 2 1 2 2 1 3 2 0 0 3 0 1 3 0 2 3 0 3 3 0]
    NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 "Pw" [0 0 0 1 1 0 0 1 0 1 0 1 1 1 0 1]
    TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]
    SubdivisionMesh "catmull-clark" [4] [0 1 2 3] ["crease" "interpolateboundary"] [2 1 0 0] [0 1] [2.5] "P" [0 0 0 1 0 0 1 1 0 0 1 0]
    SubdivisionMesh "catmull-clark" [4] [0 1 2 3] "P" [0 0 0 1 0 0 1 1 0 0 1 0]
    Sphere 1 -1 1 360
    Cylinder 1 -1 1 360
    Cone 2 1 360
    Disk 0 1 360
    Torus 1 0.25 0 360 360
    Paraboloid 1 0 1 360
    Hyperboloid 1 0 0 0 1 1 360
    Hyperboloid [0.5 0 0 0.25 0 1 180]
    Curves "linear" [2 3] "nonperiodic" "P" [0 0 0 1 0 0 0 1 0 1 1 0 2 1 0] "constantwidth" 0.1
    Curves "cubic" [4] "nonperiodic" "P" [0 0 0 1 0 0 2 1 0 3 1 0] "width" [0.1 0.2]
    Points "P" [0 0 0 1 1 1] "constantwidth" [0.1]
    Blobby 2 [1001 0 1001 16 0 2 0 1] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1] [] "Cs" [1 0 0 0 1 0]
    Geometry "teapot"
    SolidBegin "union"
      SolidBegin "primitive"
        Sphere 1 -1 1 360
      SolidEnd
      SolidBegin "primitive"
        Cylinder 1 -1 1 360
      SolidEnd
    SolidEnd
    Procedural "DelayedReadArchive" ["sub.rib"] [-1 1 -1 1 -1 1]
    Procedural "RunProgram" ["gen" "args"] [-1 1 -1 1 -1 1]
    Procedural "DynamicLoad" ["lib.so" ""] [-1 1 -1 1 -1 1]
    ReadArchive "inl"
  AttributeEnd
  ObjectBegin 7
    Sphere 0.5 -0.5 0.5 360
  ObjectEnd
  ObjectBegin "named"
    Disk 0 1 360
  ObjectEnd
  ObjectInstance 7
  ObjectInstance "named"
  TransformBegin
    Translate 1 2 3
  TransformEnd
WorldEnd
FrameEnd
)RIB";

inline const std::vector<std::string>& corpus() {
    static const std::vector<std::string> texts = {
        kKitchenSink,
        "Format 64 48 1\nWorldBegin\nSurface \"matte\"\nSphere 1 -1 1 360\nWorldEnd\n",
        "Declare \"foo\" \"varying color\"\nWorldBegin\nPolygon \"P\" [0 0 0 1 0 0 1 1 0] "
        "\"foo\" [1 0 0 0 1 0 0 0 1] \"s\" [0 1 1] \"t\" [0 0 1]\nWorldEnd\n",
        "WorldBegin\nAttributeBegin\nOpacity 0.5 0.5 0.5\nColor [0.25 0.5 0.75]\n"
        "Cone 1 0.5 270 \"Os\" [1 1 1]\nAttributeEnd\nWorldEnd\n",
    };
    return texts;
}

struct ReadResult {
    bool ok = false;
    RecordingTarget target;
    std::vector<std::string> msgs;
};

inline std::vector<std::string> splitLines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) out.push_back(line);
    return out;
}

inline ReadResult readRib(const std::string& text,
                          const rib::ReadOptions& opts = rib::ReadOptions(),
                          const std::string& name = "t.rib") {
    ReadResult r;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    r.ok = rib::readString(text, name, r.target, diag, opts);
    r.msgs = splitLines(out.str());
    return r;
}

}  // namespace ribtest
