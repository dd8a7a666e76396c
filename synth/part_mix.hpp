// Distractors: other kinds of part dropped into the bin among the part the dataset is about
// (obj_id 1). Each distractor model gets the next obj_id (2, 3, ... in the order given) and a
// share of the --objects count; the kinds are mixed in the waves by a shuffle drawn from the
// bin's seed, so the same seed gives the same pile.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace binpick {

// A distractor without a fraction gets this share of --objects, split evenly among all the
// distractors listed (one: 0.25; two: 0.125 each).
inline constexpr double kDefaultDistractorShare = 0.25;

struct DistractorSpec {
  std::string model;               // a model file or builtin:NAME
  std::optional<double> fraction;  // of --objects; none: the default share
};

// Parses "MODEL[:FRACTION],...": a trailing ":NUMBER" is the fraction (builtin:bolt has none,
// builtin:bolt:0.2 has 0.2). Throws InputError naming the option for an empty list or item, or a
// fraction that is not a number in (0, 1).
std::vector<DistractorSpec> parse_distractors(const std::string& text);

// Each distractor's fraction (given or default), in order.
std::vector<double> distractor_fractions(const std::vector<DistractorSpec>& specs);

// How many parts of each kind: [0] the dataset's part, [k] distractor k (round(fraction *
// objects)). Throws InputError unless every fraction is in (0, 1), they sum to less than 1 and
// the dataset's part keeps at least one part.
std::vector<int> kind_counts(int objects, const std::vector<DistractorSpec>& specs);

// The kinds in release order: counts[k] times k, shuffled (Fisher-Yates on std::mt19937_64's raw
// bits, the same on every platform) by `seed`. Without distractors, all 0 and no shuffle.
std::vector<int> mixed_sequence(const std::vector<int>& counts, std::uint64_t seed);

}  // namespace binpick
