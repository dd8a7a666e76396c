// Where the parts of a wave start: the paper's array of drop positions over the bin.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "synth/physics/drop.hpp"

namespace binpick {

// Centres of `count` parts (count <= grid_x * grid_y) of bounding radius `radius_mm`: a
// grid_x by grid_y array spread over the interior, a radius plus clearance away from the walls,
// at drop_height_mm but never lower than `lowest_centre_mm` (so a wave starts above the pile).
// Where neighbouring slots are closer than a part's diameter, later slots are lifted by a
// diameter until no two bounding spheres overlap. Throws InputError if the part is wider
// than the bin.
std::vector<Eigen::Vector3d> wave_drop_positions(const DropOptions& options, int count,
                                                 double radius_mm, double lowest_centre_mm);

}  // namespace binpick
