// tessellate_polygons.cpp: Newell-plane projection and earcut-style ear clipping with
// hole bridging for RI general polygons.
#include "host/scene/tessellate_polygons.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace rd {
namespace {

bool fail(std::string* err, const std::string& msg) {
    if (err) *err = msg;
    return false;
}

struct Node {
    int i;
    double x, y;
    Node *prev = nullptr, *next = nullptr;
    bool steiner = false;
};

class Earcut {
public:
    std::deque<Node> pool;
    std::vector<int>* tris = nullptr;

    Node* insertNode(int i, double x, double y, Node* last) {
        pool.push_back(Node{i, x, y});
        Node* p = &pool.back();
        if (!last) {
            p->prev = p->next = p;
        } else {
            p->next = last->next;
            p->prev = last;
            last->next->prev = p;
            last->next = p;
        }
        return p;
    }
    static void removeNode(Node* p) {
        p->next->prev = p->prev;
        p->prev->next = p->next;
    }
    static double area(const Node* p, const Node* q, const Node* r) {
        return (q->y - p->y) * (r->x - q->x) - (q->x - p->x) * (r->y - q->y);
    }
    static bool equals(const Node* a, const Node* b) { return a->x == b->x && a->y == b->y; }
    static int sign(double v) { return (v > 0) - (v < 0); }
    static bool onSegment(const Node* p, const Node* q, const Node* r) {
        return q->x <= std::max(p->x, r->x) && q->x >= std::min(p->x, r->x) &&
               q->y <= std::max(p->y, r->y) && q->y >= std::min(p->y, r->y);
    }
    static bool intersects(const Node* p1, const Node* q1, const Node* p2, const Node* q2) {
        int o1 = sign(area(p1, q1, p2)), o2 = sign(area(p1, q1, q2));
        int o3 = sign(area(p2, q2, p1)), o4 = sign(area(p2, q2, q1));
        if (o1 != o2 && o3 != o4) return true;
        if (o1 == 0 && onSegment(p1, p2, q1)) return true;
        if (o2 == 0 && onSegment(p1, q2, q1)) return true;
        if (o3 == 0 && onSegment(p2, p1, q2)) return true;
        if (o4 == 0 && onSegment(p2, q1, q2)) return true;
        return false;
    }
    static bool pointInTriangle(double ax, double ay, double bx, double by, double cx,
                                double cy, double px, double py) {
        return (cx - px) * (ay - py) >= (ax - px) * (cy - py) &&
               (ax - px) * (by - py) >= (bx - px) * (ay - py) &&
               (bx - px) * (cy - py) >= (cx - px) * (by - py);
    }
    static bool locallyInside(const Node* a, const Node* b) {
        return area(a->prev, a, a->next) < 0
                   ? area(a, b, a->next) >= 0 && area(a, a->prev, b) >= 0
                   : area(a, b, a->prev) < 0 || area(a, a->next, b) < 0;
    }
    static bool middleInside(const Node* a, const Node* b) {
        const Node* p = a;
        bool inside = false;
        double px = (a->x + b->x) / 2, py = (a->y + b->y) / 2;
        do {
            if (((p->y > py) != (p->next->y > py)) && p->next->y != p->y &&
                (px < (p->next->x - p->x) * (py - p->y) / (p->next->y - p->y) + p->x))
                inside = !inside;
            p = p->next;
        } while (p != a);
        return inside;
    }
    static bool intersectsPolygon(const Node* a, const Node* b) {
        const Node* p = a;
        do {
            if (p->i != a->i && p->next->i != a->i && p->i != b->i && p->next->i != b->i &&
                intersects(p, p->next, a, b))
                return true;
            p = p->next;
        } while (p != a);
        return false;
    }
    static bool isValidDiagonal(const Node* a, const Node* b) {
        return a->next->i != b->i && a->prev->i != b->i && !intersectsPolygon(a, b) &&
               ((locallyInside(a, b) && locallyInside(b, a) && middleInside(a, b) &&
                 (area(a->prev, a, b->prev) != 0 || area(a, b->prev, b) != 0)) ||
                (equals(a, b) && area(a->prev, a, a->next) > 0 &&
                 area(b->prev, b, b->next) > 0));
    }
    static bool sectorContainsSector(const Node* m, const Node* p) {
        return area(m->prev, m, p->prev) < 0 && area(p->next, m, m->next) < 0;
    }

    // Ring with the orientation earcut expects (outer "clockwise" by its signed area).
    Node* linkedList(const std::vector<glm::dvec2>& pts, const std::vector<int>& ids,
                     bool clockwise) {
        double sum = 0;
        for (size_t i = 0, j = ids.size() - 1; i < ids.size(); j = i++)
            sum += (pts[j].x - pts[i].x) * (pts[i].y + pts[j].y);
        Node* last = nullptr;
        if (clockwise == (sum > 0)) {
            for (size_t i = 0; i < ids.size(); ++i) last = insertNode(ids[i], pts[i].x, pts[i].y, last);
        } else {
            for (size_t i = ids.size(); i-- > 0;) last = insertNode(ids[i], pts[i].x, pts[i].y, last);
        }
        if (last && equals(last, last->next)) {
            Node* n = last->next;
            removeNode(last);
            last = n;
        }
        return last;
    }

    Node* filterPoints(Node* start, Node* end = nullptr) {
        if (!start) return start;
        if (!end) end = start;
        Node* p = start;
        bool again;
        do {
            again = false;
            if (!p->steiner && (equals(p, p->next) || area(p->prev, p, p->next) == 0)) {
                removeNode(p);
                p = end = p->prev;
                if (p == p->next) break;
                again = true;
            } else {
                p = p->next;
            }
        } while (again || p != end);
        return end;
    }

    bool isEar(const Node* ear) {
        const Node *a = ear->prev, *b = ear, *c = ear->next;
        if (area(a, b, c) >= 0) return false;
        const Node* p = ear->next->next;
        while (p != ear->prev) {
            if (!equals(p, a) && !equals(p, c) &&
                pointInTriangle(a->x, a->y, b->x, b->y, c->x, c->y, p->x, p->y) &&
                area(p->prev, p, p->next) >= 0)
                return false;
            p = p->next;
        }
        return true;
    }

    void emit(const Node* a, const Node* b, const Node* c) {
        tris->insert(tris->end(), {a->i, b->i, c->i});
    }

    Node* cureLocalIntersections(Node* start) {
        Node* p = start;
        do {
            Node *a = p->prev, *b = p->next->next;
            if (!equals(a, b) && intersects(a, p, p->next, b) && locallyInside(a, b) &&
                locallyInside(b, a)) {
                emit(a, p, b);
                removeNode(p);
                removeNode(p->next);
                p = start = b;
            }
            p = p->next;
        } while (p != start);
        return filterPoints(p);
    }

    Node* splitPolygon(Node* a, Node* b) {
        Node* a2 = insertNode(a->i, a->x, a->y, nullptr);
        Node* b2 = insertNode(b->i, b->x, b->y, nullptr);
        Node *an = a->next, *bp = b->prev;
        a->next = b;
        b->prev = a;
        a2->next = an;
        an->prev = a2;
        b2->next = a2;
        a2->prev = b2;
        bp->next = b2;
        b2->prev = bp;
        return b2;
    }

    void splitEarcut(Node* start, int depth) {
        Node* a = start;
        do {
            Node* b = a->next->next;
            while (b != a->prev) {
                if (a->i != b->i && isValidDiagonal(a, b)) {
                    Node* c = splitPolygon(a, b);
                    a = filterPoints(a, a->next);
                    c = filterPoints(c, c->next);
                    earcutLinked(a, 0, depth + 1);
                    earcutLinked(c, 0, depth + 1);
                    return;
                }
                b = b->next;
            }
            a = a->next;
        } while (a != start);
    }

    void earcutLinked(Node* ear, int pass, int depth) {
        if (!ear || depth > 64) return;
        Node* stop = ear;
        while (ear->prev != ear->next) {
            Node *prev = ear->prev, *next = ear->next;
            if (isEar(ear)) {
                emit(prev, ear, next);
                removeNode(ear);
                ear = next->next;
                stop = next->next;
                continue;
            }
            ear = next;
            if (ear == stop) {
                if (pass == 0) earcutLinked(filterPoints(ear), 1, depth);
                else if (pass == 1) earcutLinked(cureLocalIntersections(filterPoints(ear)), 2, depth);
                else splitEarcut(ear, depth);
                break;
            }
        }
    }

    static Node* findHoleBridge(Node* hole, Node* outer) {
        Node* p = outer;
        double hx = hole->x, hy = hole->y, qx = -INFINITY;
        Node* m = nullptr;
        do {
            if (hy <= p->y && hy >= p->next->y && p->next->y != p->y) {
                double x = p->x + (hy - p->y) * (p->next->x - p->x) / (p->next->y - p->y);
                if (x <= hx && x > qx) {
                    qx = x;
                    m = p->x < p->next->x ? p : p->next;
                    if (x == hx) return m;
                }
            }
            p = p->next;
        } while (p != outer);
        if (!m) return nullptr;
        Node* stop = m;
        double mx = m->x, my = m->y, tanMin = INFINITY;
        p = m;
        do {
            if (hx >= p->x && p->x >= mx && hx != p->x &&
                pointInTriangle(hy < my ? hx : qx, hy, mx, my, hy < my ? qx : hx, hy, p->x, p->y)) {
                double tan = std::fabs(hy - p->y) / (hx - p->x);
                if (locallyInside(p, hole) &&
                    (tan < tanMin || (tan == tanMin && (p->x > m->x ||
                                                        (p->x == m->x && sectorContainsSector(m, p)))))) {
                    m = p;
                    tanMin = tan;
                }
            }
            p = p->next;
        } while (p != stop);
        return m;
    }

    Node* eliminateHole(Node* hole, Node* outer) {
        Node* bridge = findHoleBridge(hole, outer);
        if (!bridge) return outer;
        Node* bridgeReverse = splitPolygon(bridge, hole);
        filterPoints(bridgeReverse, bridgeReverse->next);
        return filterPoints(bridge, bridge->next);
    }
};

}  // namespace

bool triangulatePolygon(const std::vector<glm::vec3>& pts,
                        const std::vector<std::vector<int>>& loops, std::vector<int>& tris,
                        std::string* err) {
    size_t total = 0;
    for (const auto& L : loops) {
        total += L.size();
        for (int i : L)
            if (i < 0 || size_t(i) >= pts.size()) return fail(err, "polygon: vertex index out of range");
    }
    if (total > size_t(kMaxPolygonVertices)) return fail(err, "polygon: too many vertices");
    if (loops.empty() || loops[0].size() < 3) return true;
    for (int i : loops[0]) {
        const glm::vec3& p = pts[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail(err, "polygon: non-finite vertex");
    }
    // Newell normal of the outer loop and a right-handed frame (u, v, n).
    glm::dvec3 n(0.0), c(0.0);
    const auto& outer = loops[0];
    for (size_t i = 0; i < outer.size(); ++i) {
        glm::dvec3 a(pts[outer[i]]), b(pts[outer[(i + 1) % outer.size()]]);
        n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
                        (a.x - b.x) * (a.y + b.y));
        c += a;
    }
    double len = glm::length(n);
    if (!(len > 0.0)) return true;  // collinear / degenerate outer loop
    n /= len;
    glm::dvec3 u = std::fabs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                                        : glm::cross(n, glm::dvec3(0, 1, 0));
    u = glm::normalize(u);
    glm::dvec3 v = glm::cross(n, u);
    c /= double(outer.size());
    auto project = [&](const std::vector<int>& ids) {
        std::vector<glm::dvec2> q;
        q.reserve(ids.size());
        for (int i : ids) {
            glm::dvec3 d = glm::dvec3(pts[i]) - c;
            q.emplace_back(glm::dot(d, u), glm::dot(d, v));
        }
        return q;
    };
    Earcut ec;
    std::vector<int> out;
    ec.tris = &out;
    Node* outerNode = ec.linkedList(project(outer), outer, true);
    if (!outerNode || outerNode->next == outerNode->prev) return true;
    std::vector<Node*> queue;
    for (size_t h = 1; h < loops.size(); ++h) {
        if (loops[h].empty()) continue;
        Node* list = ec.linkedList(project(loops[h]), loops[h], false);
        if (!list) continue;
        if (list == list->next) list->steiner = true;
        Node *p = list, *left = list;
        do {
            if (p->x < left->x || (p->x == left->x && p->y < left->y)) left = p;
            p = p->next;
        } while (p != list);
        queue.push_back(left);
    }
    std::sort(queue.begin(), queue.end(), [](const Node* a, const Node* b) {
        return a->x != b->x ? a->x < b->x : a->y < b->y;
    });
    for (Node* h : queue) outerNode = ec.eliminateHole(h, outerNode);
    ec.earcutLinked(outerNode, 0, 0);
    // Wind every triangle counter-clockwise about n; drop zero-area ones.
    for (size_t k = 0; k + 2 < out.size(); k += 3) {
        glm::dvec3 a(pts[out[k]]), b(pts[out[k + 1]]), d(pts[out[k + 2]]);
        double s = glm::dot(glm::cross(b - a, d - a), n);
        if (s == 0.0) continue;
        if (s > 0) tris.insert(tris.end(), {out[k], out[k + 1], out[k + 2]});
        else tris.insert(tris.end(), {out[k], out[k + 2], out[k + 1]});
    }
    return true;
}

static void appendPolygonTris(SurfaceMesh& out, int base, const std::vector<int>& tris, int face) {
    for (int i : tris) out.mesh.tris.push_back(base + i);
    out.faceIndex.insert(out.faceIndex.end(), tris.size() / 3, face);
}

bool tessellateGeneralPolygon(const std::vector<int>& nverts, const std::vector<glm::vec3>& P,
                              SurfaceMesh& out, std::string* err) {
    std::vector<std::vector<int>> loops;
    size_t k = 0;
    for (int n : nverts) {
        if (n < 0 || k + size_t(n) > P.size())
            return fail(err, "GeneralPolygon: nverts does not match P");
        std::vector<int> L(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) L[i] = int(k) + i;
        k += size_t(n);
        loops.push_back(std::move(L));
    }
    if (k != P.size()) return fail(err, "GeneralPolygon: nverts does not match P");
    std::vector<int> tris;
    if (!triangulatePolygon(P, loops, tris, err)) return false;
    if (!out.mesh.n.empty()) return fail(err, "GeneralPolygon: output mesh has normals");
    int base = int(out.mesh.p.size());
    out.mesh.p.insert(out.mesh.p.end(), P.begin(), P.end());
    out.st.resize(out.mesh.p.size(), glm::vec2(0.0f));
    appendPolygonTris(out, base, tris, 0);
    return true;
}

bool tessellatePointsGeneralPolygons(const std::vector<int>& nloops,
                                     const std::vector<int>& nverts,
                                     const std::vector<int>& vertices,
                                     const std::vector<glm::vec3>& P, SurfaceMesh& out,
                                     std::string* err) {
    size_t loopsTotal = 0, vertsTotal = 0;
    for (int l : nloops) {
        if (l < 1) return fail(err, "PointsGeneralPolygons: a polygon needs a loop");
        loopsTotal += size_t(l);
    }
    if (loopsTotal != nverts.size())
        return fail(err, "PointsGeneralPolygons: nverts does not match sum(nloops)");
    for (int n : nverts) {
        if (n < 0) return fail(err, "PointsGeneralPolygons: negative nverts");
        vertsTotal += size_t(n);
    }
    if (vertsTotal != vertices.size())
        return fail(err, "PointsGeneralPolygons: vertices does not match sum(nverts)");
    if (!out.mesh.n.empty()) return fail(err, "PointsGeneralPolygons: output mesh has normals");
    std::vector<int> tris;
    std::vector<size_t> polyEnd;
    size_t li = 0, vi = 0;
    for (size_t poly = 0; poly < nloops.size(); ++poly) {
        std::vector<std::vector<int>> loops;
        for (int l = 0; l < nloops[poly]; ++l, ++li) {
            loops.emplace_back(vertices.begin() + vi, vertices.begin() + vi + nverts[li]);
            vi += size_t(nverts[li]);
        }
        if (!triangulatePolygon(P, loops, tris, err)) return false;
        polyEnd.push_back(tris.size());
    }
    int base = int(out.mesh.p.size());
    out.mesh.p.insert(out.mesh.p.end(), P.begin(), P.end());
    out.st.resize(out.mesh.p.size(), glm::vec2(0.0f));
    size_t start = 0;
    for (size_t poly = 0; poly < polyEnd.size(); ++poly) {
        std::vector<int> part(tris.begin() + start, tris.begin() + polyEnd[poly]);
        appendPolygonTris(out, base, part, int(poly));
        start = polyEnd[poly];
    }
    return true;
}

}  // namespace rd
