// timeline_trace.cpp: the --timeline trace (timeline_trace.h).
#include "timeline_trace.h"

namespace rd {

namespace {
constexpr int kKernelTrack = 1, kIdleTrack = 2;

nlohmann::json named(const char* what, int pid, int tid, const std::string& name) {
    return {{"name", what}, {"ph", "M"}, {"pid", pid}, {"tid", tid}, {"args", {{"name", name}}}};
}
}  // namespace

std::vector<nlohmann::json> timelineTraceEvents(const std::vector<TimelineEvent>& timeline,
                                                int pid, const std::string& label) {
    std::vector<nlohmann::json> out = {named("process_name", pid, 0, label),
                                       named("thread_name", pid, kKernelTrack, "kernels"),
                                       named("thread_name", pid, kIdleTrack, "device idle")};
    for (const TimelineEvent& e : timeline) {
        if (e.idleBeforeUs > 0)
            out.push_back({{"name", e.afterWait ? "host wait" : "launch gap"},
                           {"cat", "idle"},
                           {"ph", "X"},
                           {"ts", e.startUs - e.idleBeforeUs},
                           {"dur", e.idleBeforeUs},
                           {"pid", pid},
                           {"tid", kIdleTrack}});
        out.push_back({{"name", e.kernel},
                       {"cat", "kernel"},
                       {"ph", "X"},
                       {"ts", e.startUs},
                       {"dur", e.durationUs},
                       {"pid", pid},
                       {"tid", kKernelTrack},
                       {"args", {{"work_items", e.launchedItems}}}});
    }
    return out;
}

}  // namespace rd
