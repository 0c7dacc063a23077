// The export writers' file rule (private to meshio): atomic (hal::PosixFileSink:
// temporary in the target's directory, fsync, rename), and an existing target is
// replaced only when this process committed it (same device and inode) or, with
// `force`, when it is a file of the same kind under the programs' output rule.
#pragma once

#include <string>
#include <string_view>

#include "twister/hal/expected.hpp"
#include "twister/hal/output_file.hpp"

namespace twister::meshio::internal {

hal::Expected<void> write_export_file(const std::string& path, std::string_view bytes,
                                      hal::OutputKind kind, bool force);

// Did this process commit the file now at `path` (same device and inode)?
bool written_by_this_process(const std::string& path);

}  // namespace twister::meshio::internal
