#include "core/io/file_access.h"

#include "core/errors.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace scanstation::io {

namespace fs = std::filesystem;

namespace {
std::string os_error(const std::string& what, const fs::path& path, int error) {
  return what + " " + path.string() + ": " + std::strerror(error);
}

void write_all(int fd, std::string_view content, const fs::path& temp) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(os_error("cannot write", temp, errno));
    }
    content.remove_prefix(static_cast<std::size_t>(n));
  }
}

// Moves temp onto target; when refusing, fails instead of replacing a target
// that appeared meanwhile (RENAME_NOREPLACE, or link+unlink where the file
// system lacks it).
void move_into_place(const fs::path& temp, const fs::path& target, Overwrite overwrite) {
  if (overwrite == Overwrite::replace) {
    if (std::rename(temp.c_str(), target.c_str()) != 0) throw IoError(os_error("cannot rename onto", target, errno));
    return;
  }
  if (::renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, target.c_str(), RENAME_NOREPLACE) == 0) return;
  int error = errno;
  if (error == EINVAL || error == ENOSYS) {
    if (::link(temp.c_str(), target.c_str()) == 0) {
      ::unlink(temp.c_str());
      return;
    }
    error = errno;
  }
  if (error == EEXIST)
    throw InvalidInput(target.string() + ": output exists; not replacing it (use --force to replace)");
  throw IoError(os_error("cannot create", target, error));
}
}  // namespace

std::string read_file(const fs::path& path) {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) throw InvalidInput(path.string() + ": no such file");
  if (fs::is_directory(status)) throw InvalidInput(path.string() + ": is a folder, expected a file");
  // A device such as /dev/zero never ends: it would be read until memory ran
  // out. Pipes are read (process substitution, /dev/stdin from a pipe).
  if (fs::is_character_file(status) || fs::is_block_file(status))
    throw InvalidInput(path.string() + ": is a device, expected a file or a pipe");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(os_error("cannot open", path, errno));
  std::string content;
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size > 0) {
    content.resize(static_cast<std::size_t>(size));
    in.seekg(0);
    in.read(content.data(), size);
  } else {  // not seekable (a pipe): read in chunks
    in.clear();
    content.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (in.bad()) throw IoError(os_error("cannot read", path, errno));
  return content;
}

void check_writable(const fs::path& path, Overwrite overwrite) {
  if (path.empty()) throw InvalidInput("an output file name is empty");
  std::error_code ec;
  if (overwrite == Overwrite::refuse && fs::exists(path, ec))
    throw InvalidInput(path.string() + ": output exists; not replacing it (use --force to replace)");
  if (fs::is_directory(path, ec)) throw InvalidInput(path.string() + ": is a folder, expected a file name");
}

void check_output_file(const fs::path& path, Overwrite overwrite) {
  check_writable(path, overwrite);
  const fs::path folder = path.parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::is_directory(folder, ec))
    throw InvalidInput(path.string() + ": the folder " + folder.string() +
                       (fs::exists(folder, ec) ? " is a file" : " does not exist"));
}

void make_folder(const fs::path& folder) {
  if (folder.empty()) throw InvalidInput("an output folder name is empty");  // it was an OS error, exit 2
  std::error_code ec;
  for (fs::path part = folder; !part.empty(); part = part.parent_path()) {
    if (fs::is_directory(part, ec)) break;
    if (fs::exists(part, ec))
      throw InvalidInput(folder.string() + ": " + (part == folder ? "is a file, expected a folder" : part.string() + " is a file"));
    if (part == part.parent_path()) break;
  }
  fs::create_directories(folder, ec);
  if (ec) throw IoError(os_error("cannot create the folder", folder, ec.value()));
}

namespace {
// The temporary files being written, for remove_partial_outputs: fixed
// slots of plain bytes, so that a signal handler may read them (it may not
// lock or allocate). A slot is filled before its file exists and emptied
// after the file is renamed or removed.
constexpr int kTemporarySlots = 16;
constexpr std::size_t kTemporaryPath = 4096;
char g_temporaries[kTemporarySlots][kTemporaryPath];
std::atomic<bool> g_temporary_used[kTemporarySlots];

int hold_temporary(const fs::path& temp) {
  const std::string& name = temp.native();
  if (name.size() >= kTemporaryPath) return -1;
  for (int slot = 0; slot < kTemporarySlots; ++slot) {
    bool expected = false;
    if (!g_temporary_used[slot].load() && g_temporary_used[slot].compare_exchange_strong(expected, true)) {
      // The first byte last: a signal between the two sees an empty slot,
      // never a path half copied over an older one.
      g_temporaries[slot][0] = '\0';
      std::atomic_signal_fence(std::memory_order_seq_cst);
      std::memcpy(g_temporaries[slot] + 1, name.c_str() + 1, name.size());
      std::atomic_signal_fence(std::memory_order_seq_cst);
      g_temporaries[slot][0] = name[0];
      return slot;
    }
  }
  return -1;  // more at once than slots: that one is not removed on a signal
}

void release_temporary(int slot) {
  if (slot < 0) return;
  g_temporaries[slot][0] = '\0';
  g_temporary_used[slot].store(false);
}

extern "C" void remove_partial_outputs_and_die(int signal_number) {
  remove_partial_outputs();
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// Creates a fresh temporary file beside `path`; the mode 0666 is reduced by
// the umask as for any new file.
int create_temporary(const fs::path& path, fs::path& temp) {
  static std::atomic<unsigned> counter{0};
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = ".";  // appended piecewise: GCC 12 misreports chained '+' here (-Wrestrict)
    name.append(path.filename().string()).append(".tmp-").append(std::to_string(::getpid()));
    name.append("-").append(std::to_string(counter++));
    temp = folder / name;
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST) throw IoError(os_error("cannot create a temporary file in", folder, errno));
  }
  throw IoError("cannot create a temporary file in " + folder.string());
}
}  // namespace

void write_file_atomically(const fs::path& path, std::string_view content, Overwrite overwrite) {
  write_file_atomically_streamed(path, [content](const ByteSink& sink) { sink(content); }, overwrite);
}

void write_file_atomically_streamed(const fs::path& path, const std::function<void(const ByteSink&)>& produce,
                                    Overwrite overwrite) {
  check_writable(path, overwrite);
  fs::path temp;
  int fd = create_temporary(path, temp);
  const int slot = hold_temporary(temp);
  struct Release {
    int slot;
    ~Release() { release_temporary(slot); }
  } release{slot};
  try {
    produce([fd, &temp](std::string_view piece) { write_all(fd, piece, temp); });
    if (::fsync(fd) != 0) throw IoError(os_error("cannot flush", temp, errno));
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) throw IoError(os_error("cannot close", temp, errno));
    move_into_place(temp, path, overwrite);
  } catch (...) {
    if (fd >= 0) ::close(fd);
    ::unlink(temp.c_str());
    throw;
  }
}

void remove_partial_outputs() noexcept {
  for (int slot = 0; slot < kTemporarySlots; ++slot)
    if (g_temporary_used[slot].load() && g_temporaries[slot][0] != '\0') ::unlink(g_temporaries[slot]);
}

void remove_partial_outputs_on_signals() {
  struct sigaction action{};
  action.sa_handler = remove_partial_outputs_and_die;
  sigemptyset(&action.sa_mask);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction previous{};
    sigaction(signal_number, nullptr, &previous);
    if (previous.sa_handler == SIG_IGN) continue;  // ignored on purpose (nohup, a background job): stays so
    sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace scanstation::io
