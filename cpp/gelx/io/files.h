#pragma once
/// @file files.h
/// Writing a result file so that a failure (a full disk, a kill) never leaves it half written.

#include <filesystem>
#include <functional>
#include <ios>
#include <ostream>
#include <string>

namespace gelx
{

/// Replace `path` by what `write` writes: written aside, then renamed (atomic on POSIX file
/// systems), so that a reader, or a run killed meanwhile, never leaves half a file. A write
/// that fails (a full disk) leaves `path` as it was, removes the partial copy and throws
/// std::runtime_error naming the file and the system's reason.
void replace_file(const std::filesystem::path& path,
                  const std::function<void(std::ostream&)>& write,
                  std::ios::openmode mode = std::ios::out);

/// Append `text` (whole rows of a table) to the existing file `path` in place: a table of n rows
/// costs O(n) to write, where replacing it at every row costs O(n²) (a 1e5-step explicit run's
/// steps.csv would be rewritten at 50 MB a step). A write that fails or is cut short (a full
/// disk) is undone, the file truncated to its size before, and throws std::runtime_error naming
/// the file and the system's reason. A SIGKILL can still cut a write in its middle: what follows
/// the last newline is then the row being written, which readers skip (demos/fields.py) and a
/// restart drops (ResultsWriter keeps the rows its checkpoint counts).
void append_to_file(const std::filesystem::path& path, const std::string& text);

} // namespace gelx
