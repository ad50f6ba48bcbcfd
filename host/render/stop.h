// stop.h: why a render ends early. SIGINT and SIGTERM only set a flag (async-signal-safe);
// the render loop polls it between kernel launches, drops the samples still in flight and
// writes the image of the samples retired so far (fail-soft, as BRL-CAD's incremental mode).
#pragma once

namespace rd {

// Installs the SIGINT/SIGTERM handlers; a second signal of the same kind kills at once.
void installStopSignals();
// 0 when no stop was asked for, else the signal number.
int stopSignal();
// For tests: ask for a stop as a signal would, or clear it.
void requestStop(int signal);
void clearStop();

}  // namespace rd
