#include "host/eval/report/gnuplot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "host/core/shell_quote.hpp"

namespace binpick::eval {
namespace {

namespace fs = std::filesystem;

}  // namespace

std::string gnuplot_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::optional<fs::path> find_gnuplot() {
  if (const char* env = std::getenv("BINPICK_GNUPLOT"); env && *env) {
    if (::access(env, X_OK) == 0) return fs::path(env);
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::string_view dirs = path ? path : "/usr/bin:/bin";
  while (!dirs.empty()) {
    const auto colon = dirs.find(':');
    const fs::path candidate = fs::path(std::string(dirs.substr(0, colon))) / "gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    if (colon == std::string_view::npos) break;
    dirs.remove_prefix(colon + 1);
  }
  return std::nullopt;
}

void run_gnuplot_png(const fs::path& gnuplot, const std::string& script, const fs::path& png) {
  // The temporary name is unique per process so parallel runs into one directory cannot clash.
  const fs::path partial = png.parent_path() /
                           fmt::format(".{}.{}.partial", png.filename().string(), ::getpid());
  const std::string full = "set output " + gnuplot_quoted(partial.string()) + "\n" + script +
                           "\nset output\n";
  // gnuplot reads the script on stdin; its own messages go to our stderr, where a user sees them.
  // A gnuplot that dies early must not kill us with SIGPIPE while we write its script.
  auto* previous = std::signal(SIGPIPE, SIG_IGN);
  FILE* pipe = ::popen((shell_quoted(gnuplot.string()) + " -").c_str(), "w");
  if (!pipe) {
    std::signal(SIGPIPE, previous);
    throw std::runtime_error("cannot start " + gnuplot.string());
  }
  const bool written = std::fwrite(full.data(), 1, full.size(), pipe) == full.size();
  const int status = ::pclose(pipe);
  std::signal(SIGPIPE, previous);
  std::error_code ec;
  if (!written || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
      !fs::exists(partial) || fs::file_size(partial, ec) == 0) {
    fs::remove(partial, ec);
    throw std::runtime_error(fmt::format("{} failed drawing {} (status {})", gnuplot.string(),
                                         png.string(), status));
  }
  fs::rename(partial, png);
}

}  // namespace binpick::eval
