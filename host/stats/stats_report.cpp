// stats_report.cpp: building the --stats JSON and its table form.
#include "stats_report.h"

#include <iomanip>
#include <ostream>

namespace rd {

namespace {
using nlohmann::json;

// One of a render's two programs (render_programs.h): its own options (the trace
// program's, only those its source reads), whether it was cached, its build time.
json programPart(const ProgramBuildInfo& p) {
    return {{"build_options", p.options},
            {"cache_hit", p.cacheHit},
            {"cache_key", p.cacheKey},
            {"build_ms", p.buildMs}};
}

json programSection(const RenderStats& st) {
    return {
        {"build_options", st.program.options},    {"cache_hit", st.program.cacheHit},
        {"cache_key", st.program.cacheKey},       {"cache_file", st.program.cacheFile},
        {"build_ms", st.program.buildMs},         {"trace", programPart(st.traceProgram)},
        {"shading", programPart(st.shadeProgram)}};
}

// The scene, its tree and the ray pool over the frame
json sceneSection(const RenderStats& st) {
    json fillSeries = json::array();  // [seconds, fill] every 50 ms or so
    for (const PoolFillSample& p : st.poolFillSeries)
        fillSeries.push_back({p.seconds, p.fill});
    return {{"triangles", st.triangles},
            {"quadrics", st.quadrics},
            {"csg_solids", st.csgSolids},
            {"instances", st.instances},
            {"geometry_bytes", st.sceneBytes},
            {"bvh_nodes", st.bvhNodes},
            {"dropped_primitives", st.droppedPrims},
            {"bvh_build_ms", st.bvhBuildMs},
            {"diced_triangles", st.dicedTriangles},
            {"displaced_vertices", st.displacedVertices},
            {"displace_ms", st.displaceMs},
            {"setup_ms", st.sceneSetupMs},
            {"pool_capacity", st.poolCapacity},
            {"pool_bytes_per_ray", st.poolBytesPerRay},
            {"pool_fill", st.poolFill},
            {"pool_fill_series", fillSeries},
            {"rounds", st.iterations},
            {"spilled_rays", st.spilledRays},
            {"device_busy", st.deviceBusy},
            {"host_overhead", st.hostOverhead},
            {"host_sync_overhead", st.hostSyncOverhead},
            {"launch_gaps_ms", st.launchGapsMs},
            {"plan_ms", st.planMs}};
}

json numericsSection(const RenderStats& st) {
    return {{"shader_nonfinite", st.shadeNonfinite},
            {"shader_negative", st.shadeNegative},
            {"shader_huge", st.shadeHuge},
            {"shader_denormal", st.shadeDenormal},
            {"transparent_depth_cut", st.transparentDepthCut},
            {"specular_depth_cut", st.specularDepthCut},
            {"roulette_ended", st.rouletteEnded},
            {"trace_calls_ignored", st.traceCallsIgnored},
            {"shader_loops_cut", st.shaderLoopsCut},
            {"pool_overflow_rays", st.overflowRays}};
}

json samplingSection(const RenderStats& st) {
    return {{"passes", st.passes},
            {"overlapped_passes", st.overlappedPasses},
            {"retired_samples", st.retiredSamples},
            {"reissued_samples", st.reissuedSamples},
            {"stop_reason", st.stopReason},
            {"estimated_error", st.estimatedError},
            {"unsampled_pixels", st.unsampledPixels},
            {"aborted_samples", st.abortedSamples}};
}

json treeletSection(const TreeletStats& ts) {
    json rounds = json::array();
    for (const TreeletRoundStats& r : ts.byRound)
        rounds.push_back({{"pairs", r.pairs},
                          {"treelets_with_rays", r.treeletsWithRays},
                          {"uploads", r.uploads}});
    return {{"used", ts.used},
            {"streamed", ts.streamed},
            {"not_used_because", ts.why},
            {"budget_bytes", ts.budgetBytes},
            {"count", ts.treelets},
            {"bytes", ts.treeletBytes},
            {"cache_slots", ts.cacheSlots},
            {"slot_bytes", ts.slotBytes},
            {"traces", ts.traces},
            {"rounds", ts.rounds},
            {"pairs", ts.pairs},
            {"launches", ts.launches},
            {"uploads", ts.uploads},
            {"uploaded_bytes", ts.uploadedBytes},
            {"reruns", ts.reruns},
            {"by_round", rounds}};
}

// Each kernel that ran: its launches, device time and occupancy
json kernelSection(const RenderStats& st) {
    json kernels = json::object();
    for (const auto& [name, k] : st.kernels) {
        if (k.launches == 0) continue;
        kernels[name] = {{"launches", k.launches},
                         {"device_ms", k.deviceMs},
                         {"work_items_launched", k.launchedItems},
                         {"work_items_active", k.activeItems},
                         {"occupancy", k.occupancy()}};
    }
    return kernels;
}

json textureSection(const TextureStats& t) {
    return {{"files", t.textures},
            {"resident", t.resident},
            {"cache_tiles", t.cacheTiles},
            {"total_tiles", t.totalTiles},
            {"lookups", t.lookups},
            {"missed_lookups", t.missedLookups},
            {"tile_hit_rate", t.hitRate()},
            {"tiles_uploaded", t.tilesUploaded},
            {"bytes_uploaded", t.bytesUploaded},
            {"reshade_passes", t.retryPasses},
            {"unresolved_points", t.unresolved}};
}
}  // namespace

nlohmann::json statsToJson(const RenderStats& st, const std::string& scene,
                           const std::string& output) {
    json series = json::array();
    for (const ErrorSample& e : st.errorVsTime)
        series.push_back({e.seconds, e.rays, e.estimatedError});
    return json{
        {"scene", scene},
        {"output", output},
        {"elapsed_s", st.elapsedSec},
        {"device",
         {{"name", st.device},
          {"platform", st.platform},
          {"threads_pinned", st.threadsPinned}}},
        {"rays",
         {{"eye", st.eyeRays},
          {"continuation", st.continuationRays},
          {"shadow", st.shadowRays},
          {"total", st.eyeRays + st.continuationRays + st.shadowRays}}},
        {"scene_stats", sceneSection(st)},
        {"features", st.features.names()},
        {"program", programSection(st)},
        {"nonfinite_samples", st.nonfiniteSamples},
        {"numerics", numericsSection(st)},
        {"sampling", samplingSection(st)},
        {"treelets", treeletSection(st.treelets)},
        {"error_vs_time", series},
        {"kernels", kernelSection(st)},
        {"textures", textureSection(st.textures)},
    };
}

void printStatsTable(std::ostream& out, const nlohmann::json& s) {
    out << "scene     " << s["scene"].get<std::string>() << " -> "
        << s["output"].get<std::string>() << "\n";
    out << "device    " << s["device"]["name"].get<std::string>() << " ("
        << s["device"]["platform"].get<std::string>() << ")\n";
    out << std::fixed << std::setprecision(3);
    out << "elapsed   " << s["elapsed_s"].get<double>() << " s\n";
    out << "rays      eye " << s["rays"]["eye"] << ", continuation "
        << s["rays"]["continuation"] << ", shadow " << s["rays"]["shadow"] << "\n";
    out << "sampling  " << s["sampling"]["passes"] << " passes ("
        << s["sampling"]["overlapped_passes"] << " overlapped), stopped by "
        << s["sampling"]["stop_reason"].get<std::string>() << ", estimated error "
        << s["sampling"]["estimated_error"].get<double>() << "\n";
    out << "numerics  nonfinite samples " << s["nonfinite_samples"] << ", shader NaN/Inf "
        << s["numerics"]["shader_nonfinite"] << ", negative " << s["numerics"]["shader_negative"]
        << ", huge " << s["numerics"]["shader_huge"] << ", denormal "
        << s["numerics"]["shader_denormal"] << ", cut at maxtransparentdepth "
        << s["numerics"]["transparent_depth_cut"] << ", at maxspeculardepth "
        << s["numerics"]["specular_depth_cut"] << ", shader loops cut "
        << s["numerics"]["shader_loops_cut"] << "\n";
    const auto& ss = s["scene_stats"];
    out << "scene     " << ss["triangles"] << " triangles, " << ss["quadrics"] << " quadrics, "
        << ss["csg_solids"] << " CSG solids, " << ss["instances"] << " instances, "
        << ss["bvh_nodes"] << " BVH nodes, " << ss["geometry_bytes"] << " geometry bytes\n";
    if (ss["diced_triangles"].get<uint64_t>() > 0)
        out << "displaced " << ss["diced_triangles"] << " diced triangles, "
            << ss["displaced_vertices"] << " vertices moved in "
            << ss["displace_ms"].get<double>() << " ms\n";
    out << "pool      capacity " << ss["pool_capacity"] << " (" << ss["pool_bytes_per_ray"]
        << " bytes a ray), fill "
        << ss["pool_fill"].get<double>() << " over " << ss["rounds"]
        << " rounds, device busy " << ss["device_busy"].get<double>()
        << " of the sampling loop, host overhead " << ss["host_overhead"].get<double>()
        << " of the frame (host waits " << ss["host_sync_overhead"].get<double>()
        << ", launch gaps " << ss["launch_gaps_ms"].get<double>() << " ms)\n";
    if (const auto& t = s["textures"]; t["files"].get<uint64_t>() > 0)
        out << "textures  " << t["files"] << " files, "
            << (t["resident"].get<bool>() ? "resident" : "streamed") << ", cache "
            << t["cache_tiles"] << " of " << t["total_tiles"] << " tiles, " << t["lookups"]
            << " lookups, tile hit rate " << t["tile_hit_rate"].get<double>() << ", "
            << t["tiles_uploaded"] << " tiles (" << t["bytes_uploaded"] << " bytes) uploaded, "
            << t["reshade_passes"] << " reshade passes, " << t["unresolved_points"]
            << " unresolved\n";
    if (const auto& t = s["treelets"]; t["used"].get<bool>()) {
        out << "treelets  " << t["count"] << " of <= " << t["budget_bytes"] << " bytes ("
            << t["bytes"] << " in all), "
            << (t["streamed"].get<bool>() ? "streamed through " + t["cache_slots"].dump() +
                                                " cache slots"
                                          : std::string("resident"))
            << "; " << t["traces"] << " traces, " << t["rounds"] << " rounds, " << t["pairs"]
            << " pairs, " << t["uploads"] << " uploads (" << t["uploaded_bytes"]
            << " bytes), " << t["reruns"] << " reruns\n";
        out << "  round     pairs  treelets  uploads\n";
        size_t r = 0;
        for (const auto& x : t["by_round"])
            out << std::setw(7) << r++ << std::setw(10) << x["pairs"].get<uint64_t>()
                << std::setw(10) << x["treelets_with_rays"].get<uint64_t>() << std::setw(9)
                << x["uploads"].get<uint64_t>() << "\n";
    } else if (!t["not_used_because"].get<std::string>().empty()) {
        out << "treelets  not used: " << t["not_used_because"].get<std::string>() << "\n";
    }
    out << "features ";
    for (const auto& f : s["features"]) out << " " << f.get<std::string>();
    auto built = [&](const nlohmann::json& p) {
        return (p["cache_hit"].get<bool>() ? "cache hit" : "built") + std::string(" in ") +
               std::to_string(int(p["build_ms"].get<double>() + 0.5)) + " ms";
    };
    out << "\nprogram   trace " << built(s["program"]["trace"]) << ", shading "
        << built(s["program"]["shading"]) << ", options: "
        << s["program"]["build_options"].get<std::string>() << "\n";
    out << std::left << std::setw(20) << "kernel" << std::right << std::setw(9) << "launches"
        << std::setw(12) << "device ms" << std::setw(14) << "launched" << std::setw(14)
        << "active" << std::setw(11) << "occupancy\n";
    for (const auto& [name, k] : s["kernels"].items()) {
        out << std::left << std::setw(20) << name << std::right << std::setw(9)
            << k["launches"].get<uint64_t>() << std::setw(12) << k["device_ms"].get<double>()
            << std::setw(14) << k["work_items_launched"].get<uint64_t>() << std::setw(14)
            << k["work_items_active"].get<uint64_t>() << std::setw(10)
            << k["occupancy"].get<double>() << "\n";
    }
}

}  // namespace rd
