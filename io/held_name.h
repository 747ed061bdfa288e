#pragma once
// A name a process holds on this machine while it lives: an abstract Unix socket address, which
// the kernel releases however the process ends, and which makes no file. Two processes never hold
// one name; any process can see which names are held (/proc/net/unix lists them). For marks such
// as "this shard of this dataset is being rendered" that a lock on a file cannot carry (the
// shard's files are replaced while it runs).
#include <optional>
#include <set>
#include <string>

#include "file_descriptor.h"

namespace omnicam {

class HeldName {
 public:
  // `name` held by this process, or nullopt when another process on this machine holds it.
  // Names are at most 100 bytes of printable ASCII without spaces. Where the system gives no
  // socket (a sandbox), nothing is held and nothing refused: a HeldName that holds nothing.
  static std::optional<HeldName> tryHold(const std::string& name);
  bool holds() const { return socket_.get() >= 0; }

 private:
  explicit HeldName(FileDescriptor socket) : socket_(std::move(socket)) {}
  FileDescriptor socket_;
};

// The names processes on this machine (in this network namespace) hold now that start with
// `prefix`: one read of the kernel's table, however many names are asked about.
std::set<std::string> heldNames(const std::string& prefix);

}  // namespace omnicam
