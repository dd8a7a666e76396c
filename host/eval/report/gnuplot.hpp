// Driving gnuplot (Debian's gnuplot-nox has the pngcairo terminal, no X needed) to draw PNGs.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace binpick::eval {

// The gnuplot executable on PATH (or $BINPICK_GNUPLOT), if any.
std::optional<std::filesystem::path> find_gnuplot();

// Runs script with gnuplot, its output set to a temporary PNG next to png, then renames that to
// png (so a failure never leaves a partial picture). The script must not set the output itself.
// Throws std::runtime_error with gnuplot's exit status if it fails or writes nothing.
void run_gnuplot_png(const std::filesystem::path& gnuplot, const std::string& script,
                     const std::filesystem::path& png);

// s as a gnuplot single-quoted string literal ('' doubles a quote).
std::string gnuplot_quoted(const std::string& s);

}  // namespace binpick::eval
