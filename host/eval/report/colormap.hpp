// Colours for pictures and curves: a perceptually uniform map (viridis, dark purple to yellow)
// so depth reads as brightness, and fixed colours for overlays.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace binpick::eval {

using Rgb = std::array<std::uint8_t, 3>;

// viridis at t in [0, 1] (clamped): 0 = dark purple, 1 = yellow.
Rgb viridis(double t);

// "#rrggbb", for gnuplot and HTML.
std::string hex(const Rgb& c);

// Distinct colours for the hypotheses of an image, by rank (cycles after 8).
Rgb rank_colour(int rank);

inline constexpr Rgb kCorrect{40, 220, 60};   // green
inline constexpr Rgb kWrong{235, 40, 40};     // red
inline constexpr Rgb kTopRing{255, 215, 0};   // gold: the top-ranked detection
inline constexpr Rgb kScenePoints{70, 130, 255};   // blue, as the paper's Figure 3
inline constexpr Rgb kModelPoints{255, 60, 200};   // pink, as the paper's Figure 3

}  // namespace binpick::eval
