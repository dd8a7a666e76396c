// Every output file of binpick is written through write_file_atomically: the content goes to a
// temporary file next to the target and is renamed into place only once it is complete, so an
// error (or a crash) never leaves a partial file under the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace binpick {

// Calls write(stream) on a binary stream to a temporary file in path's directory, then renames
// it to path (replacing an existing file). If write throws or the stream fails, the temporary
// file is removed and the error propagates (stream failures become binpick::InputError naming
// path). The directory must exist.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

// Removes what writers killed mid-write left under `dir` (recursively if asked): the temporary
// files of write_file_atomically (.NAME.tmpPID_N) and of the plots (.NAME.PID.partial). Only
// safe while no other process writes there: OutputLock calls it once it holds the lock.
// `name_prefix`, if not empty, limits it to names that start with it. Returns how many.
std::size_t remove_stale_temporaries(const std::filesystem::path& dir, bool recursive,
                                     const std::string& name_prefix = "");

}  // namespace binpick
