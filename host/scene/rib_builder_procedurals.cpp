// rib_builder_procedurals.cpp: DelayedReadArchive deferred until a ray reaches its bound
// (RenderDrive streamed geometry on demand; so does RayDrive with archives): the call is
// kept as a box in the scene; render_with_archives.h reads the RIB again with the
// archives the rays reached loaded.
#include "rib_builder.h"
#include "rib_builder_util.h"

namespace rd {

// A DelayedReadArchive in the world is kept as a box until a ray reaches it (then the
// renderer has the RIB read again with it loaded: setLoadedProcedurals). Inside solids
// and object definitions it is read at once.
bool RibBuilder::deferProcedural(L loc, S name, Strings args, const float bound[6], S file) {
    if (m_inWorld && m_attrStack.back().lodHidden)
        return true;  // (DetailRange: not read)
    if (!m_deferProcedurals || name != "DelayedReadArchive" || !m_inWorld || m_defining ||
        !m_solidStack.empty() || args.empty())
        return false;
    const std::string key = loc.str() + "|" + args[0];
    if (m_loadProcedurals.count(key)) return false;
    const Attributes& at = m_attrStack.back();
    std::vector<glm::vec3> corners;
    for (int k = 0; k < 8; ++k)
        corners.push_back({bound[k & 1 ? 1 : 0], bound[k & 2 ? 3 : 2], bound[k & 4 ? 5 : 4]});
    Aabb box;
    for (const glm::vec3& p : worldPoints(at.ctm, corners)) {
        const float v[3] = {p.x, p.y, p.z};
        box.grow(v);
    }
    if (!(box.lo[0] <= box.hi[0])) return false;  // an empty or non-finite bound: read now
    Quadric q{};
    q.kind = RT_Q_PROCEDURAL;
    q.material = currentMaterial();
    q.shape = f4(box.lo[0], box.lo[1], box.lo[2]);
    q.shape2 = f4(box.hi[0], box.hi[1], box.hi[2]);
    q.first_member = uint32_t(m_world.procedurals.size());
    q.primvars = RT_NO_QUADRIC_PRIMVARS;
    q.point_params = RT_NO_POINT_PARAMS;
    m_world.procedurals.push_back({key, file, loc});
    m_world.quadrics.push_back(q);
    m_world.quadricBounds.push_back(box);
    return true;
}

}  // namespace rd
