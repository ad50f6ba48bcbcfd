// timeline_trace.h: raydrive --timeline: each frame's kernel runs and the device's idle
// time between them (RenderStats::timeline) in the Chrome trace event format, to open in
// ui.perfetto.dev or chrome://tracing: a process per frame, a track for the kernels and
// one for the idle gaps, named by whose they are (a host wait or the runtime's launch gap).
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ocl/kernel.h"

namespace rd {

// The trace events of one frame's timeline (microseconds, as the format has them) as
// process `pid`, labelled `label`.
std::vector<nlohmann::json> timelineTraceEvents(const std::vector<TimelineEvent>& timeline,
                                                int pid, const std::string& label);

}  // namespace rd
