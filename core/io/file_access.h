// Whole-file reads and atomic whole-file writes.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace scanstation::io {

/// What to do when an output file already exists.
enum class Overwrite { refuse, replace };

/// The whole content of a file. Throws InvalidInput when it does not exist or
/// is a directory, IoError when it cannot be read.
std::string read_file(const std::filesystem::path& path);

/// Writes `content` to `path` atomically: into a temporary file in the same
/// folder, flushed to disk, then renamed over the target, so a crash never
/// leaves a half-written result. With Overwrite::refuse an existing target is
/// never replaced (checked atomically at the rename) and InvalidInput is
/// thrown; IoError when the folder is not writable.
void write_file_atomically(const std::filesystem::path& path, std::string_view content, Overwrite overwrite);

/// The same for content made in pieces: `produce` is called once with a sink
/// that appends each piece to the temporary file, so a large output never
/// sits in memory whole.
using ByteSink = std::function<void(std::string_view)>;
void write_file_atomically_streamed(const std::filesystem::path& path, const std::function<void(const ByteSink&)>& produce,
                                    Overwrite overwrite);

/// Throws InvalidInput when `path` exists and overwrite is refused: lets a
/// command fail before doing long work whose result it could not keep.
void check_writable(const std::filesystem::path& path, Overwrite overwrite);

/// check_writable for a command's own output file, whose folder the command
/// does not create: a missing folder is refused before any work (InvalidInput),
/// not found when the result is written.
void check_output_file(const std::filesystem::path& path, Overwrite overwrite);

/// Creates `folder` and its parents as needed. InvalidInput when it, or a
/// folder on the way, is a file; IoError when the system refuses.
void make_folder(const std::filesystem::path& folder);

/// Removes the temporary files of the writes in progress (their outputs stay
/// as they were). Async-signal-safe.
void remove_partial_outputs() noexcept;

/// SIGINT, SIGTERM and SIGHUP remove the partial outputs, then end the
/// process as the signal would (a Ctrl-C during a 19 GB tessellation left its
/// temporary file). Signals ignored already stay ignored. A safe-state guard
/// (drivers/safe_state.h) takes the signals over while it exists.
void remove_partial_outputs_on_signals();

}  // namespace scanstation::io
