// run_in_parts.h: host work over [0, n) split into contiguous parts on the host's cores,
// the parts' results joined in order, so that a result does not depend on the number of
// threads (the sample planner's visits, the film's error estimate); and a list of tasks
// of uneven sizes taken in turn by the threads (the BVH's subtrees).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
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

// Runs f(task, thread) for every task in [0, n) on up to `threads` threads, the calling
// one among them (thread 0), each taking the next task in turn. A failure in any task
// (running out of memory, say) is rethrown here once all have ended: the first task's.
template <class F>
void runTasks(size_t n, size_t threads, F&& f) {
    std::atomic<size_t> next{0};
    std::vector<std::exception_ptr> failed(n);
    auto work = [&](size_t thread) {
        for (size_t i; (i = next++) < n;) {
            try {
                f(i, thread);
            } catch (...) {
                failed[i] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < std::min(threads, n); ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& th : pool) th.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
}

}  // namespace rd
