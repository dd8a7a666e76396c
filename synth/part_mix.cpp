#include "synth/part_mix.hpp"

#include <fmt/format.h>

#include <cmath>
#include <random>

#include "host/core/error.hpp"
#include "synth/physics/drop_random.hpp"

namespace binpick {
namespace {

void check_fraction(double f, const std::string& model) {
  if (!(std::isfinite(f) && f > 0.0 && f < 1.0))
    throw InputError(
        fmt::format("--distractors: the fraction of {} must be in (0, 1), got {}", model, f));
}

// The number at the end of "builtin:bolt:0.2", if that is what follows the last colon.
std::optional<double> trailing_fraction(const std::string& item, std::size_t colon) {
  const std::string tail = item.substr(colon + 1);
  if (tail.empty()) return std::nullopt;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(tail, &used);
  } catch (const std::exception&) {
    return std::nullopt;  // "bolt": part of the model name
  }
  if (used != tail.size()) return std::nullopt;  // "0.5.ply": part of a file name
  return value;
}

}  // namespace

std::vector<DistractorSpec> parse_distractors(const std::string& text) {
  if (text.empty()) throw InputError("--distractors is empty: give MODEL[:FRACTION],...");
  std::vector<DistractorSpec> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty())
      throw InputError(
          fmt::format("--distractors '{}' has an empty item: give MODEL[:FRACTION],...", text));
    DistractorSpec spec{item, std::nullopt};
    const std::size_t colon = item.rfind(':');
    if (colon != std::string::npos) {
      if (const auto f = trailing_fraction(item, colon)) {
        spec.model = item.substr(0, colon);
        spec.fraction = *f;
        if (spec.model.empty())
          throw InputError(fmt::format("--distractors '{}': a fraction without a model", item));
        check_fraction(*f, spec.model);
      }
    }
    out.push_back(spec);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<double> distractor_fractions(const std::vector<DistractorSpec>& specs) {
  std::vector<double> out;
  for (const auto& s : specs)
    out.push_back(s.fraction.value_or(kDefaultDistractorShare / double(specs.size())));
  return out;
}

std::vector<int> kind_counts(int objects, const std::vector<DistractorSpec>& specs) {
  const std::vector<double> fractions = distractor_fractions(specs);
  std::vector<int> counts{objects};
  double sum = 0;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    check_fraction(fractions[k], specs[k].model);
    sum += fractions[k];
    counts.push_back(int(std::lround(fractions[k] * objects)));
    counts[0] -= counts.back();
  }
  if (!(sum < 1.0))
    throw InputError(
        fmt::format("--distractors: the fractions sum to {}, leaving no part of the "
                    "dataset's own; keep the sum below 1",
                    sum));
  if (counts[0] < 1)
    throw InputError(
        fmt::format("--distractors take all {} --objects: none is left for the "
                    "dataset's own part",
                    objects));
  return counts;
}

std::vector<int> mixed_sequence(const std::vector<int>& counts, std::uint64_t seed) {
  std::vector<int> sequence;
  for (std::size_t k = 0; k < counts.size(); ++k)
    sequence.insert(sequence.end(), std::size_t(counts[k]), int(k));
  if (counts.size() < 2) return sequence;
  std::mt19937_64 rng(seed);
  for (std::size_t i = sequence.size(); i > 1; --i) {
    const auto j = std::min(std::size_t(uniform_unit(rng) * double(i)), i - 1);
    std::swap(sequence[i - 1], sequence[j]);
  }
  return sequence;
}

}  // namespace binpick
