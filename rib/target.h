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
    virtual void pixelSamples(L, float /*x*/, float /*y*/) {}
    virtual void display(L, const std::string& /*name*/, const std::string& /*type*/,
                         const std::string& /*mode*/, const ParamList&) {}
    virtual void option(L, const std::string& /*name*/, const ParamList&) {}

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
};

} // namespace rib
