// stop.cpp: the signal flag behind fail-soft stops.
#include "stop.h"

#include <csignal>

namespace rd {
namespace {

volatile std::sig_atomic_t g_stopSignal = 0;

extern "C" void onStopSignal(int sig) {
    if (g_stopSignal == sig) {
        // Asked twice: the user wants out now.
        std::signal(sig, SIG_DFL);
        std::raise(sig);
        return;
    }
    g_stopSignal = sig;
}

}  // namespace

void installStopSignals() {
    std::signal(SIGINT, onStopSignal);
    std::signal(SIGTERM, onStopSignal);
}
int stopSignal() { return g_stopSignal; }
void requestStop(int signal) { g_stopSignal = signal; }
void clearStop() { g_stopSignal = 0; }

}  // namespace rd
