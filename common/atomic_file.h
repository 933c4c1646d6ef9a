// Writes a whole file so that readers and crashes only ever see the old
// content or the new one, never a half-written file.
#pragma once

#include <string>
#include <string_view>

namespace mrsim {

// Writes `bytes` to path.tmp, flushes it to disk (fsync), renames it over
// `path` and syncs the directory. Throws std::runtime_error
// "cannot write 'PATH': REASON"; the old file, if any, is left untouched.
void WriteFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace mrsim
