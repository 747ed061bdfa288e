#pragma once
// SIGTERM and SIGINT while omnicam waits on a program of its own (POV-Ray, Blender, a demo
// section): the handler only records the signal; the waiting loop ends that program's whole
// process group and throws Interrupted, so job folders and temporaries are removed on the way
// out and nothing is orphaned. Outside such a region the signal has its usual effect at once —
// unless the verb stops gracefully (a dataset finishes its frame and writes its manifest).
#include <atomic>
#include <stdexcept>
#include <string>

namespace omnicam {

// Thrown where an interrupt was noticed; `signal` is SIGTERM or SIGINT.
class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal, const std::string& what) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

// The CLI installs the handler once, at start, and adopts orphaned descendants (a child
// subreaper). Without it (Python, tests) nothing is recorded.
void installInterruptHandlers();
// The verb polls interruptRequested() itself between units of work: a signal outside a region
// no longer ends the process (the dataset verb's resumable stop).
void stopGracefullyOnInterrupt();

// The signal received (0 if none), and the same as a flag for loops that take one.
int pendingInterrupt();
const std::atomic<bool>& interruptRequested();
// Throws Interrupted naming `what` (e.g. "povray") if a signal was received.
void throwIfInterrupted(const std::string& what);
// "SIGTERM", "SIGINT" or "signal N".
std::string signalName(int signal);
// Ends the process by `signal` with its default action (the exit status shells expect, 128 + N).
[[noreturn]] void dieBySignal(int signal);

// While one exists, SIGTERM and SIGINT are only recorded: the owner of an external process
// (runProcess) or of a job folder must see them and clean up. When the last one goes with a
// signal pending that nobody acted on, the process dies by it then.
class DeferInterrupts {
 public:
  DeferInterrupts();
  ~DeferInterrupts();
  DeferInterrupts(const DeferInterrupts&) = delete;
  DeferInterrupts& operator=(const DeferInterrupts&) = delete;
};

}  // namespace omnicam
