#include "core/loadable_module.h"

#include "core/errors.h"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

namespace scanstation {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> folders() {
  std::vector<fs::path> result;
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (!error) result.push_back(executable.parent_path().parent_path() / "lib" / "scanstation");
  result.emplace_back(SCANSTATION_MODULE_BUILD_DIR);
  return result;
}

void* open_module(const std::string& name) {
  const std::string file = "libscanstation_" + name + ".so";
  std::string tried;
  for (const fs::path& folder : folders()) {
    const fs::path path = folder / file;
    if (!fs::exists(path)) {
      tried += "\n  " + path.string() + ": no such file";
      continue;
    }
    // RTLD_NOW: a module that cannot bind fails here, naming the symbol,
    // not at its first call.
    if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
    tried += "\n  " + path.string() + ": " + dlerror();
  }
  throw IoError("cannot load scanstation's module " + file + " (an incomplete build or installation):" + tried);
}

}  // namespace

void* module_symbol(const std::string& name, const char* symbol) {
  static std::mutex mutex;
  static std::map<std::string, void*> handles;
  void* handle = nullptr;
  {
    const std::lock_guard lock(mutex);
    auto [it, inserted] = handles.try_emplace(name, nullptr);
    if (inserted) {
      try {
        it->second = open_module(name);
      } catch (...) {
        handles.erase(it);
        throw;
      }
    }
    handle = it->second;
  }
  if (void* address = dlsym(handle, symbol)) return address;
  throw IoError("scanstation's module libscanstation_" + name + ".so has no entry " + symbol +
                " (a module from another build?)");
}

}  // namespace scanstation
