#include "held_name.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <set>
#include <string>

namespace omnicam {
namespace {

std::string uniqueName(const char* what) { return std::string("omnicam-test/") + what + "/" + std::to_string(::getpid()); }

bool nameHeld(const std::string& name) { return heldNames(name).count(name) > 0; }

// A child process killed and reaped however the test ends.
struct Child {
  pid_t pid = -1;
  ~Child() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

TEST(HeldName, OneHolderAtATimeAndSeenByAll) {
  const std::string name = uniqueName("one");
  EXPECT_FALSE(nameHeld(name));
  {
    const std::optional<HeldName> held = HeldName::tryHold(name);
    ASSERT_TRUE(held);
    EXPECT_TRUE(nameHeld(name));
    EXPECT_FALSE(HeldName::tryHold(name));  // the kernel refuses the address twice
    EXPECT_FALSE(nameHeld(name + "x"));     // whole names only
    EXPECT_EQ(heldNames("omnicam-test/one/"), std::set<std::string>{name});  // by prefix
  }
  EXPECT_FALSE(nameHeld(name));
  EXPECT_TRUE(HeldName::tryHold(name));
}

// A process that ends without letting go (killed) leaves the name free: nothing to clean up.
TEST(HeldName, ReleasedWhenTheHolderDiesHoweverItDies) {
  const std::string name = uniqueName("killed");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  Child child;
  child.pid = ::fork();
  ASSERT_GE(child.pid, 0);
  if (child.pid == 0) {
    const std::optional<HeldName> held = HeldName::tryHold(name);
    const char said = held ? 'y' : 'n';
    if (::write(ready[1], &said, 1) != 1) ::_exit(1);
    for (;;) ::pause();  // held until killed
  }
  char said = 0;
  ASSERT_EQ(::read(ready[0], &said, 1), 1);  // synchronised on what the child wrote
  EXPECT_EQ(said, 'y');
  EXPECT_TRUE(nameHeld(name));
  EXPECT_FALSE(HeldName::tryHold(name));
  ::kill(child.pid, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(child.pid, &status, 0), child.pid);
  child.pid = -1;
  EXPECT_FALSE(nameHeld(name));
  EXPECT_TRUE(HeldName::tryHold(name));
  ::close(ready[0]);
  ::close(ready[1]);
}

TEST(HeldName, RefusesNamesItCannotList) {
  EXPECT_THROW(HeldName::tryHold(""), std::logic_error);
  EXPECT_THROW(HeldName::tryHold("with space"), std::logic_error);
  EXPECT_THROW(HeldName::tryHold(std::string(101, 'a')), std::logic_error);
}

}  // namespace
}  // namespace omnicam
