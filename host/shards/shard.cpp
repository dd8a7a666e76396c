#include "host/shards/shard.hpp"

#include <charconv>
#include <string_view>

#include <fmt/format.h>

#include "host/core/error.hpp"

namespace binpick {
namespace {

bool parse_positive(std::string_view s, int& value) {
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size() && value >= 1;
}

}  // namespace

std::string Shard::name() const { return fmt::format("{}/{}", index + 1, count); }

Shard parse_shard(const std::string& text) {
  if (text.empty()) return {};
  const std::size_t slash = text.find('/');
  int k = 0, n = 0;
  const bool ok = slash != std::string::npos &&
                  parse_positive(std::string_view(text).substr(0, slash), k) &&
                  parse_positive(std::string_view(text).substr(slash + 1), n);
  if (!ok || k > n || n > 100000)
    throw InputError(fmt::format(
        "--shard '{}': expected K/N with 1 <= K <= N <= 100000, e.g. 2/4 for the second of "
        "four shards",
        text));
  return {k - 1, n};
}

}  // namespace binpick
