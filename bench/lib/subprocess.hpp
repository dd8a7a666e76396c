// Runs a program with arguments (no shell, so paths need no quoting) and waits for it; its
// stdout and stderr are this process's. Returns its exit status, or -1 if it could not be
// started or did not exit normally.
#pragma once

#include <string>
#include <vector>

namespace binpick::bench {

int run_program(const std::string& program, const std::vector<std::string>& args);

}  // namespace binpick::bench
