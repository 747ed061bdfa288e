#include "interrupts.h"

#include <signal.h>
#include <sys/prctl.h>
#include <string.h>
#include <unistd.h>

#include <exception>

namespace omnicam {

namespace {

std::atomic<int> receivedSignal{0};
std::atomic<bool> receivedFlag{false};
std::atomic<int> deferringRegions{0};
std::atomic<bool> graceful{false};
std::atomic<bool> installed{false};

// Async-signal-safe only: atomics, signal and raise.
extern "C" void onInterruptSignal(int signal) {
  int expected = 0;
  receivedSignal.compare_exchange_strong(expected, signal);
  receivedFlag.store(true);
  if (deferringRegions.load() == 0 && !graceful.load()) {
    ::signal(signal, SIG_DFL);
    ::raise(signal);
  }
}

}  // namespace

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onInterruptSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGTERM, &action, nullptr);
  ::sigaction(SIGINT, &action, nullptr);
  // What an ended program leaves behind (its renderer's own children) is adopted by omnicam rather
  // than by init, so that omnicam can wait until the last of a process group is gone
  // (external_process.cpp).
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  installed.store(true);
}

void stopGracefullyOnInterrupt() { graceful.store(true); }

int pendingInterrupt() { return receivedSignal.load(); }

const std::atomic<bool>& interruptRequested() { return receivedFlag; }

std::string signalName(int signal) {
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == SIGINT) return "SIGINT";
  return "signal " + std::to_string(signal);
}

void throwIfInterrupted(const std::string& what) {
  if (const int signal = pendingInterrupt())
    throw Interrupted(signal, "interrupted by " + signalName(signal) + " (" + what + " ended)");
}

void dieBySignal(int signal) {
  ::signal(signal, SIG_DFL);
  sigset_t unblock;
  sigemptyset(&unblock);
  sigaddset(&unblock, signal);
  ::pthread_sigmask(SIG_UNBLOCK, &unblock, nullptr);
  ::raise(signal);
  ::_exit(128 + signal);  // not reached: the default action of SIGTERM and SIGINT ends the process
}

DeferInterrupts::DeferInterrupts() { ++deferringRegions; }

DeferInterrupts::~DeferInterrupts() {
  // While an exception unwinds (Interrupted on its way to main), main reports and dies instead.
  if (--deferringRegions == 0 && installed.load() && !graceful.load() && std::uncaught_exceptions() == 0)
    if (const int signal = pendingInterrupt()) dieBySignal(signal);
}

}  // namespace omnicam
