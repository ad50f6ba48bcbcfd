// render_round.cpp: one round over the pool's rays (render_loop.h): trace, sort by
// shader, shade, trace shadows; then the round's end: close it, retire the samples with
// no ray left, compact the spawned rays into the next round and queue its eye rays.
#include <algorithm>

#include "render_loop.h"

namespace rd {

namespace {
// PoCL compiles a kernel first launched with fewer than 65536 work-items for such
// launches alone, and again at its first larger launch. retire_samples' first window is
// small and later ones pass that mark in five of the seven SPD scenes: its second compile
// cost 124-146 ms of their first renders. On PoCL it takes no more work-items a launch
// than this, and a larger window takes several launches.
constexpr size_t kPoclSmallGridItems = 65536 - 64;
}  // namespace

// One round over the pool's m_n rays: trace, sort by shader, shade, shadows.
void RenderLoop::traceRound() {
    const Features& f = m_dev.f;
    const DeviceScene& ds = m_dev.ds;
    RayPool& rp = m_dev.rp;
    RenderKernels& k = m_dev.k;
    const cl_uint n = m_n, nl = m_lights, shaders = m_shaderCount;
    if (m_dev.treelets)
        m_dev.treelets->closest(n, rp.origin, rp.direction, rp.state, rp.hits,
                                m_dev.traceScene);
    else
        k.intersectClosest.launch(f.closestItems(n), n, ds.nodes, ds.blocks, rp.origin,
                                  rp.direction, rp.state, rp.hits, ds.quadrics, ds.csg,
                                  ds.triangles, ds.quadricMotion, ds.trianglesEnd,
                                  rp.sample, rp.sampleTime, rp.hitInstance);
    const cl_uint parity = cl_uint(m_st.iterations & 1);
    k.classify.launch(n, n, shaders, nl, parity, rp.hits, ds.attrs, ds.materials,
                      ds.quadrics, rp.hitInstance, rp.key, rp.keyCount, rp.keyCursor,
                      rp.spawnMask, rp.shState, rp.sample, rp.slotRays, rp.state,
                      rp.weight, rp.totals, rp.aovw, rp.aovValues);
    // One shader: no sort and no wait for the counts; its run is the whole pool in order
    // (`sorted` holds 0, 1, 2, ...) and the shade kernel skips the misses.
    if (shaders > 1) m_dev.prof.markHostWait();
    std::vector<uint32_t> counts =
        shaders == 1 ? std::vector<uint32_t>{n, 0u}
                     : rp.keyCount.downloadRange(parity * (shaders + 1), shaders + 1);
    m_keyOffsets.assign(counts.size(), 0);
    for (size_t s = 1; s < counts.size(); ++s)
        m_keyOffsets[s] = m_keyOffsets[s - 1] + counts[s - 1];
    if (shaders > 1)
        k.scatter.launch(n, n, shaders, parity, rp.key, rp.keyCount, rp.keyCursor,
                         rp.sorted);
    shadeRuns(counts, m_keyOffsets, rp.sorted, m_dev.reshade.firstList());
    if (f.textures) {  // (it waits for the lists of points to shade again)
        m_dev.prof.markHostWait();
        m_dev.reshade.run(
            m_keyOffsets, m_dev.shading.surfaceNames,
            [this](const std::vector<uint32_t>& c, const std::vector<uint32_t>& o,
                   const DeviceBuffer<uint32_t>& sorted,
                   DeviceBuffer<uint32_t>& retry) { shadeRuns(c, o, sorted, retry); });
    }
    if (nl == 0) return;
    if (m_dev.treelets)
        m_dev.treelets->shadow(cl_uint(n * nl), rp.shOrigin, rp.shDirection, rp.shState,
                               rp.shWeight, m_dev.traceScene, nl,
                               f.transparentShadows ? &m_dev.shadowSurfaces : nullptr);
    else
        k.intersectShadow.launch(
            f.shadowItems(n, nl), cl_uint(n * nl), ds.nodes, ds.blocks, rp.shOrigin,
            rp.shDirection, rp.shState, rp.shWeight, ds.quadrics, ds.csg, ds.triangles,
            ds.quadricMotion, ds.trianglesEnd, rp.sample, rp.sampleTime, nl,
            m_dev.numerics, ds.attrs, ds.materials, ds.materialChannels, rp.shAov,
            rp.slotRays);
}

// One shade kernel per shader over its run [offsets[s], + counts[s]) of `sorted`; points
// a texture miss sends back are listed in `retry` at the same offsets.
void RenderLoop::shadeRuns(const std::vector<uint32_t>& counts,
                           const std::vector<uint32_t>& offsets,
                           const DeviceBuffer<uint32_t>& sorted,
                           DeviceBuffer<uint32_t>& retry) {
    const DeviceScene& ds = m_dev.ds;
    RayPool& rp = m_dev.rp;
    TextureSet& tx = m_dev.textures;
    for (cl_uint s = 0; s < m_shaderCount; ++s) {
        if (counts[s] == 0) continue;
        m_dev.k.shade[s]->launch(
            counts[s], cl_uint(offsets[s]), cl_uint(counts[s]), sorted, rp.key,
            ds.triangles, ds.attrs, ds.normals, ds.vertexSt, ds.vertexCs, ds.vertexOs,
            ds.materials, ds.materialChannels, ds.quadrics, ds.quadricPrimvars,
            ds.quadricMotion, ds.trianglesEnd, rp.sampleTime, rp.samplePixel,
            rp.sampleIndex, rp.hitInstance, ds.params, ds.triangleParams,
            ds.pointParamValues, ds.pointParamLayout, rp.origin, rp.direction, rp.weight,
            rp.state, rp.sample, rp.hits, rp.totals, rp.nextOrigin, rp.nextDirection,
            rp.nextWeight, rp.nextState, rp.nextSample, rp.spawnMask, rp.slotRays,
            rp.shOrigin, rp.shDirection, rp.shWeight, rp.shState, rp.aov, rp.aovValues,
            rp.shAov, rp.aovw, rp.nextAovw, m_lights, m_dev.numerics, tx.infoBuf,
            tx.pageBuf, tx.tileBuf, tx.requestBuf, tx.counterBuf, tx.usedBuf, retry,
            m_dev.reshade.counts(), s);
    }
}

// compact_scatter: the rays the round spawned into the pool from `base` (~0u: behind the
// eye rays fit_refill placed), past its capacity onto the spill stack.
void RenderLoop::compactBehind(cl_uint traced, cl_uint base) {
    RayPool& rp = m_dev.rp;
    m_dev.k.compactScatter.launch(
        traced, traced, base, rp.refillFit, cl_uint(m_limits.pool), cl_uint(m_spillTop),
        cl_uint(m_spillCapacity), rp.groupLive, rp.spawnMask, rp.nextOrigin,
        rp.nextDirection, rp.nextWeight, rp.nextState, rp.nextSample, rp.origin,
        rp.direction, rp.weight, rp.state, rp.sample, rp.spillOrigin, rp.spillDirection,
        rp.spillWeight, rp.spillState, rp.spillSample, rp.nextAovw, rp.aovw, rp.spillAovw,
        rp.slotRays, rp.slotAbort, m_lights, rp.shOrigin, rp.shDirection, rp.shWeight,
        rp.shState, rp.shAov);
}

// The pool has room: it takes rays back from the spill stack, newest first (as a stack
// keeps ray trees shallow).
void RenderLoop::takeFromSpill() {
    RayPool& rp = m_dev.rp;
    const size_t take = std::min(m_limits.pool - m_n, m_spillTop);
    const size_t from = m_spillTop - take;
    const size_t n = m_n;
    rp.spillOrigin.copyTo(rp.origin, from, n, take);
    rp.spillDirection.copyTo(rp.direction, from, n, take);
    rp.spillWeight.copyTo(rp.weight, from * rp.weightFloats, n * rp.weightFloats,
                          take * rp.weightFloats);
    rp.spillState.copyTo(rp.state, from, n, take);
    rp.spillSample.copyTo(rp.sample, from, n, take);
    if (rp.rayAovFloats > 0)
        rp.spillAovw.copyTo(rp.aovw, from * rp.rayAovFloats, n * rp.rayAovFloats,
                            take * rp.rayAovFloats);
    m_spillTop = from;
    m_n += cl_uint(take);
}

// What retire_samples reported of the `window` jobs in flight: retired jobs went to the
// film and the oldest free their slots; aborted jobs (a ray dropped) are issued again,
// once.
void RenderLoop::retired(std::deque<PlannedJob>& pending, size_t window) {
    SampleRing& ring = m_dev.ring;
    m_nonfiniteRetired += m_prog[2];
    if (m_prog[1] > 0) {
        std::vector<PixelJob> all = m_dev.rp.jobs.download();
        for (size_t j = window; j-- > 0;) {
            PixelJob& r = all[(ring.frontPosition() + j) % ring.jobCapacity()];
            if ((r.state & RT_JOB_STATE_MASK) != RT_JOB_ABORTED) continue;
            r.state = RT_JOB_RETIRED;
            PlannedJob again = ring.at(j);
            again.lastTry = true;
            pending.push_front(again);
            m_st.reissuedSamples += again.count;
        }
        m_dev.rp.jobs.upload(all);
        m_refill.invalidate();  // the front of `pending` changed
    }
    const size_t done = std::min<size_t>(m_prog[0], window);
    m_st.retiredSamples += ring.samplesInFront(done);
    ring.popFront(done);
}

// The end of a round: add the shadow rays that reached their light and count the rays the
// shade stage spawned (close_round), retire the jobs whose samples have no ray left, both
// read back at one wait; then compact the spawned rays into the pool, past its capacity
// onto the spill stack, and top the pool up from the stack. Pipelined
// (RenderSettings::pipelineRounds), the compaction is queued before the wait, which waits
// for the round's reads alone, and so are the next round's eye rays, at the pool's front,
// as many of the staged jobs as fit_refill finds fit beside the spawned rays.
void RenderLoop::finishRound(std::deque<PlannedJob>& pending, cl_uint traced) {
    RayPool& rp = m_dev.rp;
    RenderKernels& k = m_dev.k;
    SampleRing& ring = m_dev.ring;
    const size_t pool = m_limits.pool;
    const bool compact = m_spawns && traced > 0;
    const size_t groups = (traced + RT_COMPACT_GROUP - 1) / RT_COMPACT_GROUP;
    const cl_uint window = cl_uint(ring.inFlight());
    const cl_uint parity = m_retireLaunches & 1u, launch = m_retireLaunches;
    if (traced > 0 && (compact || m_lights > 0))
        k.closeRound.launch(traced, traced, m_lights, cl_uint(compact), rp.sample,
                            rp.shWeight, rp.shState, rp.totals, rp.shAov, rp.aovValues,
                            rp.spawnMask, rp.groupLive);
    if (window > 0) {
        ++m_retireLaunches;
        const size_t most = m_settings.retireLaunchItems > 0
                                ? m_settings.retireLaunchItems
                            : m_dev.ctx.info().isPocl() ? kPoclSmallGridItems
                                                        : window;
        for (size_t base = 0; base < window; base += most)
            k.retire.launch(std::min<size_t>(most, window - base),
                            cl_uint(ring.frontPosition()), window,
                            cl_uint(ring.jobCapacity()), cl_uint(ring.slotCapacity()),
                            launch, cl_uint(base), rp.jobs, rp.slotRays, rp.slotAbort,
                            rp.totals, m_dev.filmBuf, rp.aov, m_dev.aovBuf, rp.aovValues,
                            m_dev.shaderAovBuf, rp.progress);
    }
    m_refill.prepare(pending, m_roundCap);  // while the device finishes the round
    // Pipelined, the wait is for the retire's read (none without jobs in flight).
    capRound();
    const bool pipelined = m_settings.pipelineRounds && window > 0;
    const bool refilled =
        pipelined && m_refill.fit(compact ? groups : 0, m_spillTop, m_roundCap);
    if (refilled) {
        rp.refillFit.downloadRangeTo(0, 3, m_fitted, /*blocking=*/false);
    } else if (compact) {
        m_live.resize(groups);
        rp.groupLive.downloadRangeTo(0, groups, m_live.data(), /*blocking=*/false);
    }
    cl_event readsDone = nullptr;
    if (window > 0)
        rp.progress.downloadRangeTo(3 * parity, 3, m_prog, /*blocking=*/false,
                                    &readsDone);
    if (refilled) m_refill.commitFitted(pending);  // eye rays at the pool's front
    if (pipelined && compact)
        compactBehind(traced, refilled ? ~0u : 0u);  // spawned behind
    m_dev.prof.markHostWait();
    if (pipelined)
        m_dev.ctx.wait(readsDone);
    else {
        if (readsDone) clReleaseEvent(readsDone);
        m_dev.ctx.finish();
    }
    size_t added = 0, total = 0;
    if (refilled) {
        m_refill.bookFitted(pending, m_fitted[0]);
        added = m_fitted[1], total = m_fitted[2];
        m_st.eyeRays += added;
        // (else the next round's start commits after all; and it adds what the slot ring
        // held back before the retire freed slots)
        m_eyeQueued = added > 0 && !m_refill.fittedRingBound();
    } else if (compact) {
        for (size_t g = 0; g < groups; ++g) total += m_live[g];
        if (!pipelined && total > 0) compactBehind(traced, 0);
    }
    const size_t held = added + total;  // (compact_scatter spills past the pool)
    m_n = cl_uint(std::min(held, pool));
    if (compact) {
        if (held > pool) {
            const size_t spilled = std::min(held - pool, m_spillCapacity - m_spillTop);
            m_st.overflowRays += held - pool - spilled;  // dropped: the sample goes again
            m_spillTop += spilled;
            m_st.spilledRays += spilled;
        } else if (m_spillTop > 0) {
            takeFromSpill();
        }
    }
    if (window > 0) retired(pending, window);
}

}  // namespace rd
