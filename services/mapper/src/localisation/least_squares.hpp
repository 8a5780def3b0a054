#pragma once
// The mapper's one small least-squares solve for a position (the pose solver §II.D-E, a group's
// placement §II.D): the other small systems use Eigen's LDLT directly.

#include <Eigen/Core>

namespace relplane::mapper {

// Least squares a x = b for a position, with `previous` as a weak prior (weight `prior_weight`,
// applied when the smallest information is below `min_information`). Along a direction the
// equations leave open (information below `open_information`, LocalisationOptions) the previous
// position is kept as
// it is: their lines' millimetre disagreements would otherwise move it by centimetres, through
// the slight angle between them, every time it is solved.
Eigen::Vector2d SolveWithPrior(const Eigen::Matrix2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& previous, double prior_weight,
                               double min_information, double open_information);

}  // namespace relplane::mapper
