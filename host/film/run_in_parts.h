// run_in_parts.h: host work over [0, n) split into contiguous parts on the host's cores,
// the parts' results joined in order, so that a result does not depend on the number of
// threads (the sample planner's visits, the film's error estimate).
#pragma once
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace rd {

// The threads a large host pass uses: the host's cores, at most 8.
inline size_t hostThreads() {
    return std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 8);
}

// Runs f(begin, end, part) over [0, n) cut into `parts` contiguous parts, the first on the
// calling thread.
template <class F>
void runInParts(size_t n, size_t parts, F&& f) {
    std::vector<std::thread> pool;
    for (size_t t = 1; t < parts; ++t)
        pool.emplace_back([&f, n, parts, t] { f(n * t / parts, n * (t + 1) / parts, t); });
    f(0, n / parts, 0);
    for (std::thread& th : pool) th.join();
}

}  // namespace rd
