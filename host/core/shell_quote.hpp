// Quoting for /bin/sh: a word in single quotes (a single quote inside as '\''), so any path or
// argument reaches the program as is.
#pragma once

#include <string>
#include <vector>

namespace binpick {

std::string shell_quoted(const std::string& word);

// The words quoted and joined by spaces: a command line for sh -c or a script.
std::string shell_command(const std::vector<std::string>& words);

}  // namespace binpick
