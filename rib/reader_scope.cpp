// reader_scope.cpp: block structure and valid scopes. Begin/End requests are matched on a
// stack; every other request is checked against the scope its requests.def row allows
// (options before WorldBegin, geometry inside World or an object definition, lights in
// World, only motion-capable requests inside MotionBegin, all of the same request and as
// many as there are times). A request in the wrong place is reported and not forwarded.
#include "reader_impl.h"

namespace rib {
namespace detail {

bool Reader::has(Req begin) const { return m_open[size_t(begin)] > 0; }

void Reader::beginBlock(Req begin, const char* name, const SourceLoc& loc) {
    OpenBlock b;
    b.begin = begin;
    b.name = name;
    b.loc = loc;
    b.ustep = m_ustep;
    b.vstep = m_vstep;
    b.condAttributes = m_condAttributes;  // (shared until an Attribute changes it)
    m_blocks.push_back(std::move(b));
    ++m_open[size_t(begin)];
}

bool Reader::endBlock(Req begin, const char* beginName, const char* endName,
                      const SourceLoc& loc) {
    if (!has(begin)) {
        error(loc, std::string(endName) + " without " + beginName);
        return false;
    }
    const OpenBlock& top = m_blocks.back();
    if (top.begin != begin) {
        error(loc, std::string("unbalanced ") + endName + " (open block: " + top.name +
                       " at " + top.loc.str() + ")");
        return false;
    }
    if (begin == Req::AttributeBegin || begin == Req::WorldBegin ||
        begin == Req::FrameBegin) {
        m_ustep = top.ustep;  // Basis is an attribute: restored with the others
        m_vstep = top.vstep;
        m_condAttributes = std::const_pointer_cast<CondValues>(top.condAttributes);
    }
    if (begin == Req::FrameBegin) m_frame.reset();
    m_blocks.pop_back();
    --m_open[size_t(begin)];
    return true;
}

bool Reader::checkScope(const RequestInfo& info, const SourceLoc& loc) {
    const std::string req = info.name;
    if (!m_blocks.empty() && m_blocks.back().begin == Req::MotionBegin &&
        info.req != Req::MotionEnd) {
        OpenBlock& mb = m_blocks.back();
        if (!info.motion) {
            error(loc, req + " is not allowed inside MotionBegin/MotionEnd");
            return false;
        }
        if (mb.motionReq && req != mb.motionReq) {
            error(loc, "MotionBegin at " + mb.loc.str() + " mixes " + mb.motionReq +
                           " and " + req);
            return false;
        }
        if (mb.motionCount >= mb.motionTimes) {
            error(loc, "MotionBegin at " + mb.loc.str() + " has " +
                           plural(mb.motionTimes, "time") + " but more requests");
            return false;
        }
        mb.motionReq = info.name;
        ++mb.motionCount;
    }
    // The contents of an archive definition are checked where the archive is read.
    if (has(Req::ArchiveBegin)) return true;
    bool world = has(Req::WorldBegin), object = has(Req::ObjectBegin);
    switch (info.kind) {
        case Kind::Opt:
            if (world || object) {
                error(loc, req + " is an option: not allowed inside " +
                               (object ? "ObjectBegin/ObjectEnd" : "WorldBegin/WorldEnd"));
                return false;
            }
            break;
        case Kind::Tex:
            if (world) {
                error(loc, req + " is not allowed inside WorldBegin/WorldEnd");
                return false;
            }
            break;
        case Kind::Geom:
            if (!world && !object) {
                error(loc, req + " outside WorldBegin/WorldEnd");
                return false;
            }
            break;
        case Kind::Light:
            // (before WorldBegin a light is placed in camera space and lights the world:
            // PRMan 3's RIB, the RenderMan Companion's listings)
            if (object) {
                error(loc, req + " is not allowed inside ObjectBegin/ObjectEnd");
                return false;
            }
            break;
        case Kind::Any:
        case Kind::Attr:
        case Kind::Xform:
        case Kind::Block:
            break;
    }
    return true;
}

bool Reader::dispatchBlock(const RequestInfo& info, const Args& a, const SourceLoc& loc) {
    return dispatchBegin(info, a, loc) || dispatchEnd(info, loc);
}

bool Reader::dispatchBegin(const RequestInfo& info, const Args& a, const SourceLoc& loc) {
    const ArgAt v{a};
    Target& t = m_target;
    const std::string req = info.name;
    bool world = has(Req::WorldBegin), object = has(Req::ObjectBegin);
    switch (info.req) {
        case Req::FrameBegin:
            if (has(Req::FrameBegin) || world || object) {
                error(loc, req + " is not allowed inside " +
                               (object ? "ObjectBegin" : world ? "WorldBegin" : "FrameBegin"));
                break;
            }
            beginBlock(Req::FrameBegin, info.name, loc);
            m_frame = a.nums.empty() ? 0 : static_cast<int>(a.nums[0]);
            t.frameBegin(loc, a.nums.empty() ? 0 : static_cast<int>(a.nums[0]));
            break;
        case Req::WorldBegin:
            if (world || object) {
                error(loc, req + " is not allowed inside " +
                               (object ? "ObjectBegin" : "WorldBegin"));
                break;
            }
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
        case Req::MotionBegin:
            motionBegin(a.floatArrays.at(0), loc);
            break;
        case Req::SolidBegin:
            solidBegin(v.s(0), loc);
            break;
        case Req::ObjectBegin:
            if (object) {
                error(loc, "ObjectBegin is not allowed inside ObjectBegin");
                break;
            }
            beginBlock(Req::ObjectBegin, info.name, loc);
            m_objects.insert(v.s(0));
            t.objectBegin(loc, v.s(0));
            break;
        case Req::ArchiveBegin:
            if (m_opts.expandArchives) {
                recordInlineArchive(v.s(0), loc);
                break;
            }
            beginBlock(Req::ArchiveBegin, info.name, loc);
            t.archiveBegin(loc, v.s(0), a.params);
            break;
        case Req::ResourceBegin:
            beginBlock(Req::ResourceBegin, info.name, loc);
            m_resources.emplace_back();
            t.resourceBegin(loc);
            break;
        default:
            return false;
    }
    return true;
}

void Reader::motionBegin(const std::vector<float>& times, const SourceLoc& loc) {
    if (times.empty()) {
        error(loc, "MotionBegin needs at least one time");
        return;
    }
    for (size_t i = 1; i < times.size(); ++i) {
        if (!(times[i] >= times[i - 1])) {
            error(loc, "MotionBegin times must not decrease");
            return;
        }
    }
    beginBlock(Req::MotionBegin, "MotionBegin", loc);
    m_blocks.back().motionTimes = times.size();
    m_target.motionBegin(loc, times);
}

void Reader::solidBegin(const std::string& op, const SourceLoc& loc) {
    if (op != "primitive" && op != "union" && op != "intersection" &&
        op != "difference") {
        error(loc, "SolidBegin: unknown operation \"" + op +
                       "\" (primitive, union, intersection, difference)");
        return;
    }
    if (!has(Req::WorldBegin) && !has(Req::ObjectBegin) && !has(Req::ArchiveBegin)) {
        error(loc, "SolidBegin outside WorldBegin/WorldEnd");
        return;
    }
    for (auto it = m_blocks.rbegin(); it != m_blocks.rend(); ++it) {
        if (it->begin != Req::SolidBegin) continue;
        if (it->solidOp == "primitive") {
            error(loc, "SolidBegin inside a primitive solid (at " + it->loc.str() + ")");
            return;
        }
        break;
    }
    beginBlock(Req::SolidBegin, "SolidBegin", loc);
    m_blocks.back().solidOp = op;
    m_target.solidBegin(loc, op);
}

bool Reader::dispatchEnd(const RequestInfo& info, const SourceLoc& loc) {
    Target& t = m_target;
    const char* end = info.name;
    switch (info.req) {
        case Req::FrameEnd:
            if (endBlock(Req::FrameBegin, "FrameBegin", end, loc)) t.frameEnd(loc);
            break;
        case Req::WorldEnd:
            if (endBlock(Req::WorldBegin, "WorldBegin", end, loc)) t.worldEnd(loc);
            break;
        case Req::AttributeEnd:
            if (endBlock(Req::AttributeBegin, "AttributeBegin", end, loc))
                t.attributeEnd(loc);
            break;
        case Req::TransformEnd:
            if (endBlock(Req::TransformBegin, "TransformBegin", end, loc))
                t.transformEnd(loc);
            break;
        case Req::MotionEnd:
            motionEnd(loc);
            break;
        case Req::SolidEnd:
            if (endBlock(Req::SolidBegin, "SolidBegin", end, loc)) t.solidEnd(loc);
            break;
        case Req::ResourceEnd:
            if (endBlock(Req::ResourceBegin, "ResourceBegin", end, loc)) {
                m_resources.pop_back();
                t.resourceEnd(loc);
            }
            break;
        case Req::ObjectEnd:
            if (endBlock(Req::ObjectBegin, "ObjectBegin", end, loc)) t.objectEnd(loc);
            break;
        case Req::ArchiveEnd:
            if (endBlock(Req::ArchiveBegin, "ArchiveBegin", end, loc)) t.archiveEnd(loc);
            break;
        default:
            return false;
    }
    return true;
}

// MotionEnd: closed even when its count of requests is wrong, so that the target's
// nesting stays balanced.
void Reader::motionEnd(const SourceLoc& loc) {
    if (m_blocks.empty() || m_blocks.back().begin != Req::MotionBegin) {
        endBlock(Req::MotionBegin, "MotionBegin", "MotionEnd", loc);
        return;
    }
    OpenBlock mb = m_blocks.back();
    endBlock(Req::MotionBegin, "MotionBegin", "MotionEnd", loc);
    if (mb.motionCount != mb.motionTimes)
        error(loc, "MotionBegin at " + mb.loc.str() + " has " +
                       plural(mb.motionTimes, "time") + " but " +
                       plural(mb.motionCount, "request"));
    m_target.motionEnd(loc);
}

}  // namespace detail
}  // namespace rib
