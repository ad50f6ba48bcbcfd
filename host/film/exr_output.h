// exr_output.h: writes the resolved film as an OpenEXR file (RGB or RGBA, half or float).
// The file is written under a temporary name and renamed into place, so an interrupted
// or failed write never leaves a file that looks complete.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "film.h"

namespace rd {

struct ExrOptions {
    bool colour = true;      // false: only the extra channels (a depth map: "Z")
    bool alpha = true;       // "rgba" vs "rgb"
    bool halfFloat = false;  // 16-bit half instead of 32-bit float channels
    std::map<std::string, std::string> metadata;  // string attributes in the header
    // 4x4 matrix attributes, row-major in the row-vector convention (p' = p M), e.g. a
    // depth map's "worldToCamera" and "worldToScreen"
    std::map<std::string, std::array<float, 16>> matrices;
    std::vector<Channel> extra;  // AOV channels (always 32-bit float), width*height each
    // A crop window: the pixels given are the data window at (dataX, dataY) of a frame of
    // displayWidth x displayHeight (0: the data is the whole frame).
    int dataX = 0, dataY = 0, displayWidth = 0, displayHeight = 0;
};

// Throws std::runtime_error with the file name and the reason on failure.
void writeExr(const std::string& path, int width, int height, const std::vector<Rgba>& pixels,
              const ExrOptions& options);

// Reads an RGBA EXR back (for tests and tools); missing channels read as 0 (alpha 1).
std::vector<Rgba> readExr(const std::string& path, int& width, int& height);

}  // namespace rd
