// A folder handle (SafeFolder) is opened once: every path inside is walked from its descriptor,
// so a folder renamed, or a link planted where its path was, after it was opened does not
// change where a handle reads and writes; the path-based functions look again each call.
#include "safe_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "errors.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

class SafeFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_safe_folder_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string text(const fs::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  fs::path dir_;
};

TEST_F(SafeFolderTest, AHandleKeepsItsFolderWhenThePathIsRenamedOrReplacedByALink) {
  const fs::path original = dir_ / "dataset", moved = dir_ / "moved", elsewhere = dir_ / "elsewhere";
  const SafeFolder folder(original.string(), true);  // made, then held
  ASSERT_TRUE(fs::is_directory(original));
  folder.makeFolders("cam0/rgb");
  folder.writeFile("cam0/rgb/000000.png", "first", Durability::Unsynced);
  // The folder goes away under its name, and a link to another folder takes the name.
  fs::rename(original, moved);
  fs::create_directories(elsewhere);
  fs::create_directory_symlink(elsewhere, original);
  folder.writeFile("cam0/rgb/000001.png", "second", Durability::Unsynced);
  EXPECT_EQ(folder.readFile("cam0/rgb/000000.png", 100), "first");
  EXPECT_EQ(folder.entry("cam0/rgb/000001.png"), EntryKind::File);
  EXPECT_EQ(text(moved / "cam0/rgb/000001.png"), "second");  // written where the handle points
  EXPECT_TRUE(fs::is_empty(elsewhere));                       // never through the planted link
  // The path-based functions look again: the name now leads into the link's target.
  EXPECT_EQ(entryInside(original.string(), "cam0/rgb/000001.png"), EntryKind::Missing);
}

// A file written piece by piece: its pieces in order, atomically; a source that fails midway
// leaves neither the file nor its temporary.
TEST_F(SafeFolderTest, AStreamedFileIsItsPiecesOrNothing) {
  const SafeFolder folder(dir_.string());
  const std::vector<std::string> pieces = {"kalibr", ".bag ", std::string(3000, 'x'), "end"};
  size_t next = 0;
  folder.writeFileFrom("sub/streamed.bin", [&](std::string_view& piece) {
    if (next == pieces.size()) return false;
    piece = pieces[next++];
    return true;
  }, Durability::Synced);
  EXPECT_EQ(text(dir_ / "sub/streamed.bin"), "kalibr.bag " + std::string(3000, 'x') + "end");
  int calls = 0;
  EXPECT_THROW(folder.writeFileFrom("failed.bin", [&](std::string_view& piece) {
    if (++calls == 2) throw OutputError("the source failed");
    piece = "first";
    return true;
  }, Durability::Unsynced), OutputError);
  EXPECT_FALSE(fs::exists(dir_ / "failed.bin"));
  size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1u) << "only sub/: no temporary left";
}

TEST_F(SafeFolderTest, AMissingFolderIsLookedForAgainAndOnlyMadeWhenAsked) {
  const fs::path later = dir_ / "later";
  const SafeFolder looking(later.string());
  EXPECT_FALSE(fs::exists(later));  // not made by a handle that only reads
  EXPECT_EQ(looking.entry("manifest.json"), EntryKind::Missing);
  EXPECT_THROW(looking.readFile("manifest.json", 100), InputError);
  fs::create_directories(later);
  std::ofstream(later / "manifest.json") << "{}";
  EXPECT_EQ(looking.readFile("manifest.json", 100), "{}");
  // Inside a handle, links are never followed.
  fs::create_symlink(later / "manifest.json", later / "link.json");
  EXPECT_EQ(looking.entry("link.json"), EntryKind::Link);
  EXPECT_THROW(looking.readFile("link.json", 100), InputError);
}

}  // namespace
}  // namespace omnicam
