#include "held_name.h"

#include <sys/socket.h>
#include <sys/un.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace omnicam {

namespace {

void checkName(const std::string& name) {
  const bool printable = std::all_of(name.begin(), name.end(), [](char c) { return c > ' ' && c < 0x7F; });
  if (name.empty() || name.size() > 100 || !printable) throw std::logic_error("held name: not 1 to 100 printable bytes: " + name);
}

}  // namespace

std::optional<HeldName> HeldName::tryHold(const std::string& name) {
  checkName(name);
  // A stream socket never listening: bound, it takes the name, and nobody can send it anything.
  FileDescriptor socket(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (socket.get() < 0) return HeldName(FileDescriptor());
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  // sun_path[0] stays 0: the abstract namespace, whose names are the bytes after it.
  std::memcpy(address.sun_path + 1, name.data(), name.size());
  const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + name.size());
  if (::bind(socket.get(), reinterpret_cast<const sockaddr*>(&address), length) == 0) return HeldName(std::move(socket));
  if (errno == EADDRINUSE) return std::nullopt;
  return HeldName(FileDescriptor());  // the system lends no name: hold none, refuse nothing
}

std::set<std::string> heldNames(const std::string& prefix) {
  // Each line: Num RefCount Protocol Flags Type St Inode [Path]; an abstract name's path is "@name".
  std::set<std::string> names;
  std::ifstream table("/proc/net/unix");
  const std::string wanted = "@" + prefix;
  for (std::string line; std::getline(table, line);) {
    std::istringstream fields(line);
    std::string field, last;
    while (fields >> field) last = field;
    if (last.compare(0, wanted.size(), wanted) == 0) names.insert(last.substr(1));
  }
  return names;
}

}  // namespace omnicam
