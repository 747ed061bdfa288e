#pragma once
// The flags of the benchmarks that are programs of their own (not Google Benchmark's): each
// `--name VALUE` or `--name=VALUE`, once, or `--help`. An unknown flag, one without its value or
// given twice, a stray argument or a value that is not the integer it must be prints the usage
// and exits 2 (--help: 0), before any work: a typo never starts a long run.
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace omnicam::bench {

class BenchFlags {
 public:
  BenchFlags(int argc, char** argv, const std::vector<std::string>& flags, const char* usage, size_t maxPositional = 0)
      : program_(argv[0]), usage_(usage) {
    for (int k = 1; k < argc; ++k) {
      std::string arg = argv[k];
      if (arg == "--help" || arg == "-h") exitWithUsage(0, "");
      if (arg.rfind("-", 0) != 0) {
        if (positional_.size() == maxPositional) exitWithUsage(2, "unexpected argument " + arg);
        positional_.push_back(arg);
        continue;
      }
      std::string value;
      const size_t equals = arg.find('=');
      const bool inline_value = equals != std::string::npos;
      if (inline_value) value = arg.substr(equals + 1), arg.erase(equals);
      bool known = false;
      for (const std::string& flag : flags) known = known || flag == arg;
      if (!known) exitWithUsage(2, "unknown option " + arg);
      if (values_.count(arg)) exitWithUsage(2, arg + " given twice");
      if (!inline_value) {
        if (k + 1 == argc) exitWithUsage(2, arg + " needs a value");
        value = argv[++k];
      }
      values_[arg] = value;
    }
  }
  const std::vector<std::string>& positional() const { return positional_; }
  std::string text(const std::string& flag, const std::string& otherwise) const {
    const auto found = values_.find(flag);
    return found == values_.end() ? otherwise : found->second;
  }
  // The flag's integer in [lo, hi], or `otherwise` when it was not given.
  int integer(const std::string& flag, int otherwise, int lo, int hi) const {
    const auto found = values_.find(flag);
    if (found == values_.end()) return otherwise;
    const std::string& s = found->second;
    int value = 0;
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (error != std::errc() || end != s.data() + s.size() || value < lo || value > hi)
      exitWithUsage(2, flag + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + s + ")");
    return value;
  }

 private:
  [[noreturn]] void exitWithUsage(int code, const std::string& problem) const {
    if (!problem.empty()) std::fprintf(stderr, "%s: %s\n", program_.c_str(), problem.c_str());
    std::fprintf(code == 0 ? stdout : stderr, "usage: %s\n", usage_);
    std::exit(code);
  }

  std::string program_;
  const char* usage_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
};

}  // namespace omnicam::bench
