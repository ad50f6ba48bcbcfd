// progress.cpp: the progress bar.
#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace rd {

Progress::Progress(bool enabled) : m_enabled(enabled && ::isatty(STDERR_FILENO)) {}

void Progress::update(double fraction, double elapsed, uint64_t rays, double error) {
    if (!m_enabled || elapsed - m_lastPrint < 0.2) return;
    m_lastPrint = elapsed;
    fraction = std::clamp(fraction, 0.0, 1.0);
    const int width = 30;
    int filled = int(fraction * width + 0.5);
    char bar[width + 1];
    for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '.';
    bar[width] = '\0';
    double eta = fraction > 0.01 ? elapsed * (1.0 - fraction) / fraction : -1.0;
    char err[32] = "err ?";
    if (error >= 0) std::snprintf(err, sizeof err, "err %.2f%%", error * 100.0);
    char etaText[32] = "ETA ?";
    if (eta >= 0) std::snprintf(etaText, sizeof etaText, "ETA %.1fs", eta);
    std::fprintf(stderr, "\r[%s] %3.0f%% %.1fs %s %.2f Mrays/s %s   ", bar, fraction * 100.0,
                 elapsed, etaText, elapsed > 0 ? double(rays) / elapsed * 1e-6 : 0.0, err);
    std::fflush(stderr);
    m_printed = true;
}

void Progress::finish() {
    if (m_printed) std::fprintf(stderr, "\n");
    m_printed = false;
}

}  // namespace rd
