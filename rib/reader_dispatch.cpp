// reader_dispatch.cpp: the last step of reading a request: geometry consistency checks
// (vertex counts and indices against "P"), Begin/End nesting, Declare bookkeeping, and
// the call of the matching Target virtual. A request that fails a check is reported and
// not forwarded, so a Target only ever sees well-formed data.
#include "reader_impl.h"

namespace rib {
namespace detail {

// The vertex positions of a primitive: "P" (3 floats a point) or "Pw" (4). Returns the
// number of points, or -1 after reporting why there are none.
long long Reader::countPoints(const char* req, const ParamList& params,
                              const SourceLoc& loc) {
    const Param* P = params.find("P");
    size_t per = 3;
    if (!P || P->floats.empty()) {
        P = params.find("Pw");
        per = 4;
    }
    if (!P || P->floats.empty()) {
        m_diag.error(loc, std::string(req) + " requires \"P\"");
        return -1;
    }
    if (P->floats.size() % per != 0) {
        m_diag.error(loc, std::string(req) + " \"" + P->name + "\" needs a multiple of " +
                              std::to_string(per) + " values, got " +
                              std::to_string(P->floats.size()));
        return -1;
    }
    return static_cast<long long>(P->floats.size() / per);
}

bool Reader::checkPointsPolygons(const Args& a, const SourceLoc& loc) {
    if (a.intArrays.size() != 2) return false;
    const std::vector<int>& nverts = a.intArrays[0];
    const std::vector<int>& verts = a.intArrays[1];
    long long sum = 0;
    for (size_t i = 0; i < nverts.size(); ++i) {
        if (nverts[i] < 3) {
            m_diag.error(loc, "PointsPolygons polygon " + std::to_string(i) + " has " +
                                  std::to_string(nverts[i]) +
                                  " vertices (needs at least 3)");
            return false;
        }
        sum += nverts[i];
    }
    if (sum != static_cast<long long>(verts.size())) {
        m_diag.error(loc, "PointsPolygons nverts add up to " + std::to_string(sum) +
                              " but verts has " + std::to_string(verts.size()) +
                              " entries");
        return false;
    }
    long long npoints = countPoints("PointsPolygons", a.params, loc);
    if (npoints < 0) return false;
    for (int v : verts) {
        if (v < 0 || v >= npoints) {
            m_diag.error(loc, "PointsPolygons vertex index " + std::to_string(v) +
                                  " out of range (" +
                                  plural(static_cast<size_t>(npoints), "point") +
                                  " in \"P\")");
            return false;
        }
    }
    return true;
}

void Reader::beginBlock(Req begin, const char* name, const SourceLoc& loc) {
    m_blocks.push_back(OpenBlock{begin, name, loc});
}

bool Reader::endBlock(Req begin, const char* beginName, const char* endName,
                      const SourceLoc& loc) {
    bool open = false;
    for (const OpenBlock& b : m_blocks) open = open || b.begin == begin;
    if (!open) {
        m_diag.error(loc, std::string(endName) + " without " + beginName);
        return false;
    }
    const OpenBlock& top = m_blocks.back();
    if (top.begin != begin) {
        m_diag.error(loc, std::string("unbalanced ") + endName +
                              " (open block: " + top.name + " at " + top.loc.str() + ")");
        return false;
    }
    m_blocks.pop_back();
    return true;
}

void Reader::dispatch(const RequestInfo& info, const Args& a, const SourceLoc& loc) {
    // parseArgs guarantees the counts; the accessors are checked anyway so a table typo
    // can never index out of range.
    auto f = [&](size_t i) {
        return i < a.nums.size() ? static_cast<float>(a.nums[i]) : 0.f;
    };
    auto n = [&](size_t i) {
        return i < a.nums.size() ? static_cast<int>(a.nums[i]) : 0;
    };
    auto s = [&](size_t i) { return i < a.strs.size() ? a.strs[i] : std::string(); };
    auto matrix = [&](float m[16]) {
        for (size_t i = 0; i < 16; ++i) m[i] = f(i);
    };
    const ParamList& P = a.params;
    Target& t = m_target;
    float m[16];
    switch (info.req) {
        case Req::FrameBegin:
            beginBlock(Req::FrameBegin, info.name, loc);
            t.frameBegin(loc, n(0));
            break;
        case Req::WorldBegin:
            beginBlock(Req::WorldBegin, info.name, loc);
            t.worldBegin(loc);
            break;
        case Req::AttributeBegin:
            beginBlock(Req::AttributeBegin, info.name, loc);
            t.attributeBegin(loc);
            break;
        case Req::TransformBegin:
            beginBlock(Req::TransformBegin, info.name, loc);
            t.transformBegin(loc);
            break;
        case Req::FrameEnd:
            if (endBlock(Req::FrameBegin, "FrameBegin", info.name, loc)) t.frameEnd(loc);
            break;
        case Req::WorldEnd:
            if (endBlock(Req::WorldBegin, "WorldBegin", info.name, loc)) t.worldEnd(loc);
            break;
        case Req::AttributeEnd:
            if (endBlock(Req::AttributeBegin, "AttributeBegin", info.name, loc))
                t.attributeEnd(loc);
            break;
        case Req::TransformEnd:
            if (endBlock(Req::TransformBegin, "TransformBegin", info.name, loc))
                t.transformEnd(loc);
            break;
        case Req::Format:
            t.format(loc, n(0), n(1), f(2));
            break;
        case Req::FrameAspectRatio:
            t.frameAspectRatio(loc, f(0));
            break;
        case Req::ScreenWindow:
            t.screenWindow(loc, f(0), f(1), f(2), f(3));
            break;
        case Req::Projection:
            t.projection(loc, s(0), P);
            break;
        case Req::Clipping:
            t.clipping(loc, f(0), f(1));
            break;
        case Req::PixelSamples:
            t.pixelSamples(loc, f(0), f(1));
            break;
        case Req::Display:
            t.display(loc, s(0), s(1), s(2), P);
            break;
        case Req::Option:
            t.option(loc, s(0), P);
            break;
        case Req::Attribute:
            t.attribute(loc, s(0), P);
            break;
        case Req::Color:
            t.color(loc, {f(0), f(1), f(2)});
            break;
        case Req::Opacity:
            t.opacity(loc, {f(0), f(1), f(2)});
            break;
        case Req::Surface:
            t.surface(loc, s(0), P);
            break;
        case Req::LightSource:
            t.lightSource(loc, s(0), s(1), P);
            break;
        case Req::Illuminate:
            t.illuminate(loc, s(0), n(0) != 0);
            break;
        case Req::ShadingRate:
            t.shadingRate(loc, f(0));
            break;
        case Req::Sides:
            t.sides(loc, n(0));
            break;
        case Req::Orientation:
            t.orientation(loc, s(0));
            break;
        case Req::ReverseOrientation:
            t.reverseOrientation(loc);
            break;
        case Req::Declare: {
            ParamDecl decl;
            std::string unused;
            if (!parseParamDecl(s(1), false, decl, unused)) {
                m_diag.error(loc, "Declare: bad declaration \"" + s(1) + "\" for \"" +
                                      s(0) + "\"");
                break;
            }
            m_declared[s(0)] = decl;
            t.declare(loc, s(0), s(1));
            break;
        }
        case Req::Identity:
            t.identity(loc);
            break;
        case Req::Transform:
            matrix(m);
            t.transform(loc, m);
            break;
        case Req::ConcatTransform:
            matrix(m);
            t.concatTransform(loc, m);
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
        case Req::Polygon:
            if (countPoints("Polygon", P, loc) >= 0) t.polygon(loc, P);
            break;
        case Req::PointsPolygons:
            if (checkPointsPolygons(a, loc))
                t.pointsPolygons(loc, a.intArrays[0], a.intArrays[1], P);
            break;
        case Req::Sphere:
            t.sphere(loc, f(0), f(1), f(2), f(3), P);
            break;
        case Req::Exposure:
        case Req::Quantize:
        case Req::PixelFilter:
        case Req::Hider:
        case Req::version:
            break;
    }
}

}  // namespace detail
}  // namespace rib
