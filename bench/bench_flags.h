#pragma once
// The flags of the benchmarks that are programs of their own (not Google Benchmark's): each
// `--name VALUE`, or `--help`. An unknown flag, one without its value, or a stray argument prints
// the usage and exits 2 (--help: 0), before any work: a typo never starts a long run.
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace omnicam::bench {

// The values given, by flag name; `positional` (at most `maxPositional`) the other arguments.
struct BenchFlags {
  std::map<std::string, std::string> values;
  std::vector<std::string> positional;
  std::string value(const std::string& flag, const std::string& otherwise) const {
    const auto found = values.find(flag);
    return found == values.end() ? otherwise : found->second;
  }
};

inline BenchFlags readBenchFlags(int argc, char** argv, const std::vector<std::string>& flags, const char* usage,
                                 size_t maxPositional = 0) {
  const auto exitWithUsage = [&](int code, const std::string& problem) {
    if (!problem.empty()) std::fprintf(stderr, "%s: %s\n", argv[0], problem.c_str());
    std::fprintf(code == 0 ? stdout : stderr, "usage: %s\n", usage);
    std::exit(code);
  };
  BenchFlags read;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--help" || arg == "-h") exitWithUsage(0, "");
    if (arg.rfind("-", 0) != 0) {
      if (read.positional.size() == maxPositional) exitWithUsage(2, "unexpected argument " + arg);
      read.positional.push_back(arg);
      continue;
    }
    bool known = false;
    for (const std::string& flag : flags) known = known || flag == arg;
    if (!known) exitWithUsage(2, "unknown option " + arg);
    if (k + 1 == argc) exitWithUsage(2, arg + " needs a value");
    read.values[arg] = argv[++k];
  }
  return read;
}

}  // namespace omnicam::bench
