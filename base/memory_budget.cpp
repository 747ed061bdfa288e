#include "memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace omnicam {

namespace {

// Room kept for everything the estimate leaves out: the process's stacks, the allocator's
// slack, libraries' scratch.
constexpr int64_t kMarginBytes = int64_t{256} << 20;

// The address space this process maps now (VmSize), bytes.
int64_t mappedBytes() {
  std::ifstream statm("/proc/self/statm");
  int64_t pages = 0;
  if (!(statm >> pages)) return 0;
  return pages * static_cast<int64_t>(sysconf(_SC_PAGESIZE));
}

// MemAvailable + SwapFree from /proc/meminfo, bytes; nullopt-like -1 when unreadable.
int64_t machineAvailableBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  int64_t available = -1, swapFree = 0;
  while (std::getline(meminfo, line)) {
    std::istringstream fields(line);
    std::string key;
    int64_t kib = 0;
    fields >> key >> kib;
    if (key == "MemAvailable:") available = kib * 1024;
    if (key == "SwapFree:") swapFree = kib * 1024;
  }
  return available < 0 ? -1 : available + swapFree;
}

}  // namespace

MemoryAvailable availableMemory() {
  MemoryAvailable out{std::numeric_limits<int64_t>::max(), "nothing"};
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const int64_t cap = static_cast<int64_t>(std::min<rlim_t>(limit.rlim_cur, std::numeric_limits<int64_t>::max()));
    out = {std::max<int64_t>(0, cap - mappedBytes()), "the address-space limit (ulimit -v)"};
  }
  const int64_t machine = machineAvailableBytes();
  if (machine >= 0 && machine < out.bytes) out = {machine, "the machine's available memory and swap"};
  return out;
}

std::string byteSizeText(int64_t bytes) {
  char text[48];
  const double b = static_cast<double>(bytes);
  if (b >= 1024.0 * 1024 * 1024) std::snprintf(text, sizeof text, "%.1f GiB", b / (1024.0 * 1024 * 1024));
  else std::snprintf(text, sizeof text, "%.0f MiB", std::max(1.0, b / (1024.0 * 1024)));
  return text;
}

namespace {

void requireWithin(int64_t bytes, const MemoryAvailable& available, const std::string& what) {
  if (bytes + kMarginBytes > available.bytes)
    throw MemoryShortage(what + " needs " + byteSizeText(bytes) + " of memory, and the program " + byteSizeText(kMarginBytes) +
                         " more; " + byteSizeText(available.bytes) + " are available (limited by " + available.limitedBy + ")");
}

}  // namespace

void requireMemory(int64_t bytes, const std::string& what) { requireWithin(bytes, availableMemory(), what); }

int concurrencyWithin(int64_t bytesEach, int wanted, const std::string& what) {
  const MemoryAvailable available = availableMemory();
  requireWithin(bytesEach, available, what);
  const int64_t fit = (available.bytes - kMarginBytes) / std::max<int64_t>(1, bytesEach);
  return static_cast<int>(std::clamp<int64_t>(fit, 1, std::max(1, wanted)));
}

}  // namespace omnicam
