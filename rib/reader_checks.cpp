// reader_checks.cpp: the array-shape checks of the more involved primitives (TrimCurve,
// SubdivisionMesh tags, Curves, Blobby code), kept apart from reader_geometry.cpp so each
// file stays readable. All counts are summed in 64 bits.
#include "reader_impl.h"

namespace rib {
namespace detail {

bool Reader::checkTrimCurve(const Args& a, const SourceLoc& loc) {
    const std::vector<int>& ncurves = a.intArrays[0];
    const std::vector<int>& order = a.intArrays[1];
    const std::vector<int>& n = a.intArrays[2];
    for (int c : ncurves) {
        if (c < 1) {
            error(loc, "TrimCurve loops need at least one curve");
            return false;
        }
    }
    size_t total = static_cast<size_t>(sum(ncurves));
    const std::vector<float>& knot = a.floatArrays[0];
    if (order.size() != total || n.size() != total || a.floatArrays[1].size() != total ||
        a.floatArrays[2].size() != total) {
        error(loc, "TrimCurve: order, n, min and max need one value per curve (" +
                       std::to_string(total) + ")");
        return false;
    }
    long long knots = 0, cvs = 0;
    for (size_t i = 0; i < total; ++i) {
        if (order[i] < 1 || n[i] < order[i]) {
            error(loc, "TrimCurve curve " + std::to_string(i) + ": n = " +
                           std::to_string(n[i]) + " must be at least order = " +
                           std::to_string(order[i]) + " (>= 1)");
            return false;
        }
        knots += static_cast<long long>(n[i]) + order[i];
        cvs += n[i];
    }
    if (static_cast<long long>(knot.size()) != knots) {
        error(loc, "TrimCurve knot has " + std::to_string(knot.size()) +
                       " values, needs sum(n + order) = " + std::to_string(knots));
        return false;
    }
    for (size_t k = 3; k < 6; ++k) {
        if (static_cast<long long>(a.floatArrays[k].size()) != cvs) {
            error(loc, std::string("TrimCurve ") + "uvw"[k - 3] + " has " +
                           std::to_string(a.floatArrays[k].size()) +
                           " values, needs sum(n) = " + std::to_string(cvs));
            return false;
        }
    }
    return true;
}

bool Reader::checkSubdivisionMesh(const Args& a, const SourceLoc& loc) {
    const char* req = "SubdivisionMesh";
    const std::vector<int>& nverts = a.intArrays[0];
    const std::vector<int>& verts = a.intArrays[1];
    for (int n : nverts) {
        if (n < 3) {
            error(loc, std::string(req) + " face with " + std::to_string(n) +
                           " vertices (needs at least 3)");
            return false;
        }
    }
    long long total = sum(nverts);
    if (total != static_cast<long long>(verts.size())) {
        error(loc, std::string(req) + " nverts add up to " + std::to_string(total) +
                       " but verts has " + std::to_string(verts.size()) + " entries");
        return false;
    }
    long long npoints = countPoints(req, a.params, loc);
    if (npoints < 0 || !checkIndices(req, verts, npoints, "vertex", loc)) return false;
    if (!a.optionalMissing) {
        const std::vector<std::string>& tags = a.strArrays[0];
        const std::vector<int>& nargs = a.intArrays[2];
        const std::vector<int>& intargs = a.intArrays[3];
        const std::vector<float>& floatargs = a.floatArrays[0];
        if (nargs.size() != 2 * tags.size()) {
            error(loc, std::string(req) + " nargs has " + std::to_string(nargs.size()) +
                           " entries, needs 2 per tag (" +
                           std::to_string(2 * tags.size()) + ")");
            return false;
        }
        long long ni = 0, nf = 0;
        for (size_t k = 0; k < tags.size(); ++k) {
            int ci = nargs[2 * k], cf = nargs[2 * k + 1];
            if (ci < 0 || cf < 0) {
                error(loc, std::string(req) + " tag \"" + tags[k] + "\" has negative nargs");
                return false;
            }
            if (ni + ci > static_cast<long long>(intargs.size()) ||
                nf + cf > static_cast<long long>(floatargs.size())) {
                error(loc, std::string(req) + " tag \"" + tags[k] +
                               "\" needs more intargs/floatargs than given");
                return false;
            }
            std::vector<int> ints(intargs.begin() + ni, intargs.begin() + ni + ci);
            const std::string& tag = tags[k];
            if ((tag == "crease" && ci < 2) || (tag == "crease" && cf < 1) ||
                (tag == "corner" && cf < 1)) {
                error(loc, std::string(req) + " tag \"" + tag +
                               "\" needs at least 2 vertices and a sharpness");
                return false;
            }
            if ((tag == "crease" || tag == "corner") &&
                !checkIndices(req, ints, npoints, (tag + " vertex").c_str(), loc))
                return false;
            if (tag == "hole" &&
                !checkIndices(req, ints, static_cast<long long>(nverts.size()), "hole face",
                              loc))
                return false;
            ni += ci;
            nf += cf;
        }
        if (ni != static_cast<long long>(intargs.size()) ||
            nf != static_cast<long long>(floatargs.size())) {
            error(loc, std::string(req) + " nargs call for " + std::to_string(ni) +
                           " intargs and " + std::to_string(nf) + " floatargs, got " +
                           std::to_string(intargs.size()) + " and " +
                           std::to_string(floatargs.size()));
            return false;
        }
    }
    return checkVaryingCounts(req, a.params, -1, npoints, npoints, total, loc);
}

bool Reader::checkCurves(const Args& a, const SourceLoc& loc) {
    const std::string type = a.strs[0];
    bool cubic = type == "cubic", periodic = false;
    if (!cubic && type != "linear") {
        error(loc, "Curves: unknown type \"" + type + "\" (linear, cubic)");
        return false;
    }
    if (!wrapMode(a.strs[1], periodic)) {
        error(loc, "Curves: wrap must be \"periodic\" or \"nonperiodic\"");
        return false;
    }
    long long varying = 0, patches = 0, var = 0;
    for (int n : a.intArrays[0]) {
        std::string why;
        if (!spanCount(cubic, periodic, n, m_vstep, patches, var, why)) {
            error(loc, "Curves curve with " + std::to_string(n) + " vertices: " + why);
            return false;
        }
        varying += var;
    }
    long long total = sum(a.intArrays[0]);
    long long npoints = countPoints("Curves", a.params, loc);
    if (npoints < 0) return false;
    if (npoints != total) {
        error(loc, "Curves nvertices add up to " + std::to_string(total) + " but \"P\" has " +
                       plural(static_cast<size_t>(npoints), "point"));
        return false;
    }
    return checkVaryingCounts("Curves", a.params, -1, varying, total, varying, loc);
}

bool Reader::checkBlobby(const Args& a, const SourceLoc& loc) {
    long long nleaf = static_cast<long long>(a.nums[0]);
    const std::vector<int>& code = a.intArrays[0];
    size_t nfloats = a.floatArrays[0].size(), nstrings = a.strArrays[0].size();
    long long items = 0, leaves = 0;
    size_t pc = 0;
    auto bad = [&](const std::string& why) {
        error(loc, "Blobby code at " + std::to_string(pc) + ": " + why);
        return false;
    };
    while (pc < code.size()) {
        int op = code[pc++];
        auto operands = [&](size_t k) { return pc + k <= code.size(); };
        if (op >= 1000 && op <= 1003) {
            static const int floatsFor[] = {1, 16, 23, 4};
            size_t k = op == 1003 ? 2 : 1;
            if (!operands(k)) return bad("missing operands");
            long long fi = code[pc + k - 1];
            if (fi < 0 || fi + floatsFor[op - 1000] > static_cast<long long>(nfloats))
                return bad("float index out of range");
            if (op == 1003 && (code[pc] < 0 || code[pc] >= static_cast<long long>(nstrings)))
                return bad("string index out of range");
            pc += k;
            ++leaves;
        } else if (op >= 0 && op <= 7) {
            size_t count = op <= 3 ? 0 : op <= 5 ? 2 : 1;
            if (op <= 3) {
                if (!operands(1) || code[pc] < 0) return bad("missing operand count");
                count = static_cast<size_t>(code[pc++]);
            }
            if (!operands(count)) return bad("missing operands");
            for (size_t i = 0; i < count; ++i, ++pc)
                if (code[pc] < 0 || code[pc] >= items)
                    return bad("operand " + std::to_string(code[pc]) +
                               " is not an earlier item");
        } else {
            return bad("unknown opcode " + std::to_string(op));
        }
        ++items;
    }
    if (leaves != nleaf) {
        error(loc, "Blobby nleaf is " + std::to_string(nleaf) + " but the code has " +
                       plural(static_cast<size_t>(leaves), "primitive"));
        return false;
    }
    return checkVaryingCounts("Blobby", a.params, -1, nleaf, nleaf, nleaf, loc);
}

}  // namespace detail
}  // namespace rib
