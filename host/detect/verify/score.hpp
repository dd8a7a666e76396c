// The verified score of a pose, as one model (docs/detect/verify.md, "The score").
//
// It is built in three phases, always in this order (verify_poses.hpp runs them):
//  1. image context, once per image from all its poses: the verification tolerance (it follows
//     the depth noise the best-fitting pose shows) and the ray spread's noise floor;
//  2. per-pose factors, multiplied in the order of ScoreFactor, agreement first; zero when the
//     part would lie below the bin's floor;
//  3. cross-pose adjustments: the rival cap, then the look-alike share.
// fit() is the score before the look-alike share (what --confident compares); score() ranks.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace binpick {

// The factors, in the order they combine. Each has a pure function below (or in its own
// header) and its own unit test.
enum ScoreFactor : std::size_t {
  kAgreement,       // agreement over support (agreement_factor)
  kSeeThrough,      // free space seen where the pose puts the part (see_through_factor)
  kOutline,         // the outline steps down (outline_factor; outline.hpp)
  kPatchBias,       // patches whose residuals do not average out (patch_bias.hpp)
  kSeenArea,        // how much of the part the pose shows (seen_area.hpp)
  kRaySpread,       // spread along the rays beyond the noise (ray_spread.hpp)
  kLookalikeHoles,  // seen through where a look-alike has a hole (lookalike_holes.hpp)
  kEdgeStep,        // a thin part's edges step down (edge_step.hpp)
  kBelowFloor,      // 0: the part would lie below the bin's floor (below_floor.hpp)
  kRivalCap,        // the most the pose may score, out-fitted by a rival (rival.hpp)
  kLookalikeShare,  // s / (s + w a) against its best look-alike (lookalike_share.hpp)
  kScoreFactorCount
};

enum class FactorScope { pose, poses };  // computed from the pose alone, or from several
enum class FactorCombine { multiply, zero, cap };

// One row of the score's table (docs/detect/verify.md shows the same table; a test compares).
struct ScoreFactorInfo {
  const char* name;       // the details.csv column and the --verbose name
  const char* parameter;  // the detection parameter that sets it ("" when none)
  FactorScope scope;
  FactorCombine combine;
  const char* meaning;
};
std::span<const ScoreFactorInfo> score_factors();  // kScoreFactorCount rows, in order
const char* scope_name(FactorScope scope);
const char* combine_name(FactorCombine combine);

struct ScoreBreakdown {
  // Agreement starts at 0 (an unverified pose scores nothing); every other factor at what
  // leaves the score as it is.
  std::array<double, kScoreFactorCount> factor{0, 1, 1, 1, 1, 1, 1, 1, 1, INFINITY, 1};

  double& operator[](ScoreFactor f) { return factor[f]; }
  double operator[](ScoreFactor f) const { return factor[f]; }
  // Phase 2: the product of the multiplying factors in order, zero below the floor.
  double per_pose() const;
  // With the rival cap: the fit, before the look-alike share.
  double fit() const;
  // With the look-alike share: the verified score in [0, 1].
  double score() const;
};

// The table of docs/detect/verify.md ("The score"), one row a factor in order.
std::string score_table_markdown();

// "agreement 0.912 x patch_bias 0.750 x lookalike_share 0.500": the factors that are not neutral,
// in order ("below_floor 0" and "rival_cap 0.310" where they apply).
std::string describe_factors(const ScoreBreakdown& breakdown);
// The factors as CSV cells in order, each preceded by a comma, %.6f; rival_cap empty without a cap.
std::string factor_columns(const ScoreBreakdown& breakdown);

// agreement / max(visible - missing / 2, min_support, 1): missing depth counts half, neither for
// the pose nor fully against it. 0 when nothing is visible or all of it lacks depth.
double agreement_factor(double agreement, std::uint32_t visible, std::uint32_t missing,
                        double min_support);
// The support the agreement is divided by (as above).
double score_support(std::uint32_t visible, std::uint32_t missing, double min_support);
// max(0, 1 - weight x see_through / support); 1 for weight <= 0.
double see_through_factor(double weight, std::uint32_t see_through, double support);
// The share of outline cells where the surface steps down; 1 without cells.
double outline_factor(std::uint32_t step, std::uint32_t run_on);
// s / (s + weight x lookalike) for s > 0 and a look-alike scoring > 0; 1 otherwise.
double lookalike_share_factor(double s, double lookalike, double weight);

}  // namespace binpick
