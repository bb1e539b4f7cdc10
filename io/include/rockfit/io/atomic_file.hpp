// Text files written atomically: to a temporary file in the same directory, flushed to disk and renamed over
// the target, so that a crash never leaves a half-written file or damages an existing one (docs/design.md §8).
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace rockfit::io {

// Calls `write` with a stream to the temporary file, then renames it to `path`. OutputError when the file
// cannot be written (the previous `path`, if any, is then unchanged); exceptions from `write` propagate after
// the temporary file is removed.
void WriteFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// Every rockfit writer names its temporary file ".<name>.rockfit-tmp-<pid>-<serial>" beside the target.
inline constexpr const char* kTemporaryMarker = ".rockfit-tmp-";

// Removes the temporary files of `target` left by rockfit processes that no longer run (killed before they
// could rename or remove them). Temporaries of running processes, this one included, are kept. Called by
// every writer before it starts, so a kill -9 leaves at most one stale file until the next write.
void RemoveStaleTemporaries(const std::filesystem::path& target);

}  // namespace rockfit::io
