// A CSV field in double quotes, inner quotes doubled (RFC 4180): free text such as a reason.
#pragma once

#include <string>

namespace binpick {

inline std::string csv_quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace binpick
