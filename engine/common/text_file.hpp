#pragma once
// Writing an output file whole or not at all: the text goes to a temporary file beside the target, which is
// flushed, closed and then renamed over it, so a reader (or a crash) never sees a half-written file.
#include <string>

namespace dampbench {

/// Writes `text` to `path` atomically (POSIX rename). InputError naming the path and the system's reason when
/// the folder is missing or not writable or the disk is full; the target is then left as it was.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace dampbench
