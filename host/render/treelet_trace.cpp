// treelet_trace.cpp: rounds of the treelet-streamed trace: queue growth, grouping by
// treelet, and the device treelet cache with its chunked uploads.
#include "treelet_trace.h"

#include <algorithm>
#include <cstring>
#include <deque>
#include <functional>
#include <optional>

namespace rd {

namespace {

// The cut as the tracer uploads it, whatever its node width: its nodes as bytes.
struct NodeCut {
    std::vector<unsigned char> nodes;
    size_t nodeBytes = 0;  // of one node
    std::vector<Triangle4> blocks;
    std::vector<TreeletRange> ranges;
    std::vector<TreeletRef> residentRefs;
    std::vector<std::vector<uint32_t>> links;  // each treelet's child treelets
    uint32_t maxNodes = 0, maxBlocks = 0;
    size_t allBytes = 0;
    size_t count() const { return ranges.size(); }
    size_t bytes() const { return allBytes; }
};

template <class Node>
NodeCut nodeCut(const BvhWide<Node>& bvh, size_t budget) {
    TreeletsOf<Node> t = cutTreelets(bvh, budget);
    NodeCut c;
    c.nodeBytes = sizeof(Node);
    c.nodes.resize(t.nodes.size() * sizeof(Node));
    if (!t.nodes.empty()) std::memcpy(c.nodes.data(), t.nodes.data(), c.nodes.size());
    c.residentRefs = t.residentRefs();
    c.links.resize(t.ranges.size());
    for (size_t i = 0; i < t.ranges.size(); ++i)
        for (uint32_t k = 0; k < t.ranges[i].nodeCount; ++k) {
            const Node& n = t.nodes[t.ranges[i].nodeFirst + k];
            for (size_t lane = 0; lane < std::size(n.count); ++lane)
                if (n.count[lane] == RT_TREELET_LINK) c.links[i].push_back(uint32_t(n.child[lane]));
        }
    c.allBytes = t.bytes();
    c.maxNodes = t.maxNodes, c.maxBlocks = t.maxBlocks;
    c.blocks = std::move(t.blocks);
    c.ranges = std::move(t.ranges);
    return c;
}

}  // namespace

void configureTreelets(Features& f, const ClContext& ctx, size_t budgetBytes,
                       TreeletStats& stats) {
    f.treelets = f.int64Min = false;
    stats.budgetBytes = budgetBytes;
    if (budgetBytes == 0) return;
    size_t extBytes = 0;
    clGetDeviceInfo(ctx.device(), CL_DEVICE_EXTENSIONS, 0, nullptr, &extBytes);
    std::string ext(extBytes, '\0');
    clGetDeviceInfo(ctx.device(), CL_DEVICE_EXTENSIONS, extBytes, ext.data(), nullptr);
    if (f.instances || f.procedurals)
        stats.why = "the scene has instances or deferred archives (the treelet cut does not "
                    "cover their trees): resident traversal";
    else if (ext.find("cl_khr_int64_base_atomics") == std::string::npos)
        stats.why = "the device lacks cl_khr_int64_base_atomics: resident traversal";
    if (!stats.why.empty()) return;
    f.treelets = true;
    f.int64Min = ext.find("cl_khr_int64_extended_atomics") != std::string::npos;
}

struct TreeletTracer::Impl {
    Impl(const ClContext& c, cl_program p, Profiler& prof, NodeCut&& theCut,
         TreeletStats& s)
        : ctx(c),
          st(s),
          cut(std::move(theCut)),
          closestRoot(c, p, "treelet_closest_root", prof),
          closestPairs(c, p, "treelet_closest", prof),
          shadowRoot(c, p, "treelet_shadow_root", prof),
          shadowPairs(c, p, "treelet_shadow", prof),
          scatter(c, p, "treelet_scatter", prof),
          resolve(c, p, "treelet_resolve", prof),
          program(p),
          prof(prof),
          counters(c, cut.count() + 1),
          cursor(c, cut.count()) {}

    const ClContext& ctx;
    TreeletStats& st;
    NodeCut cut;
    Kernel closestRoot, closestPairs, shadowRoot, shadowPairs, scatter, resolve;
    // The transparent shadow walk (made at its first use: only programs built with
    // RT_HAS_TRANSPARENT_SHADOWS have its kernels): its closest-hit kernels, its rays'
    // moving origins and states, their hits, what got through so far, the rays going on.
    struct Walk {
        Walk(const ClContext& c, cl_program p, Profiler& prof)
            : root(c, p, "treelet_walk_root", prof),
              pairs(c, p, "treelet_walk", prof),
              begin(c, p, "treelet_shadow_walk_begin", prof),
              step(c, p, "treelet_shadow_walk_step", prof),
              walking(c, 1) {}
        Kernel root, pairs, begin, step;
        DeviceBuffer<rt_float4> origin;
        DeviceBuffer<RayState> state;
        DeviceBuffer<RayHit> hits;
        DeviceBuffer<float> through;
        DeviceBuffer<cl_uint> walking;
    };
    std::optional<Walk> walk;
    cl_program program;
    Profiler& prof;
    DeviceBuffer<unsigned char> nodes;  // every treelet, or the cache's slots
    DeviceBuffer<Triangle4> blocks;
    DeviceBuffer<TreeletRef> refs;  // where each treelet is in nodes and blocks
    DeviceBuffer<cl_ulong> keys;    // per ray: closest hit so far, (t bits << 32) | prim
    DeviceBuffer<TreeletPair> queue, sorted;  // a round's queue as emitted, then grouped
    DeviceBuffer<cl_uint> counters, cursor;
    size_t capacity = 0;  // of queue and sorted
    // The cache (streamed only): slot s holds treelet slotTreelet[s] (slot 0: the root,
    // always), last used in chunk slotStamp[s]; treeletSlot[t] = -1 when not cached.
    std::vector<int64_t> slotTreelet, treeletSlot;
    std::vector<uint64_t> slotStamp;
    uint64_t stamp = 0;

    // Treelet t into cache slot s. The writes do not block (a round's uploads overlap
    // the host's planning of the next chunk; the in-order queue runs them before the
    // chunk's kernel): the nodes and blocks come from `cut`, which outlives them, and
    // each new TreeletRef from `pendingRefs`, whose elements stay put until the trace's
    // next blocking read, after which it is cleared.
    void upload(uint32_t t, size_t slot) {
        const TreeletRange& r = cut.ranges[t];
        write(nodes.mem(), slot * cut.maxNodes * cut.nodeBytes,
              &cut.nodes[r.nodeFirst * cut.nodeBytes], r.nodeCount * cut.nodeBytes);
        write(blocks.mem(), slot * cut.maxBlocks * sizeof(Triangle4),
              cut.blocks.data() + r.blockFirst, r.blockCount * sizeof(Triangle4));
        pendingRefs.push_back({int32_t(slot * cut.maxNodes), int32_t(slot * cut.maxBlocks)});
        write(refs.mem(), t * sizeof(TreeletRef), &pendingRefs.back(), sizeof(TreeletRef));
        if (const int64_t evicted = slotTreelet[slot]; evicted >= 0) {
            // no longer in device memory: a traversal that meets its link queues it
            treeletSlot[size_t(evicted)] = -1;
            pendingRefs.push_back({-1, -1});
            write(refs.mem(), size_t(evicted) * sizeof(TreeletRef), &pendingRefs.back(),
                  sizeof(TreeletRef));
        }
        slotTreelet[slot] = t;
        treeletSlot[t] = int64_t(slot);
        ++st.uploads;
        st.uploadedBytes += r.bytes();
    }
    void write(cl_mem m, size_t offset, const void* data, size_t bytes) {
        if (bytes)
            RD_CL_CHECK(clEnqueueWriteBuffer(ctx.queue(), m, CL_FALSE, offset, bytes, data, 0,
                                             nullptr, nullptr),
                        ctx.name());
    }
    std::deque<TreeletRef> pendingRefs;

    // Slots [0, pinned) keep their treelets: the root's and those nearest it.
    size_t pinned = 1;

    // Runs one round's grouped pairs: at once when resident, else treelet by treelet in
    // chunks whose treelets all fit in the cache (the pinned slots are never given up; a
    // slot used in the current chunk is not evicted). Returns the uploads.
    uint64_t runGrouped(const std::vector<cl_uint>& counts, const std::vector<cl_uint>& offset,
                        cl_uint total, const std::function<void(cl_uint, cl_uint)>& launch) {
        if (!st.streamed) {
            launch(0, total);
            return 0;
        }
        const uint64_t uploadsBefore = st.uploads;
        const size_t T = cut.count();
        uint64_t chunk = ++stamp;
        size_t chunkFirst = 0;
        for (size_t t = 0; t < T; ++t) {
            if (counts[t] == 0) continue;
            if (treeletSlot[t] >= 0) {
                slotStamp[size_t(treeletSlot[t])] = chunk;
                continue;
            }
            auto lru = [&] {
                size_t best = 0;
                for (size_t s = pinned; s < slotStamp.size(); ++s)
                    if (slotStamp[s] != chunk && (best == 0 || slotStamp[s] < slotStamp[best]))
                        best = s;
                return best;  // 0: every slot serves this chunk
            };
            size_t slot = lru();
            if (slot == 0) {  // the cache is full of this chunk's treelets: run them
                launch(offset[chunkFirst], offset[t] - offset[chunkFirst]);
                chunkFirst = t;
                chunk = ++stamp;
                slotStamp[0] = chunk;
                slot = lru();
            }
            upload(uint32_t(t), slot);
            slotStamp[slot] = chunk;
        }
        launch(offset[chunkFirst], total - offset[chunkFirst]);
        return st.uploads - uploadsBefore;
    }

    // Closest hits of the first n live rays through `root` and `pairs` (closest kernels),
    // then resolved into hits; `lights` rays share a sample (their time).
    void closest(Kernel& root, Kernel& pairs, cl_uint n,
                 const DeviceBuffer<rt_float4>& origin,
                 const DeviceBuffer<rt_float4>& direction,
                 const DeviceBuffer<RayState>& state, DeviceBuffer<RayHit>& hits,
                 const TraceScene& sc, cl_uint lights) {
        if (keys.size() < n) keys = DeviceBuffer<cl_ulong>(ctx, n);
        const cl_uint T = cl_uint(cut.count());
        rounds(n, [&](bool isRoot, cl_uint first, cl_uint count) {
            ++st.launches;
            (isRoot ? root : pairs)
                .launch(count, first, count, sorted, refs, nodes, blocks, origin,
                        direction, state, keys, queue, cl_uint(capacity), counters, T,
                        cl_uint(st.streamed), sc.quadrics, sc.csg, sc.triangles,
                        sc.quadricMotion, sc.trianglesEnd, sc.raySample, sc.sampleTime,
                        lights);
        });
        resolve.launch(n, n, origin, direction, state, keys, hits, sc.quadrics, sc.csg,
                       sc.triangles, sc.quadricMotion, sc.trianglesEnd, sc.raySample,
                       sc.sampleTime, lights);
    }

    // The rounds of one trace; `launch(rootOnly, first, count)` runs the closest or the
    // shadow kernel over pairs [first, first + count) of `sorted` (or the rays, rootOnly).
    void rounds(cl_uint n, const std::function<void(bool, cl_uint, cl_uint)>& launch) {
        ++st.traces;
        const size_t T = cut.count();
        counters.fillZero();
        std::function<void()> round = [&] { launch(true, 0, n); };
        round();
        if (st.byRound.empty()) st.byRound.resize(1);
        st.byRound[0].pairs += n;
        st.byRound[0].treeletsWithRays += 1;
        st.pairs += n;
        ++st.rounds;
        for (size_t r = 1;; ++r) {
            std::vector<cl_uint> counts = counters.download();  // blocks: uploads done
            pendingRefs.clear();
            const cl_uint total = counts[T];
            if (total > capacity) {
                // The queue overflowed: grow it and run the round again (keys and
                // occlusion are the same the second time; the counts start again).
                capacity = size_t(total) + total / 2;
                queue = DeviceBuffer<TreeletPair>(ctx, capacity);
                counters.fillZero();
                ++st.reruns;
                round();
                --r;
                continue;
            }
            if (sorted.size() < capacity) sorted = DeviceBuffer<TreeletPair>(ctx, capacity);
            if (total == 0) break;
            std::vector<cl_uint> offset(T, 0);
            cl_uint sum = 0, nonEmpty = 0;
            for (size_t t = 0; t < T; ++t) {
                offset[t] = sum;
                sum += counts[t];
                nonEmpty += counts[t] > 0;
            }
            cursor.upload(offset);
            scatter.launch(total, total, queue, cursor, sorted);
            counters.fillZero();
            if (st.byRound.size() <= r) st.byRound.resize(r + 1);
            st.byRound[r].pairs += total;
            st.byRound[r].treeletsWithRays += nonEmpty;
            st.pairs += total;
            ++st.rounds;
            round = [this, counts, offset, total, r, &launch] {
                st.byRound[r].uploads +=
                    runGrouped(counts, offset, total, [&](cl_uint first, cl_uint count) {
                        launch(false, first, count);
                    });
            };
            round();
        }
    }
};

template <class Node>
TreeletTracer::TreeletTracer(const ClContext& ctx, cl_program program, Profiler& prof,
                             const BvhWide<Node>& bvh, size_t budgetBytes,
                             size_t sceneMemoryBytes, size_t rays, TreeletStats& stats)
    : m(std::make_unique<Impl>(ctx, program, prof, nodeCut(bvh, budgetBytes), stats)) {
    Impl& s = *m;
    const NodeCut& cut = s.cut;
    stats.used = true;
    stats.treelets = cut.count();
    stats.treeletBytes = cut.bytes();
    stats.slotBytes = size_t(cut.maxNodes) * cut.nodeBytes + size_t(cut.maxBlocks) * sizeof(Triangle4);
    // Streamed when the cut does not fit the scene memory and a cache of at least two
    // slots (the root and one more) is smaller than the cut.
    const size_t slots = sceneMemoryBytes > 0 ? std::max<size_t>(2, sceneMemoryBytes / stats.slotBytes) : 0;
    stats.streamed = sceneMemoryBytes > 0 && sceneMemoryBytes < cut.bytes() && slots < cut.count();
    if (stats.streamed) {
        stats.cacheSlots = slots;
        s.nodes = DeviceBuffer<unsigned char>(ctx, slots * cut.maxNodes * cut.nodeBytes,
                                              CL_MEM_READ_ONLY);
        s.blocks = DeviceBuffer<Triangle4>(ctx, slots * cut.maxBlocks, CL_MEM_READ_ONLY);
        // (none in device memory yet: rt_treelet_traverse queues their links)
        s.refs = DeviceBuffer<TreeletRef>(ctx, std::vector<TreeletRef>(cut.count(), {-1, -1}));
        s.slotTreelet.assign(slots, -1);
        s.slotStamp.assign(slots, 0);
        s.treeletSlot.assign(cut.count(), -1);
        s.upload(0, 0);  // the root treelet stays resident
        // The empty slots take the treelets nearest the root, breadth first, and the
        // first half of the cache keeps them: every ray passes through them, and a ray
        // that meets the link to a treelet in the cache goes on into it in the same round
        // (rt_treelet_traverse).
        std::deque<uint32_t> next(cut.links[0].begin(), cut.links[0].end());
        for (size_t slot = 1; slot < slots && !next.empty(); ++slot) {
            const uint32_t t = next.front();
            next.pop_front();
            s.upload(t, slot);
            if (slot < slots / 2) s.pinned = slot + 1;
            next.insert(next.end(), cut.links[t].begin(), cut.links[t].end());
        }
    } else {
        stats.cacheSlots = cut.count();
        s.nodes = DeviceBuffer<unsigned char>(ctx, cut.nodes);
        s.blocks = DeviceBuffer<Triangle4>(ctx, cut.blocks);
        s.refs = DeviceBuffer<TreeletRef>(ctx, cut.residentRefs);
    }
    s.keys = DeviceBuffer<cl_ulong>(ctx, std::max<size_t>(rays, 1));
    s.capacity = std::max<size_t>(2 * rays, 1024);
    s.queue = DeviceBuffer<TreeletPair>(ctx, s.capacity);
    s.sorted = DeviceBuffer<TreeletPair>(ctx, s.capacity);
}
template TreeletTracer::TreeletTracer(const ClContext&, cl_program, Profiler&, const Bvh4&,
                                      size_t, size_t, size_t, TreeletStats&);
template TreeletTracer::TreeletTracer(const ClContext&, cl_program, Profiler&, const Bvh8&,
                                      size_t, size_t, size_t, TreeletStats&);
template TreeletTracer::TreeletTracer(const ClContext&, cl_program, Profiler&, const Bvh16&,
                                      size_t, size_t, size_t, TreeletStats&);

// Uploads may still be queued: they read from the cut and pendingRefs.
TreeletTracer::~TreeletTracer() { m->ctx.finish(); }

void TreeletTracer::closest(cl_uint n, const DeviceBuffer<rt_float4>& origin,
                            const DeviceBuffer<rt_float4>& direction,
                            const DeviceBuffer<RayState>& state, DeviceBuffer<RayHit>& hits,
                            const TraceScene& sc) {
    m->closest(m->closestRoot, m->closestPairs, n, origin, direction, state, hits, sc, 1);
}

void TreeletTracer::shadow(cl_uint n, DeviceBuffer<rt_float4>& origin,
                           const DeviceBuffer<rt_float4>& direction,
                           DeviceBuffer<RayState>& state, DeviceBuffer<float>& weight,
                           const TraceScene& sc, cl_uint lights,
                           const ShadowSurfaces* surfaces) {
    Impl& s = *m;
    lights = std::max<cl_uint>(lights, 1);
    if (surfaces) {
        // A layer a trace, from front to back, as intersect_shadow's loop: the walk ends
        // when no ray goes on, or at the transparent depth.
        if (!s.walk) s.walk.emplace(s.ctx, s.program, s.prof);
        Impl::Walk& w = *s.walk;
        if (w.state.size() < n) {
            w.origin = DeviceBuffer<rt_float4>(s.ctx, n);
            w.state = DeviceBuffer<RayState>(s.ctx, n);
            w.hits = DeviceBuffer<RayHit>(s.ctx, n);
        }
        if (w.through.size() < weight.size())
            w.through = DeviceBuffer<float>(s.ctx, weight.size());
        w.begin.launch(n, n, origin, state, weight, w.origin, w.state, w.through);
        for (int layer = 0; layer <= surfaces->maxTransparentDepth; ++layer) {
            s.closest(w.root, w.pairs, n, w.origin, direction, w.state, w.hits, sc,
                      lights);
            w.walking.fillZero();
            w.step.launch(n, n, cl_uint(layer), cl_uint(surfaces->maxTransparentDepth), w.hits,
                          w.origin, w.state, w.through, weight, surfaces->shadowAov,
                          surfaces->attrs, surfaces->materials,
                          surfaces->materialChannels, sc.quadrics, w.walking, origin, state,
                          sc.raySample, lights, surfaces->slotRays);
            if (w.walking.download()[0] == 0) break;
        }
        return;
    }
    const cl_uint T = cl_uint(s.cut.count());
    s.rounds(n, [&](bool root, cl_uint first, cl_uint count) {
        ++s.st.launches;
        (root ? s.shadowRoot : s.shadowPairs)
            .launch(count, first, count, s.sorted, s.refs, s.nodes, s.blocks, origin,
                    direction, state, weight, s.queue, cl_uint(s.capacity), s.counters, T,
                    cl_uint(s.st.streamed), sc.quadrics, sc.csg, sc.triangles,
                    sc.quadricMotion, sc.trianglesEnd, sc.raySample, sc.sampleTime,
                    lights);
    });
}

uint64_t TreeletTracer::peekRays() const {
    return m->closestRoot.peekActive() + m->shadowRoot.peekActive() +
           (m->walk ? m->walk->begin.peekActive() : 0);
}

void TreeletTracer::collectActive() {
    std::vector<Kernel*> k = {&m->closestRoot, &m->closestPairs, &m->shadowRoot,
                              &m->shadowPairs, &m->scatter,      &m->resolve};
    if (m->walk)
        k.insert(k.end(),
                 {&m->walk->root, &m->walk->pairs, &m->walk->begin, &m->walk->step});
    Kernel::collectActive(k);
}

}  // namespace rd
