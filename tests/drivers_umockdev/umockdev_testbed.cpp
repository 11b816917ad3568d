#include "umockdev_testbed.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <umockdev.h>

namespace scanstation::test {

namespace {

void check(gboolean ok, GError* error, const std::string& what) {
  if (ok) return;
  const std::string message = error ? error->message : "?";
  g_clear_error(&error);
  throw std::runtime_error("umockdev: " + what + ": " + message);
}

}  // namespace

UmockdevTestbed::UmockdevTestbed() : testbed_(umockdev_testbed_new()) {}

UmockdevTestbed::~UmockdevTestbed() { g_object_unref(testbed_); }

void UmockdevTestbed::add(const std::string& record) {
  GError* error = nullptr;
  check(umockdev_testbed_add_from_string(testbed_, record.c_str(), &error), error, "cannot add a device");
}

void UmockdevTestbed::attach(const std::string& devnode, UMockdevIoctlBase* handler) {
  GError* error = nullptr;
  check(umockdev_testbed_attach_ioctl(testbed_, devnode.c_str(), handler, &error), error,
        "cannot attach an ioctl handler to " + devnode);
}

void UmockdevTestbed::detach(const std::string& devnode) {
  umockdev_testbed_detach_ioctl(testbed_, devnode.c_str(), nullptr);
}

void UmockdevTestbed::uevent(const std::string& syspath, const char* action) {
  umockdev_testbed_uevent(testbed_, syspath.c_str(), action);
}

void UmockdevTestbed::remove(const std::string& syspath) { umockdev_testbed_remove_device(testbed_, syspath.c_str()); }

std::string UmockdevTestbed::sys_dir() const {
  gchar* dir = umockdev_testbed_get_sys_dir(testbed_);
  std::string result = dir;
  g_free(dir);
  return result;
}

bool umockdev_preloaded() {
  // What umockdev itself checks (umockdev_in_mock_environment() instead tells
  // whether a testbed exists).
  const char* preload = std::getenv("LD_PRELOAD");
  return preload && std::strstr(preload, "libumockdev-preload");
}

}  // namespace scanstation::test
