// sah_builder.cpp: binned SAH BVH builder (Wald 2007, "On fast construction of SAH-based
// bounding volume hierarchies"). Each node bins primitive centroids along all three axes,
// evaluates the SAH at every bin boundary and partitions its primitive range in place.
// An explicit task stack replaces recursion so that deep trees cannot overflow the stack.
#include "host/bvh/sah_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "host/film/run_in_parts.h"

namespace rd {
namespace {

constexpr int kMaxBins = 256;

// A box padded to four lanes, so that growing one is two 4-wide min/max operations the
// compiler can vectorise; lane 3 carries no meaning.
struct Box4 {
    alignas(16) float lo[4] = {FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX};
    alignas(16) float hi[4] = {-FLT_MAX, -FLT_MAX, -FLT_MAX, -FLT_MAX};

    Box4() = default;
    explicit Box4(const Aabb& b)
        : lo{b.lo[0], b.lo[1], b.lo[2], 0.0f}, hi{b.hi[0], b.hi[1], b.hi[2], 0.0f} {}
    void grow(const Box4& b) {
        for (int a = 0; a < 4; ++a) {
            lo[a] = lo[a] < b.lo[a] ? lo[a] : b.lo[a];
            hi[a] = hi[a] > b.hi[a] ? hi[a] : b.hi[a];
        }
    }
    bool isEmpty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }
};

// Primitive reference partitioned in place during the build. Centroid is precomputed so
// that the binning and partition passes touch only this contiguous array.
struct PrimRef {
    Box4 box;
    float c[3];
    uint32_t id;
};

// Bounds of a primitive range and of its centroids, handed from parent to child so
// that no node needs a separate pass just to compute them.
struct RangeBounds {
    Box4 box;
    Aabb cbox;
};

struct BuildTask {
    uint32_t node;
    uint32_t begin, end;
    int depth;
    RangeBounds bounds;
};

struct Bin {
    Box4 box;
    uint32_t count = 0;
};

// Area of a box, or its summed edge lengths when the parent is a zero-area box (all
// primitives on a line), where area would make every SAH cost 0/0.
// In double: near +-FLT_MAX a float product overflows and SAH costs turn into NaN.
double sahMeasure(const Box4& b, bool useLength) {
    if (b.isEmpty()) return 0.0;
    double dx = double(b.hi[0]) - b.lo[0], dy = double(b.hi[1]) - b.lo[1];
    double dz = double(b.hi[2]) - b.lo[2];
    return useLength ? dx + dy + dz : 2.0 * (dx * dy + dy * dz + dz * dx);
}

class Builder {
public:
    // `binThreads`: the threads that bin a range of kParallelBinning primitives or more
    // (the top levels' builder only: the subtrees below are built on the host's cores
    // already).
    Builder(const BvhBuildSettings& s, std::vector<PrimRef>& refs, size_t binThreads = 1)
        : refs_(refs), binThreads_(binThreads) {
        binCount_ = std::clamp(s.binCount, 2, kMaxBins);
        maxLeaf_ = std::max(1, s.maxLeafSize);
        leafCap_ = std::max(kBvhMaxLeafCap, maxLeaf_);
        ct_ = s.traversalCost;
        ci_ = s.intersectionCost;
        block_ = uint32_t(std::max(1, s.blockSize));
    }

    static BvhNode emptyLeaf() {
        BvhNode n{};
        for (int a = 0; a < 3; ++a) {
            n.bmin[a] = FLT_MAX;
            n.bmax[a] = -FLT_MAX;
        }
        n.left_or_first = 0;
        n.count = 0;
        return n;
    }

    // Builds the subtree of `root` (its node: nodes[root.node]) into `nodes`, depth
    // first, raising `depth` to its deepest level. With `deferred`, a task of at most
    // `defer` primitives is set aside there instead, its node left to be filled by its
    // own build.
    void buildSubtree(const BuildTask& root, std::vector<BvhNode>& nodes, int& depth,
                      uint32_t defer = 0, std::vector<BuildTask>* deferred = nullptr) {
        std::vector<BuildTask> stack{root};
        while (!stack.empty()) {
            BuildTask t = stack.back();
            stack.pop_back();
            if (deferred && t.end - t.begin <= defer) {
                deferred->push_back(t);
                continue;
            }
            depth = std::max(depth, t.depth);
            uint32_t mid = 0;
            RangeBounds kids[2];
            if (!chooseSplit(t, nodes[t.node], mid, kids)) {
                BvhNode& n = nodes[t.node];
                n.left_or_first = int32_t(t.begin);
                n.count = int32_t(t.end - t.begin);
                continue;
            }
            // Both children are appended together, which keeps them adjacent.
            uint32_t left = uint32_t(nodes.size());
            nodes.push_back(BvhNode{});
            nodes.push_back(BvhNode{});
            nodes[t.node].left_or_first = int32_t(left);
            nodes[t.node].count = 0;
            // Left on top of the stack: depth-first order keeps subtrees close in memory.
            stack.push_back({left + 1, mid, t.end, t.depth + 1, kids[1]});
            stack.push_back({left, t.begin, mid, t.depth + 1, kids[0]});
        }
    }

    // Writes the node's bounds, then decides between a leaf (returns false) and a split
    // of [begin, end) at `mid` (returns true, refs already partitioned, kids set).
    bool chooseSplit(const BuildTask& t, BvhNode& node, uint32_t& mid,
                     RangeBounds kids[2]) {
        const Box4& box = t.bounds.box;
        const Aabb& cbox = t.bounds.cbox;
        for (int a = 0; a < 3; ++a) {
            node.bmin[a] = box.lo[a];
            node.bmax[a] = box.hi[a];
        }
        uint32_t n = t.end - t.begin;
        if (n <= uint32_t(maxLeaf_)) return false;

        useLength_ = sahMeasure(box, false) <= 0.0;
        parentMeasure_ = sahMeasure(box, useLength_);
        double leafCost = double(ci_) * blocks(n);
        bool canLeaf = n <= uint32_t(leafCap_);

        if (t.depth < kBvhMedianDepth) {
            int axis = -1, bin = 0;
            double cost = std::numeric_limits<double>::infinity();
            if (binnedSah(t, cbox, axis, bin, cost)) {
                if (canLeaf && leafCost <= cost) return false;
                mid = partition(t, cbox, axis, bin, kids);
                return true;
            }
        }
        // Object median along the widest centroid axis: used when binning cannot
        // separate the centroids (all coincide, or too close for the bins) and past
        // kBvhMedianDepth. Always splits n > 1 into two non-empty halves.
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (double(cbox.hi[a]) - cbox.lo[a] > double(cbox.hi[axis]) - cbox.lo[axis])
                axis = a;
        mid = t.begin + n / 2;
        auto first = refs_.begin() + t.begin;
        std::nth_element(
            first, refs_.begin() + mid, refs_.begin() + t.end,
            [axis](const PrimRef& x, const PrimRef& y) { return x.c[axis] < y.c[axis]; });
        for (uint32_t i = t.begin; i < t.end; ++i) {
            RangeBounds& k = kids[i < mid ? 0 : 1];
            k.box.grow(refs_[i].box);
            k.cbox.grow(refs_[i].c);
        }
        double cost = splitCost(kids[0].box, mid - t.begin, kids[1].box, t.end - mid);
        return !(canLeaf && leafCost <= cost);
    }

    double splitCost(const Box4& l, uint32_t nl, const Box4& r, uint32_t nr) const {
        // A zero-measure parent (all primitives at one point): every ratio is 1.
        if (parentMeasure_ <= 0.0) return ct_ + double(ci_) * (blocks(nl) + blocks(nr));
        return ct_ + ci_ *
                         (sahMeasure(l, useLength_) * blocks(nl) +
                          sahMeasure(r, useLength_) * blocks(nr)) /
                         parentMeasure_;
    }
    double blocks(uint32_t n) const { return double((n + block_ - 1) / block_); }

    // Scale mapping a centroid coordinate to its bin; 0 for an axis that binning cannot
    // split. The extent is taken in double because near +-FLT_MAX it overflows a float;
    // a denormal extent would overflow the float scale, so that axis is left out too.
    float binScale(const Aabb& cbox, int axis) const {
        double ext = double(cbox.hi[axis]) - cbox.lo[axis];
        float scale = ext > 0.0 ? float(binCount_ / ext) : 0.0f;
        return std::isfinite(scale) ? scale : 0.0f;
    }

    // The single bin-index formula shared by binning and partitioning, so that a
    // primitive lands on the same side in both passes. c >= lo, so the product is >= 0.
    // It may be +inf (c - lo overflowed), or NaN (inf * 0 where flush-to-zero made a
    // tiny scale 0); the comparison sends both to the last bin, never out of range.
    static int binOf(float c, float lo, float scale, float lastBin) {
        float f = (c - lo) * scale;
        return f < lastBin ? int(f) : int(lastBin);
    }

    bool binnedSah(const BuildTask& t, const Aabb& cbox, int& bestAxis, int& bestBin,
                   double& bestCost) {
        // Locals rather than members in the hot loop: the bin writes would otherwise
        // force the compiler to reload them on every primitive.
        const int k = binCount_;
        const float lastBin = float(k - 1);
        float scale[3], lo[3];
        for (int a = 0; a < 3; ++a) {
            scale[a] = binScale(cbox, a);
            lo[a] = cbox.lo[a];
            for (int b = 0; b < k; ++b) bins_[a][b] = Bin();
        }
        // An axis with scale 0 puts everything in bin 0; cheaper than a branch, and the
        // sweep below skips it.
        const PrimRef* refs = refs_.data();
        auto binRange = [&](uint32_t begin, uint32_t end, auto& bins) {
            for (uint32_t i = begin; i < end; ++i) {
                const PrimRef& r = refs[i];
                for (int a = 0; a < 3; ++a) {
                    Bin& bin =
                        bins[size_t(a)][size_t(binOf(r.c[a], lo[a], scale[a], lastBin))];
                    bin.box.grow(r.box);
                    ++bin.count;
                }
            }
        };
        const uint32_t n = t.end - t.begin;
        if (binThreads_ > 1 && n >= kParallelBinning) {
            // The top levels' large ranges on the host's cores, each part into bins of
            // its own, merged after: boxes by min and max and counts by sums, exactly
            // what one pass gives, so the same tree.
            std::vector<std::array<std::array<Bin, kMaxBins>, 3>> parts(binThreads_);
            runInParts(n, parts.size(), [&](size_t begin, size_t end, size_t part) {
                binRange(t.begin + uint32_t(begin), t.begin + uint32_t(end), parts[part]);
            });
            for (const auto& part : parts)
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < k; ++b) {
                        bins_[a][b].box.grow(part[size_t(a)][size_t(b)].box);
                        bins_[a][b].count += part[size_t(a)][size_t(b)].count;
                    }
        } else {
            binRange(t.begin, t.end, bins_);
        }
        bool found = false;
        for (int a = 0; a < 3; ++a) {
            if (scale[a] == 0.0f) continue;
            const Bin* bins = bins_[a];
            // Right-to-left sweep first: rightBox_[b] / rightCount_[b] cover bins [b, k).
            Box4 acc;
            uint32_t cnt = 0;
            for (int b = k - 1; b > 0; --b) {
                acc.grow(bins[b].box);
                cnt += bins[b].count;
                rightBox_[b] = acc;
                rightCount_[b] = cnt;
            }
            acc = Box4();
            cnt = 0;
            for (int b = 1; b < k; ++b) {
                // Behind an empty bin lies the same split as at the previous boundary.
                if (bins[b - 1].count == 0) continue;
                acc.grow(bins[b - 1].box);
                cnt += bins[b - 1].count;
                if (rightCount_[b] == 0) break;
                double cost = splitCost(acc, cnt, rightBox_[b], rightCount_[b]);
                // Strict < keeps the first of equal costs: the build is deterministic.
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = a;
                    bestBin = b;
                    found = true;
                }
            }
        }
        return found;
    }

    // Hoare partition of [begin, end) by bin; grows each side's centroid bounds on the
    // way, and takes the children's boxes from the bins rather than another pass.
    uint32_t partition(const BuildTask& t, const Aabb& cbox, int axis, int bin,
                       RangeBounds kids[2]) {
        float scale = binScale(cbox, axis);
        float lo = cbox.lo[axis];
        for (int b = 0; b < binCount_; ++b)
            kids[b < bin ? 0 : 1].box.grow(bins_[axis][b].box);
        const float lastBin = float(binCount_ - 1);
        auto isLeft = [&](const PrimRef& r) {
            return binOf(r.c[axis], lo, scale, lastBin) < bin;
        };
        uint32_t i = t.begin, j = t.end;
        for (;;) {
            while (i < j && isLeft(refs_[i])) kids[0].cbox.grow(refs_[i++].c);
            while (i < j && !isLeft(refs_[j - 1])) kids[1].cbox.grow(refs_[--j].c);
            if (i >= j) break;
            // refs_[i] belongs right and refs_[j - 1] left, so i < j - 1.
            std::swap(refs_[i], refs_[j - 1]);
            kids[0].cbox.grow(refs_[i++].c);
            kids[1].cbox.grow(refs_[--j].c);
        }
        return i;
    }

    static constexpr uint32_t kParallelBinning = 1u << 16;
    std::vector<PrimRef>& refs_;  // shared: each build partitions its own range
    size_t binThreads_;
    int binCount_ = 16, maxLeaf_ = 4, leafCap_ = kBvhMaxLeafCap;
    float ct_ = 1.0f, ci_ = 1.0f;
    uint32_t block_ = 1;
    bool useLength_ = false;
    double parentMeasure_ = 0.0;
    Bin bins_[3][kMaxBins];
    Box4 rightBox_[kMaxBins];
    uint32_t rightCount_[kMaxBins] = {};
};

}  // namespace

Bvh buildBvh(const std::vector<Aabb>& primBounds, const BvhBuildSettings& settings) {
    // left_or_first and count are int32 in the shared node layout.
    if (primBounds.size() > size_t(std::numeric_limits<int32_t>::max()) / 2)
        throw std::length_error("buildBvh: too many primitives for 32-bit node indices");
    Bvh bvh;
    std::vector<PrimRef> refs;
    refs.reserve(primBounds.size());
    for (size_t i = 0; i < primBounds.size(); ++i) {
        const Aabb& b = primBounds[i];
        if (!b.isValid()) {
            ++bvh.droppedPrims;
            continue;
        }
        PrimRef r;
        r.box = Box4(b);
        b.centroid(r.c);
        r.id = uint32_t(i);
        refs.push_back(r);
    }
    // A binary tree with leaves of >= 1 primitive has at most 2n - 1 nodes.
    bvh.nodes.reserve(refs.empty() ? 1 : 2 * refs.size() - 1);
    bvh.nodes.push_back(Builder::emptyLeaf());
    bvh.depth = 1;
    if (!refs.empty()) {
        RangeBounds bounds;
        for (const PrimRef& r : refs) {
            bounds.box.grow(r.box);
            bounds.cbox.grow(r.c);
        }
        const BuildTask root{0, 0, uint32_t(refs.size()), 1, bounds};
        const size_t threads = settings.threads > 0 ? settings.threads : hostThreads();
        // (at least 16 primitives: a part holds at least one)
        const bool parallel = refs.size() >= std::max<size_t>(settings.parallelPrims, 16);
        // The builders hold ~45 KiB of bins each; keep them off the caller's stack.
        auto builder = std::make_unique<Builder>(settings, refs, parallel ? threads : 1);
        if (!parallel) {
            builder->buildSubtree(root, bvh.nodes, bvh.depth);
        } else {
            // The top levels here; the subtrees of at most a 16th of the primitives each
            // on the host's cores, into nodes of their own, appended in the order they
            // were set aside: the same tree whatever the number of threads.
            std::vector<BuildTask> parts;
            builder->buildSubtree(root, bvh.nodes, bvh.depth, uint32_t(refs.size() / 16),
                                  &parts);
            std::vector<std::vector<BvhNode>> partNodes(parts.size());
            std::vector<int> partDepth(parts.size(), 0);
            std::vector<std::unique_ptr<Builder>> own(threads);  // a builder a thread
            runTasks(parts.size(), threads, [&](size_t i, size_t thread) {
                if (!own[thread]) own[thread] = std::make_unique<Builder>(settings, refs);
                BuildTask t = parts[i];
                t.node = 0;
                partNodes[i].reserve(2 * (t.end - t.begin) - 1);
                partNodes[i].push_back(Builder::emptyLeaf());
                own[thread]->buildSubtree(t, partNodes[i], partDepth[i]);
            });
            for (size_t i = 0; i < parts.size(); ++i) {
                // a part's node j > 0 lands at offset + j; its root in the node set aside
                const int32_t offset = int32_t(bvh.nodes.size()) - 1;
                for (size_t j = 0; j < partNodes[i].size(); ++j) {
                    BvhNode n = partNodes[i][j];
                    if (n.count == 0) n.left_or_first += offset;
                    if (j == 0)
                        bvh.nodes[parts[i].node] = n;
                    else
                        bvh.nodes.push_back(n);
                }
                bvh.depth = std::max(bvh.depth, partDepth[i]);
            }
        }
    }
    bvh.primIndices.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) bvh.primIndices[i] = refs[i].id;
    return bvh;
}

double bvhSahCost(const Bvh& bvh, float traversalCost, float intersectionCost) {
    if (bvh.empty()) return 0.0;
    auto boxOf = [](const BvhNode& n) {
        return Aabb(n.bmin[0], n.bmin[1], n.bmin[2], n.bmax[0], n.bmax[1], n.bmax[2]);
    };
    double rootArea = boxOf(bvh.nodes[0]).area();
    double inv = rootArea > 0.0 ? 1.0 / rootArea : 0.0;
    double cost = 0.0;
    for (const BvhNode& n : bvh.nodes) {
        // With a zero-area root every node's area ratio is taken to be 1.
        double ratio = rootArea > 0.0 ? boxOf(n).area() * inv : 1.0;
        cost += n.count == 0 ? traversalCost * ratio
                             : double(intersectionCost) * n.count * ratio;
    }
    return cost;
}

}  // namespace rd
