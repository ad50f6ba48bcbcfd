// rib_builder_solids.cpp: SolidBegin/SolidEnd (RI 3.2 section 5.8). The blocks build a
// tree; at the outermost SolidEnd it becomes one CSG record (cl/include/quadric.h): the
// member surfaces with the primitive solid (leaf) each belongs to, and the boolean tree
// as a postfix program the device evaluates along each ray (cl/lib/objects.clh). Every
// primitive solid must be closed, or "inside" means nothing: its boundary circles must
// meet (a cylinder capped by two disks) and a mesh may have no boundary edges.
#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <sstream>

#include "rib_builder.h"

namespace rd {
namespace {

float boxDiagonal(const Aabb& b) {
    if (b.isEmpty()) return 0.0f;
    glm::vec3 d(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]);
    return glm::length(d);
}

Aabb intersectBoxes(const Aabb& a, const Aabb& b) {
    Aabb r;
    for (int k = 0; k < 3; ++k) {
        r.lo[k] = std::max(a.lo[k], b.lo[k]);
        r.hi[k] = std::min(a.hi[k], b.hi[k]);
    }
    return r;
}

// World distance from p to the boundary circle c of quadric q.
float distanceToCircle(const Quadric& q, const BoundaryCircle& c, glm::vec3 p) {
    glm::vec3 o = quadricToObject(q, p);
    glm::vec2 xy(o.x, o.y);
    float len = glm::length(xy);
    glm::vec2 dir = len > 0 ? xy / len : glm::vec2(1, 0);
    glm::vec3 onCircle(c.rho * dir.x, c.rho * dir.y, c.z);
    return glm::length(quadricToWorld(q, onCircle) - p);
}

}  // namespace

// A solid block saves and restores the attributes, as an attribute block does (RI 3.2).
void RibBuilder::solidBegin(L loc, S op) {
    m_attrStack.push_back(m_attrStack.back());
    if (m_defining) {
        m_diag.error(loc, "SolidBegin inside ObjectBegin is not supported");
        return;
    }
    if (!inWorld(loc, "SolidBegin")) return;
    int node = int(m_solidNodes.size());
    m_solidNodes.push_back({op, loc, {}, {}, {}});
    if (!m_solidStack.empty()) m_solidNodes[m_solidStack.back()].children.push_back(node);
    m_solidStack.push_back(node);
}

void RibBuilder::solidEnd(L) {
    if (m_attrStack.size() > 1) m_attrStack.pop_back();
    if (m_solidStack.empty()) return;
    int node = m_solidStack.back();
    m_solidStack.pop_back();
    if (m_solidStack.empty()) {
        finishSolid(node);
        m_solidNodes.clear();
    }
}

int RibBuilder::solidLeafForSurface(L loc) {
    if (m_solidStack.empty()) return -1;
    int top = m_solidStack.back();
    if (m_solidNodes[top].op == "primitive") return top;
    // A surface directly under an operation is a primitive solid of its own.
    int node = int(m_solidNodes.size());
    m_solidNodes.push_back({"primitive", loc, {}, {}, {}});
    m_solidNodes[top].children.push_back(node);
    return node;
}

// Per node (children follow their parents), whether it holds no surface at all.
std::vector<char> RibBuilder::emptySolidNodes(const std::vector<SolidNode>& nodes) {
    std::vector<char> empty(nodes.size(), 1);
    for (int i = int(nodes.size()) - 1; i >= 0; --i) {
        const SolidNode& n = nodes[size_t(i)];
        if (n.op == "primitive") {
            empty[size_t(i)] = n.members.empty();
        } else if (n.op == "intersection") {
            empty[size_t(i)] = n.children.empty();
            for (int c : n.children) empty[size_t(i)] |= empty[size_t(c)];
        } else if (n.op == "difference") {
            empty[size_t(i)] = n.children.empty() || empty[size_t(n.children[0])];
        } else {
            empty[size_t(i)] = 1;
            for (int c : n.children) empty[size_t(i)] &= empty[size_t(c)];
        }
    }
    return empty;
}

// Why a primitive solid's members do not close it ("" when they do): an edge of its
// mesh with no other triangle on it, a quadric that sweeps less than a turn or whose
// boundary circle no other member shares (within `tol`).
std::string RibBuilder::whyNotClosed(const SolidNode& n, float tol) const {
    std::string open;
    std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
    for (size_t m = 0; m < n.members.size() && open.empty(); ++m) {
        uint32_t prim = n.members[m];
        if (!(prim & RT_OBJECT_BIT)) {
            const Triangle& t = m_world.triangles[prim];
            std::array<float, 3> v[3] = {{t.v0.x, t.v0.y, t.v0.z},
                                         {t.v1.x, t.v1.y, t.v1.z},
                                         {t.v2.x, t.v2.y, t.v2.z}};
            for (int e = 0; e < 3; ++e) {
                auto a = v[e], b = v[(e + 1) % 3];
                ++edges[std::minmax(a, b)];
            }
            continue;
        }
        const Quadric& q = m_world.quadrics[prim & RT_OBJECT_MASK];
        auto circles = quadricBoundary(q);
        if (!circles) {
            open = n.memberWhat[m] + " sweeps less than 360 degrees";
            break;
        }
        for (const BoundaryCircle& c : *circles) {
            bool matched = false;
            for (size_t o = 0; o < n.members.size() && !matched; ++o) {
                uint32_t other = n.members[o];
                if (o == m || !(other & RT_OBJECT_BIT)) continue;
                const Quadric& q2 = m_world.quadrics[other & RT_OBJECT_MASK];
                auto circles2 = quadricBoundary(q2);
                if (!circles2) continue;
                for (const BoundaryCircle& c2 : *circles2) {
                    bool all = true;
                    for (int k = 0; k < 8 && all; ++k) {
                        float a = float(k) * 0.785398163f;
                        glm::vec3 p = quadricToWorld(
                            q, {c.rho * std::cos(a), c.rho * std::sin(a), c.z});
                        all = distanceToCircle(q2, c2, p) <= tol;
                    }
                    if (all) matched = true;
                }
            }
            if (!matched) {
                std::ostringstream s;
                s << n.memberWhat[m] << " has an open edge (the circle z = " << c.z
                  << ", radius " << c.rho << " in its object space)";
                open = s.str();
                break;
            }
        }
    }
    int boundaryEdges = 0;
    for (const auto& [e, count] : edges) boundaryEdges += count == 1;
    if (open.empty() && boundaryEdges > 0)
        open = "its mesh has " + std::to_string(boundaryEdges) + " boundary edge(s)";
    return open;
}

// A solid's tree being written as its members (primitive, leaf) and its program.
struct RibBuilder::SolidProgram {
    const std::vector<char>& empty;  // (emptySolidNodes)
    std::vector<uint32_t> members, program;
    int maxDepth = 0, leaves = 0;
    bool ok = true;
};

Aabb RibBuilder::solidMemberBounds(uint32_t prim) const {
    if (prim & RT_OBJECT_BIT) return m_world.quadricBounds[prim & RT_OBJECT_MASK];
    Aabb b;
    const Triangle& t = m_world.triangles[prim];
    for (const rt_float4* v : {&t.v0, &t.v1, &t.v2}) {
        const float p[3] = {v->x, v->y, v->z};
        b.grow(p);
    }
    return b;
}

// Node i's leaves, its part of the program and polarity (a member subtracted an odd
// number of times shows its inside: its shading normal is reversed), in one walk; its
// bounds.
Aabb RibBuilder::writeSolid(int i, bool negative, int depth, SolidProgram& p) {
    const SolidNode& n = m_solidNodes[i];
    p.maxDepth = std::max(p.maxDepth, depth + 1);
    if (n.op == "primitive") {
        int leaf = p.leaves++;
        if (leaf >= RT_CSG_MAX_LEAVES) {
            if (p.ok)
                m_diag.error(n.loc,
                             "SolidBegin: more than 32 primitive solids in one tree");
            p.ok = false;
        }
        Aabb b;
        for (uint32_t prim : n.members) {
            p.members.push_back(prim);
            p.members.push_back(uint32_t(leaf & 31));
            if (negative) {
                if (prim & RT_OBJECT_BIT)
                    m_world.quadrics[prim & RT_OBJECT_MASK].flags ^= RT_QF_FLIP;
                else
                    m_world.attrs[prim].flags ^= RT_QF_FLIP;
            }
            b.grow(solidMemberBounds(prim));
        }
        p.program.push_back(RT_CSG_LEAF | uint32_t(leaf & 31));
        return b;
    }
    uint32_t op = n.op == "intersection" ? RT_CSG_INTERSECTION
                  : n.op == "difference" ? RT_CSG_DIFFERENCE
                                         : RT_CSG_UNION;
    Aabb b;
    bool first = true;
    for (int c : n.children) {
        if (p.empty[c]) continue;
        bool sub = op == RT_CSG_DIFFERENCE && !first;
        Aabb cb = writeSolid(c, negative != sub, first ? depth : depth + 1, p);
        if (first)
            b = cb;
        else {
            p.program.push_back(op);
            if (op == RT_CSG_UNION)
                b.grow(cb);
            else if (op == RT_CSG_INTERSECTION)
                b = intersectBoxes(b, cb);
        }
        first = false;
    }
    return b;
}

// Whether every primitive solid is closed (its inside defined), reporting those not
bool RibBuilder::solidsClosed(const Aabb& bounds) {
    const float tol = 1e-4f * std::max(boxDiagonal(bounds), 1e-30f);
    for (const SolidNode& n : m_solidNodes) {
        if (n.op != "primitive" || n.members.empty()) continue;
        const std::string open = whyNotClosed(n, tol);
        if (!open.empty()) {
            m_diag.error(n.loc, "SolidBegin \"primitive\" is not closed, so its inside is "
                                "undefined: " + open);
            return false;
        }
    }
    return true;
}

void RibBuilder::finishSolid(int root) {
    const SolidNode& top = m_solidNodes[root];
    // Which nodes hold any surface at all: empty operands drop out of unions and
    // differences, and empty an intersection.
    const std::vector<char> empty = emptySolidNodes(m_solidNodes);
    if (empty[root]) {
        m_diag.warning(top.loc, "SolidBegin \"" + top.op + "\" is empty");
        return;
    }
    SolidProgram p{empty, {}, {}};
    const Aabb bounds = writeSolid(root, false, 0, p);
    if (p.maxDepth > 32) {
        m_diag.error(top.loc, "SolidBegin: tree deeper than 32");
        p.ok = false;
    }
    if (!p.ok || !solidsClosed(bounds)) return;

    Quadric solid{};
    solid.kind = RT_Q_CSG;
    solid.point_params = RT_NO_POINT_PARAMS;
    solid.first_member = uint32_t(m_world.csg.size());
    solid.member_count = uint32_t(p.members.size() / 2);
    m_world.csg.insert(m_world.csg.end(), p.members.begin(), p.members.end());
    solid.first_op = uint32_t(m_world.csg.size());
    solid.op_count = uint32_t(p.program.size());
    m_world.csg.insert(m_world.csg.end(), p.program.begin(), p.program.end());
    if (bounds.isEmpty()) return;  // an intersection of disjoint boxes: nothing to see
    m_world.quadrics.push_back(solid);
    m_world.quadricBounds.push_back(bounds);
}

}  // namespace rd
