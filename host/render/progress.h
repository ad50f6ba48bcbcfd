// progress.h: the progress line on stderr for a person: a bar, elapsed time, ETA, rays/s
// and the current error estimate. Silent when stderr is not a terminal or with -q.
#pragma once
#include <cstdint>

namespace rd {

class Progress {
public:
    explicit Progress(bool enabled);
    // fraction in [0, 1] (best guess), error < 0 when not yet known.
    void update(double fraction, double elapsedSec, uint64_t rays, double error);
    void finish();

private:
    bool m_enabled;
    double m_lastPrint = -1;
    bool m_printed = false;
};

}  // namespace rd
