// run_program.h: the RunProgram procedural's helper process (RI 3.2 section 5.7): the
// program gets "detail datablock" on its standard input and answers with RIB ended by a
// 0377 byte. It runs under a time limit and an output limit, so a program that hangs or
// never stops writing ends in an error rather than a hung or exhausted reader.
#pragma once
#include <cstddef>
#include <string>

namespace rib {

struct RunProgramLimits {
    double seconds = 60;                // from the start to the 0377 byte
    size_t maxBytes = size_t(1) << 30;  // its answer
};

// Runs `command` (through /bin/sh, as the RIB names it with its arguments), sends it
// `request` and a newline, and returns its answer up to the 0377 byte in *rib. False,
// with *why saying what went wrong (could not start, exit status, no answer in time, too
// much output), when there is no such answer; the program is stopped either way.
bool runProgram(const std::string& command, const std::string& request,
                const RunProgramLimits& limits, std::string* rib, std::string* why);

// DynamicLoad procedurals (RI 3.2 section 5.7): a loader runs the shared object's
// ConvertParameters, Subdivide (at `detail`) and Free, and gives back in *rib the RIB of
// the Ri calls it made, which the reader then reads in place, as RunProgram's answer.
// The Ri library sets it (host/ri/ri_dynamic_load.h); with none set, DynamicLoad is a
// warning and skipped.
using DynamicLoader = bool (*)(const std::string& dso, const std::string& data,
                               float detail, std::string* rib, std::string* why);
void setDynamicLoader(DynamicLoader loader);
DynamicLoader dynamicLoader();

}  // namespace rib
