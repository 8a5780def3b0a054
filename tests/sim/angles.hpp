#pragma once
// Angle constants shared by the simulator's tests (one definition: the test sources are compiled
// together in a unity build).

namespace relplane::sim::testing {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDeg = kPi / 180.0;

}  // namespace relplane::sim::testing
