#include <regex>
#include <set>
#include <sstream>

#include "host/runtime/cl/cl_device.hpp"
#include "host/runtime/embedded.hpp"

namespace binpick::ocl {
namespace {

void append_resolved(std::string_view file, std::set<std::string, std::less<>>& seen,
                     std::string& out) {
  if (!seen.insert(std::string(file)).second) return;  // each header once
  static const std::regex include_line(R"re(^\s*#\s*include\s+"([^"]+)"\s*$)re");
  std::istringstream in(embedded::kernel_source(file));
  std::string line;
  int number = 0;
  out += "#line 1 \"" + std::string(file) + "\"\n";
  while (std::getline(in, line)) {
    ++number;
    std::smatch m;
    if (std::regex_match(line, m, include_line)) {
      append_resolved(m[1].str(), seen, out);
      out += "#line " + std::to_string(number + 1) + " \"" + std::string(file) + "\"\n";
    } else {
      out += line + "\n";
    }
  }
}

}  // namespace

std::string resolved_source(std::string_view program_file) {
  std::set<std::string, std::less<>> seen;
  std::string out;
  append_resolved(program_file, seen, out);
  return out;
}

}  // namespace binpick::ocl
