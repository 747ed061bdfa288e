#pragma once
#include <memory>
#include <string>
#include <string_view>

namespace omnicam {

// SHA-256 fed piece by piece, so that a file of any size is hashed in constant memory.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(std::string_view bytes);
  // Lower-case hex digest of everything fed; the object is spent afterwards.
  std::string hex();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

// Lower-case hex SHA-256 of a file's bytes; throws InputError if it cannot be read.
std::string sha256OfFile(const std::string& path);
std::string sha256OfBytes(std::string_view bytes);
}  // namespace omnicam
