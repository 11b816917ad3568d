#include "core/errors.h"
#include "core/io/file_access.h"
#include "core/io/file_format.h"
#include "core/io/json_document.h"
#include "test_support.h"

#include <atomic>
#include <csignal>
#include <fstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace scanstation::io {
namespace {

using test::expect_error;
using test::ScratchFolder;

std::size_t entries(const std::filesystem::path& folder) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(folder), {}));
}

TEST(AtomicWrite, WritesNewFileAndLeavesNoTemporary) {
  ScratchFolder dir;
  write_file_atomically(dir / "a.txt", "hello", Overwrite::refuse);
  EXPECT_EQ(read_file(dir / "a.txt"), "hello");
  EXPECT_EQ(entries(dir.path()), 1u);
}

TEST(AtomicWrite, RefusesToReplaceUnlessAsked) {
  ScratchFolder dir;
  write_file_atomically(dir / "a.txt", "first", Overwrite::refuse);
  expect_error<InvalidInput>([&] { write_file_atomically(dir / "a.txt", "second", Overwrite::refuse); },
                             {"a.txt", "exists", "--force"});
  EXPECT_EQ(read_file(dir / "a.txt"), "first");
  write_file_atomically(dir / "a.txt", "second", Overwrite::replace);
  EXPECT_EQ(read_file(dir / "a.txt"), "second");
  EXPECT_EQ(entries(dir.path()), 1u);
}

// Many writers race for one name without --force: exactly one wins, the
// file holds exactly its content (never a mix), and no temporary is left.
TEST(AtomicWrite, ConcurrentRefusingWritersNeverClobber) {
  ScratchFolder dir;
  const std::string big_a(1 << 20, 'a'), big_b(1 << 20, 'b');
  std::atomic<int> wins{0};
  std::vector<std::thread> writers;
  for (int t = 0; t < 8; ++t)
    writers.emplace_back([&, t] {
      try {
        write_file_atomically(dir / "race.bin", t % 2 ? big_a : big_b, Overwrite::refuse);
        ++wins;
      } catch (const InvalidInput&) {
      }
    });
  for (auto& w : writers) w.join();
  EXPECT_EQ(wins.load(), 1);
  const std::string content = read_file(dir / "race.bin");
  EXPECT_TRUE(content == big_a || content == big_b);
  EXPECT_EQ(entries(dir.path()), 1u);
}

TEST(AtomicWrite, MissingFolderIsAnIoErrorAndLeavesNothing) {
  ScratchFolder dir;
  EXPECT_THROW(write_file_atomically(dir / "no/such/folder/x.txt", "x", Overwrite::refuse), IoError);
  EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(AtomicWrite, ReplacingKeepsOldContentVisibleUntilTheRename) {
  // A reader that opened the old file keeps reading the old bytes: the new
  // file is a different inode renamed into place, not an in-place rewrite.
  ScratchFolder dir;
  write_file_atomically(dir / "a.txt", "old content", Overwrite::refuse);
  std::ifstream reader(dir / "a.txt");
  write_file_atomically(dir / "a.txt", "new", Overwrite::replace);
  std::string seen;
  std::getline(reader, seen);
  EXPECT_EQ(seen, "old content");
  EXPECT_EQ(read_file(dir / "a.txt"), "new");
}

TEST(ReadFile, MissingFileAndFolderAreClearErrors) {
  ScratchFolder dir;
  expect_error<InvalidInput>([&] { read_file(dir / "none.ply"); }, {"none.ply", "no such file"});
  expect_error<InvalidInput>([&] { read_file(dir.path()); }, {"folder"});
  // /dev/zero never ends: it was read until memory ran out.
  expect_error<InvalidInput>([&] { read_file("/dev/zero"); }, {"/dev/zero", "is a device"});
  // A folder without an extension is named as a folder, not as an unknown format.
  expect_error<InvalidInput>([&] { resolve_format(dir.path(), std::nullopt); }, {"is a folder, expected a file"});
  // --format xy names the 2D files' own extension (it was refused while .xy was read).
  EXPECT_EQ(resolve_format("p.txt", std::string("xy")), FileFormat::xyz);
  EXPECT_EQ(format_name(FileFormat::xyz), "xyz");
}

// A signal during a write ends the process as the signal would and leaves no
// temporary file (a Ctrl-C during a 19 GB tessellation left it).
TEST(WriteFile, ASignalMidWriteLeavesNoTemporaryFile) {
  ScratchFolder dir;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_partial_outputs_on_signals();
    write_file_atomically_streamed(dir / "out.ply", [](const ByteSink& sink) {
      sink(std::string(1 << 20, 'x'));
      raise(SIGTERM);  // as if the user ended it here
      sink("never");
    }, Overwrite::refuse);
    _exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ADD_FAILURE() << "left behind: " << entry.path();
}

// JSON documents: what is wrong, where, in words of the file (nlohmann's
// exception tags and its out_of_range for "1e999" reached the terminal).
TEST(ReadJsonDocument, ProblemsNameTheFileAndLine) {
  ScratchFolder dir;
  std::ofstream(dir / "empty.json") << " \n";
  expect_error<InvalidInput>([&] { read_json_document(dir / "empty.json"); }, {"empty.json: file is empty"});
  std::ofstream(dir / "cut.json") << "{\n  \"a\": [1,\n";
  expect_error<InvalidInput>([&] { read_json_document(dir / "cut.json"); }, {"cut.json:3: not valid JSON: column"});
  std::ofstream(dir / "huge.json") << "{\"fx\": 1e999}\n";
  expect_error<InvalidInput>([&] { read_json_document(dir / "huge.json"); },
                             {"huge.json: not valid JSON: number overflow parsing '1e999'"});
  for (const char* name : {"empty.json", "cut.json", "huge.json"})
    try {
      read_json_document(dir / name);
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
    }
  expect_error<InvalidInput>([&] { check_writable(dir.path(), Overwrite::replace); }, {"folder"});
}

// A command's output file is refused before the work when its folder is
// missing or is a file (it was an IoError once the result was written);
// folders a command creates are refused when a file is in the way (it was a
// std::filesystem error, exit code 2).
TEST(OutputFolders, MissingOrFileInTheWayAreNamedBeforeAnyWork) {
  ScratchFolder dir;
  std::ofstream(dir / "file.txt") << "x";
  EXPECT_NO_THROW(check_output_file(dir / "out.ply", Overwrite::refuse));
  expect_error<InvalidInput>([&] { check_output_file(dir / "no" / "out.ply", Overwrite::refuse); },
                             {"out.ply", "does not exist"});
  expect_error<InvalidInput>([&] { check_output_file(dir / "file.txt" / "out.ply", Overwrite::refuse); },
                             {"file.txt is a file"});
  expect_error<InvalidInput>([&] { make_folder(""); }, {"an output folder name is empty"});
  expect_error<InvalidInput>([&] { check_output_file("", Overwrite::replace); }, {"an output file name is empty"});
  make_folder(dir / "a" / "b");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "a" / "b"));
  EXPECT_NO_THROW(make_folder(dir / "a" / "b"));
  expect_error<InvalidInput>([&] { make_folder(dir / "file.txt"); }, {"file.txt: is a file, expected a folder"});
  expect_error<InvalidInput>([&] { make_folder(dir / "file.txt" / "frames"); }, {"file.txt is a file"});
  EXPECT_EQ(read_file(dir / "file.txt"), "x");
}

}  // namespace
}  // namespace scanstation::io
