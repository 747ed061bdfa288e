#pragma once
// Memory the input asks for, sized before it is allocated (docs/robustness.md, "Memory").
//
// Work whose size the input controls (a ray table, two frames to compare, a frame file's pixels)
// states what it needs first. What the documented limits forbid is bad input (InputError, exit
// 2); what they allow but this machine cannot give — less free memory, or a smaller address
// space (ulimit -v), than the work needs — is a MemoryShortage (exit 5), said before anything is
// allocated or written, never an out-of-memory abort halfway.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace omnicam {

// The machine, not the input, lacks what the work needs. The CLI exits 5 (like OutputError).
class MemoryShortage : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct MemoryAvailable {
  int64_t bytes = 0;      // what this process can still allocate
  std::string limitedBy;  // "the address-space limit (ulimit -v)" or "the machine's available memory"
};

// The smaller of the address space left under RLIMIT_AS and the kernel's MemAvailable (plus free
// swap); an estimate read from /proc, good to a few percent.
MemoryAvailable availableMemory();

// Throws MemoryShortage("<what> needs N GiB of memory; M GiB are available (limited by …)") when
// `bytes` exceed what is available, leaving a margin for the process's own working memory.
void requireMemory(int64_t bytes, const std::string& what);

// How many of `tasks` that each need `bytesEach` may run at once, at most `wanted`, at least 1;
// MemoryShortage if even one does not fit.
int concurrencyWithin(int64_t bytesEach, int wanted, const std::string& what);

// "1.5 GiB", "640 MiB": sizes in messages.
std::string byteSizeText(int64_t bytes);

}  // namespace omnicam
