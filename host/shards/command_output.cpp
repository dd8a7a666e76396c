#include "host/shards/command_output.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "host/core/shell_quote.hpp"

namespace binpick {

CommandOutput capture_command(const std::vector<std::string>& words) {
  const std::string line = shell_command(words) + " 2>&1";
  FILE* pipe = ::popen(line.c_str(), "r");
  if (!pipe) return {};
  CommandOutput result;
  std::array<char, 4096> buffer;
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.text.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.status = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "";
  while (!rest.empty()) {
    const std::size_t colon = rest.find(':');
    const std::filesystem::path dir(rest.substr(0, colon));
    rest = colon == rest.npos ? std::string_view() : rest.substr(colon + 1);
    if (::access((dir / program).c_str(), X_OK) == 0) return true;
  }
  return false;
}

}  // namespace binpick
