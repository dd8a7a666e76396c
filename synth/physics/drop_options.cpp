// Rejects drop options that would make Bullet divide by zero, never settle or run forever.
#include <cmath>
#include <string>

#include "host/core/error.hpp"
#include "synth/physics/drop.hpp"

namespace binpick {
namespace {

void require_positive(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0))
    throw InputError(std::string("drop option ") + name + " must be positive and finite, got " +
                     std::to_string(value));
}

void require_non_negative(double value, const char* name) {
  if (!std::isfinite(value) || value < 0.0)
    throw InputError(std::string("drop option ") + name +
                     " must be zero or positive and finite, got " + std::to_string(value));
}

void require_positive(int value, const char* name) {
  if (value <= 0)
    throw InputError(std::string("drop option ") + name + " must be positive, got " +
                     std::to_string(value));
}

}  // namespace

void validate_drop_options(const DropOptions& o) {
  require_positive(o.bin_size_mm.x(), "bin width (x)");
  require_positive(o.bin_size_mm.y(), "bin depth (y)");
  require_positive(o.bin_size_mm.z(), "bin height (z)");
  require_positive(o.objects, "objects");
  require_positive(o.grid_x, "grid x");
  require_positive(o.grid_y, "grid y");
  require_positive(o.drop_height_mm, "drop height");
  require_positive(o.rest_linear_speed_mm_s, "rest linear speed");
  require_positive(o.rest_angular_speed_rad_s, "rest angular speed");
  require_positive(o.rest_seconds, "rest seconds");
  require_positive(o.max_wave_seconds, "max wave seconds");
  require_non_negative(o.max_wall_seconds, "max wall seconds");
  require_non_negative(o.final_all_dynamic_seconds, "final all-dynamic seconds");
  require_positive(o.time_step_s, "time step");
  if (o.time_step_s > 0.05)
    throw InputError("drop option time step must be at most 0.05 s, got " +
                     std::to_string(o.time_step_s));
  require_positive(o.step_travel, "step travel");
  require_positive(o.solver_iterations, "solver iterations");
  require_non_negative(o.sheet_hull_mm, "sheet hull width");
  require_positive(o.sheet_solver_iterations, "sheet solver iterations");
  require_non_negative(o.friction, "friction");
  require_non_negative(o.restitution, "restitution");
  require_non_negative(o.rolling_friction_mm, "rolling friction");
  if (o.restitution > 1.0)
    throw InputError("drop option restitution must be at most 1, got " +
                     std::to_string(o.restitution));
}

}  // namespace binpick
