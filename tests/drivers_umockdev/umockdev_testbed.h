// A umockdev testbed owned by a test: a private sysfs, udev database and /dev
// tree for this process (libumockdev-preload.so redirects /sys and /dev there
// and forwards ioctls on emulated nodes to handlers in the test).
#pragma once

#include <string>

typedef struct _UMockdevTestbed UMockdevTestbed;
typedef struct _UMockdevIoctlBase UMockdevIoctlBase;

namespace scanstation::test {

class UmockdevTestbed {
 public:
  UmockdevTestbed();
  ~UmockdevTestbed();
  UmockdevTestbed(const UmockdevTestbed&) = delete;
  UmockdevTestbed& operator=(const UmockdevTestbed&) = delete;

  /// Adds a device from umockdev's record format (P: path, N: node, E: udev
  /// property, A: attribute, H: binary attribute in hex); throws on errors.
  void add(const std::string& record);
  /// Answers the ioctls (and reads/writes) on `devnode` with `handler`.
  void attach(const std::string& devnode, UMockdevIoctlBase* handler);
  void detach(const std::string& devnode);
  void uevent(const std::string& syspath, const char* action);
  void remove(const std::string& syspath);
  /// The real directory standing in for /sys.
  std::string sys_dir() const;

 private:
  UMockdevTestbed* testbed_;
};

/// True when libumockdev-preload.so is loaded (the test runs under umockdev-wrapper).
bool umockdev_preloaded();

/// Message for GTEST_SKIP() when it is not.
inline constexpr const char* kNotPreloaded =
    "libumockdev-preload.so is not loaded: run this binary through umockdev-wrapper (ctest does); "
    "install Debian's umockdev package";

}  // namespace scanstation::test
