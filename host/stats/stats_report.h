// stats_report.h: --stats output. The same figures as JSON (a file) or as a table for a
// person (`--stats -`): elapsed time, rays by kind, features and build options, program
// cache, and per kernel: launches, device ms, launched and active work-items, occupancy.
#pragma once
#include <iosfwd>
#include <string>

#include <nlohmann/json.hpp>

#include "render/renderer.h"

namespace rd {

nlohmann::json statsToJson(const RenderStats& st, const std::string& scene,
                           const std::string& output);
void printStatsTable(std::ostream& out, const nlohmann::json& stats);

}  // namespace rd
