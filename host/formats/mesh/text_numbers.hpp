// Numbers in text mesh formats (ascii PLY, OBJ): the shortest decimal form that reads
// back to the same value, independent of the locale.
#pragma once

#include <charconv>
#include <string>

namespace binpick {

template <typename T>
void append_number(std::string& out, T value) {
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, end);
}

}  // namespace binpick
