// Runs a command (the words shell-quoted, stderr joined to stdout) and captures its output, for
// the Slurm client commands (sbatch, squeue, scancel).
#pragma once

#include <string>
#include <vector>

namespace binpick {

struct CommandOutput {
  int status = -1;  // exit status; -1 if it could not run or did not exit normally
  std::string text;
};

CommandOutput capture_command(const std::vector<std::string>& words);

// Whether `program` is an executable file in a directory of $PATH.
bool on_path(const std::string& program);

}  // namespace binpick
