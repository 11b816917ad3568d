// scanstation's own shared objects, loaded when first used.
#pragma once

#include <string>

namespace scanstation {

/// The address of `symbol` in the loadable module `name`
/// (libscanstation_<name>.so), which is loaded on the first call and stays
/// for the life of the process; later calls only look the symbol up.
///
/// Why modules: OpenCV's image codecs (and ximgproc, built on them) bring
/// about 120 libraries with them — GDAL, GDCM, poppler, HDF5 … — and their
/// symbol binding cost every process about 80 ms and 45 MB at start, most
/// of `scanstation info` or of reconstructing a small mesh. Behind a module
/// only the commands that read or write an image pay it, as libcamera loads
/// its IPA modules.
///
/// Where: `<dir of the executable>/../lib/scanstation/` (an installed
/// tree), then the build tree's module folder. Thread-safe.
/// Throws IoError naming the paths tried and the loader's reason.
void* module_symbol(const std::string& name, const char* symbol);

/// The table of functions that module `name` hands out through its entry
/// `extern "C" const Table* entry()` (see core/imgcodecs_module.h).
template <typename Table>
const Table& module_table(const std::string& name, const char* entry) {
  return *reinterpret_cast<const Table* (*)()>(module_symbol(name, entry))();
}

}  // namespace scanstation
