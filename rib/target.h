// target.h: the RenderMan Interface as a C++ abstract class. The RIB reader calls it, one
// virtual per request, each with the request's source location; the scene builder
// (host/scene/) and later a RIB writer implement it. Requests a target does not override
// do nothing. Arguments follow the RI 3.2 spec: angles in degrees, matrices row-major as
// written in RIB (RtMatrix order: m[row][col], points are row vectors, p' = p * M).
#pragma once
#include <string>
#include <vector>

#include "diagnostics.h"
#include "param_list.h"

namespace rib {

class Target {
public:
    virtual ~Target() = default;
    using L = const SourceLoc&;

    // Blocks
    virtual void frameBegin(L, int /*frame*/) {}
    virtual void frameEnd(L) {}
    virtual void worldBegin(L) {}
    virtual void worldEnd(L) {}
    virtual void attributeBegin(L) {}
    virtual void attributeEnd(L) {}
    virtual void transformBegin(L) {}
    virtual void transformEnd(L) {}

    // Options
    virtual void format(L, int /*xres*/, int /*yres*/, float /*pixelAspect*/) {}
    virtual void frameAspectRatio(L, float) {}
    virtual void screenWindow(L, float, float, float, float) {}
    virtual void projection(L, const std::string& /*name*/, const ParamList&) {}
    virtual void clipping(L, float /*near*/, float /*far*/) {}
    // A point on the plane and its normal, in the current space: what lies on the side
    // the normal points to is clipped away.
    virtual void clippingPlane(L, float /*x*/, float /*y*/, float /*z*/, float /*nx*/,
                               float /*ny*/, float /*nz*/) {}
    // Names the camera as it stands (a coordinate system of that name).
    virtual void camera(L, const std::string& /*name*/, const ParamList&) {}
    virtual void pixelSamples(L, float /*x*/, float /*y*/) {}
    virtual void display(L, const std::string& /*name*/, const std::string& /*type*/,
                         const std::string& /*mode*/, const ParamList&) {}
    virtual void option(L, const std::string& /*name*/, const ParamList&) {}
    // PRMan's DisplayChannel "type name": declares an output channel (an AOV).
    virtual void displayChannel(L, const std::string& /*channel*/, const ParamList&) {}

    // Attributes
    virtual void attribute(L, const std::string& /*name*/, const ParamList&) {}
    virtual void color(L, const std::vector<float>&) {}
    virtual void opacity(L, const std::vector<float>&) {}
    virtual void surface(L, const std::string& /*name*/, const ParamList&) {}
    virtual void lightSource(L, const std::string& /*name*/, const std::string& /*handle*/,
                             const ParamList&) {}
    virtual void illuminate(L, const std::string& /*handle*/, bool /*on*/) {}
    virtual void shadingRate(L, float) {}
    virtual void sides(L, int) {}
    virtual void orientation(L, const std::string&) {}
    virtual void reverseOrientation(L) {}

    // Transformations
    virtual void identity(L) {}
    virtual void transform(L, const float /*m*/[16]) {}
    virtual void concatTransform(L, const float /*m*/[16]) {}
    virtual void translate(L, float, float, float) {}
    virtual void rotate(L, float /*angleDeg*/, float, float, float) {}
    virtual void scale(L, float, float, float) {}

    // Geometry
    virtual void polygon(L, const ParamList&) {}
    virtual void pointsPolygons(L, const std::vector<int>& /*nverts*/,
                                const std::vector<int>& /*verts*/, const ParamList&) {}
    virtual void sphere(L, float /*radius*/, float /*zmin*/, float /*zmax*/,
                        float /*thetamaxDeg*/, const ParamList&) {}

    // Declarations: the reader resolves parameter types itself; this only tells a target
    // (a RIB writer, say) that `Declare "name" "decl"` was seen.
    virtual void declare(L, const std::string& /*name*/, const std::string& /*decl*/) {}

    // ---- The rest of RI 3.2 (added later; same conventions). Vectors are passed as
    // written; the reader has already checked their lengths against each other.
    using S = const std::string&;
    using P = const ParamList&;
    using Floats = const std::vector<float>&;
    using Ints = const std::vector<int>&;
    using Strings = const std::vector<std::string>&;

    // Options
    virtual void exposure(L, float /*gain*/, float /*gamma*/) {}
    virtual void imager(L, S /*name*/, P) {}
    virtual void quantize(L, S /*type*/, int /*one*/, int /*min*/, int /*max*/,
                          float /*ditherAmplitude*/) {}
    virtual void pixelVariance(L, float) {}
    // `filter` is the RI name: "box", "triangle", "catmull-rom", "gaussian", "sinc" (or a
    // renderer-specific one; the reader does not restrict it).
    virtual void pixelFilter(L, S /*filter*/, float /*xwidth*/, float /*ywidth*/) {}
    virtual void hider(L, S /*type*/, P) {}
    // nRGB is n*3 floats (n rows of RGB), RGBn is 3*n; both row-major.
    virtual void colorSamples(L, Floats /*nRGB*/, Floats /*RGBn*/) {}
    // A target that renders RGB asks the reader for every colour (Color, Opacity, color
    // parameters) as RGB: under ColorSamples n the reader converts the n values with the
    // nRGB matrix before the call. Writers keep the n values (false).
    virtual bool wantsRgbColors() const { return false; }
    // A target that renders up to k colour channels itself (k = keptColorSamples(), 0:
    // none) takes colours under ColorSamples n <= k as the n values, padded to three by
    // repeating the last (ColorSamples 1: v v v), and converts them at its output.
    virtual int keptColorSamples() const { return 0; }
    // Around each geometry request: its parameter list (the primitive variables) before
    // the call, nullptr after it, so a target can read them wherever it needs them.
    virtual void primitiveVariables(const ParamList* /*params*/) {}
    virtual void relativeDetail(L, float) {}
    virtual void cropWindow(L, float /*xmin*/, float /*xmax*/, float /*ymin*/,
                            float /*ymax*/) {}
    // A bare `DepthOfField` (pinhole) arrives as fstop = +infinity, the others 0.
    virtual void depthOfField(L, float /*fstop*/, float /*focalLength*/,
                              float /*focalDistance*/) {}
    virtual void shutter(L, float /*open*/, float /*close*/) {}
    virtual void errorHandler(L, S /*"print" | "ignore" | "abort"*/) {}

    // Attributes and shaders
    virtual void matte(L, bool) {}
    virtual void shadingInterpolation(L, S /*"constant" | "smooth"*/) {}
    // "primitive" (surfaces), or "lines" / "points" ... (RI 3.2 4.2.4)
    virtual void geometricRepresentation(L, S) {}
    virtual void textureCoordinates(L, float /*s1*/, float /*t1*/, float /*s2*/,
                                    float /*t2*/, float /*s3*/, float /*t3*/,
                                    float /*s4*/, float /*t4*/) {}
    virtual void bound(L, const float /*xmin xmax ymin ymax zmin zmax*/[6]) {}
    virtual void detail(L, const float /*bound*/[6]) {}
    virtual void detailRange(L, float /*minVisible*/, float /*lowerTransition*/,
                             float /*upperTransition*/, float /*maxVisible*/) {}
    virtual void geometricApproximation(L, S /*type*/, float /*value*/) {}
    virtual void displacement(L, S /*name*/, P) {}
    virtual void atmosphere(L, S /*name*/, P) {}
    virtual void interior(L, S /*name*/, P) {}
    virtual void exterior(L, S /*name*/, P) {}
    virtual void deformation(L, S /*name*/, P) {}
    virtual void areaLightSource(L, S /*name*/, S /*handle*/, P) {}
    // ubasisName/vbasisName are the names when written by name ("bezier"...), else "";
    // the matrices are always filled in (row-major).
    virtual void basis(L, S /*ubasisName*/, const float /*ubasis*/[16], int /*ustep*/,
                       S /*vbasisName*/, const float /*vbasis*/[16], int /*vstep*/) {}
    virtual void trimCurve(L, Ints /*ncurves per loop*/, Ints /*order*/, Floats /*knot*/,
                           Floats /*min*/, Floats /*max*/, Ints /*n*/, Floats /*u*/,
                           Floats /*v*/, Floats /*w*/) {}

    // Transformations and coordinate systems
    virtual void perspective(L, float /*fovDeg*/) {}
    virtual void skew(L, float /*angleDeg*/, float /*dx*/, float /*dy*/, float /*dz*/,
                      float /*ax*/, float /*ay*/, float /*az*/) {}
    virtual void coordinateSystem(L, S) {}
    // A name for the current transform until the enclosing attribute block ends.
    virtual void scopedCoordinateSystem(L, S) {}
    virtual void coordSysTransform(L, S) {}
    // RiTransformPoints: moves n points (x, y, z each) from the space `from` to `to` as
    // the state stands; false when the target keeps no state (a RIB writer) or cannot.
    virtual bool transformPoints(S /*from*/, S /*to*/, float* /*xyz*/, int /*n*/) {
        return false;
    }

    // Blocks
    virtual void motionBegin(L, Floats /*times*/) {}
    virtual void motionEnd(L) {}
    virtual void solidBegin(L, S /*"primitive" | "union" | "intersection" | "difference"*/) {}
    virtual void solidEnd(L) {}
    // Object handles are integers or strings in RIB; both arrive as strings.
    virtual void objectBegin(L, S /*handle*/) {}
    virtual void objectEnd(L) {}
    virtual void objectInstance(L, S /*handle*/) {}
    virtual void archiveBegin(L, S /*name*/, P) {}
    virtual void archiveEnd(L) {}
    // Only called when ReadOptions::expandArchives is false; by default the reader reads
    // the archive itself and the target sees its requests.
    virtual void readArchive(L, S /*file*/, P) {}
    // PRMan's Resource "name" "attributes" "string operation" ["save"|"restore"]
    // "string subset" ["all"|"shading"|"transform"]: a named copy of the attributes,
    // restored later; names given inside ResourceBegin/ResourceEnd end with the block.
    // The reader has checked the operation, the subset and that a restored name exists.
    virtual void resourceBegin(L) {}
    virtual void resourceEnd(L) {}
    virtual void resource(L, S /*name*/, S /*type*/, P) {}

    // Geometry
    virtual void generalPolygon(L, Ints /*nverts per loop*/, P) {}
    virtual void pointsGeneralPolygons(L, Ints /*nloops*/, Ints /*nverts*/, Ints /*verts*/,
                                       P) {}
    virtual void patch(L, S /*"bilinear" | "bicubic"*/, P) {}
    virtual void patchMesh(L, S /*type*/, int /*nu*/, S /*uwrap*/, int /*nv*/,
                           S /*vwrap*/, P) {}
    virtual void nuPatch(L, int /*nu*/, int /*uorder*/, Floats /*uknot*/, float /*umin*/,
                         float /*umax*/, int /*nv*/, int /*vorder*/, Floats /*vknot*/,
                         float /*vmin*/, float /*vmax*/, P) {}
    virtual void subdivisionMesh(L, S /*scheme*/, Ints /*nverts*/, Ints /*verts*/,
                                 Strings /*tags*/, Ints /*nargs*/, Ints /*intargs*/,
                                 Floats /*floatargs*/, P) {}
    virtual void cylinder(L, float /*radius*/, float /*zmin*/, float /*zmax*/,
                          float /*thetamaxDeg*/, P) {}
    virtual void cone(L, float /*height*/, float /*radius*/, float /*thetamaxDeg*/, P) {}
    virtual void disk(L, float /*height*/, float /*radius*/, float /*thetamaxDeg*/, P) {}
    virtual void torus(L, float /*majorRadius*/, float /*minorRadius*/, float /*phiMinDeg*/,
                       float /*phiMaxDeg*/, float /*thetamaxDeg*/, P) {}
    virtual void paraboloid(L, float /*rmax*/, float /*zmin*/, float /*zmax*/,
                            float /*thetamaxDeg*/, P) {}
    virtual void hyperboloid(L, const float /*point1*/[3], const float /*point2*/[3],
                             float /*thetamaxDeg*/, P) {}
    virtual void curves(L, S /*"linear" | "cubic"*/, Ints /*nvertices*/,
                        S /*"periodic" | "nonperiodic"*/, P) {}
    virtual void points(L, P) {}
    virtual void blobby(L, int /*nleaf*/, Ints /*code*/, Floats /*floats*/,
                        Strings /*strings*/, P) {}
    virtual void geometry(L, S /*type*/, P) {}
    // "DelayedReadArchive" | "RunProgram" | "DynamicLoad"; bound is 6 floats.
    virtual void procedural(L, S /*name*/, Strings /*args*/, const float /*bound*/[6]) {}
    // Before the reader expands a DelayedReadArchive (file: the archive it would read,
    // found on the archive search path): a target that loads it only once a ray reaches
    // its bound keeps it and returns true; the reader then reads nothing now.
    virtual bool deferProcedural(L, S /*name*/, Strings /*args*/, const float /*bound*/[6],
                                 S /*file*/) {
        return false;
    }
    // Whether the reader runs DynamicLoad procedurals for this target (a scene builder)
    // when a loader is set (run_program.h), rather than passing them on (a RIB writer).
    virtual bool runsDynamicLoad() const { return false; }

    // Texture making (outside World)
    virtual void makeTexture(L, S /*picture*/, S /*texture*/, S /*swrap*/, S /*twrap*/,
                             S /*filter*/, float /*swidth*/, float /*twidth*/, P) {}
    virtual void makeBump(L, S /*picture*/, S /*texture*/, S /*swrap*/, S /*twrap*/,
                          S /*filter*/, float /*swidth*/, float /*twidth*/, P) {}
    virtual void makeLatLongEnvironment(L, S /*picture*/, S /*texture*/, S /*filter*/,
                                        float /*swidth*/, float /*twidth*/, P) {}
    // faces: px nx py ny pz nz
    virtual void makeCubeFaceEnvironment(L, Strings /*faces (6)*/, S /*texture*/,
                                         float /*fov*/, S /*filter*/, float /*swidth*/,
                                         float /*twidth*/, P) {}
    virtual void makeShadow(L, S /*picture*/, S /*texture*/, P) {}
};

} // namespace rib
