// teapot.h: the control points of Geometry "teapot" (Newell's teapot as bicubic Bezier
// patches, teapot.cpp).
#pragma once
#include <vector>

namespace rd {

constexpr int kTeapotPatches = 32;

// Patch `patch` (0 .. kTeapotPatches - 1): 16 points, 48 floats, u fastest, for Patch
// "bicubic" under the Bezier basis.
std::vector<float> teapotPatch(int patch);

}  // namespace rd
