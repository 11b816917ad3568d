// Helpers shared by the test suites: real data paths, scratch folders, and
// checks on error messages.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>

namespace scanstation::test {

/// A file from Debian's libcgal-demo data, e.g. cgal_data("meshes/elephant.off").
inline std::filesystem::path cgal_data(const std::string& relative) {
  return std::filesystem::path(SCANSTATION_CGAL_DATA) / relative;
}

/// A fresh, empty folder removed at the end of the test.
class ScratchFolder {
 public:
  ScratchFolder() {
    static std::mt19937_64 engine{std::random_device{}()};
    path_ = std::filesystem::temp_directory_path() / ("scanstation-test-" + std::to_string(engine()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Runs `action`, expects an exception of type E whose message holds every
/// one of `parts`.
template <typename E>
void expect_error(const std::function<void()>& action, std::initializer_list<std::string> parts) {
  try {
    action();
    ADD_FAILURE() << "expected an exception mentioning " << *parts.begin();
  } catch (const E& e) {
    for (const std::string& part : parts) EXPECT_THAT(e.what(), testing::HasSubstr(part));
  }
}

}  // namespace scanstation::test
