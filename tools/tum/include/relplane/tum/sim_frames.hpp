#pragma once
// Simulated frames in the TUM convention: the simulator's pinhole grid as intrinsics and a
// scan as a 16-bit depth image (relplane-tum-write, and the tests that play such a folder).

#include "relplane/sim/depth_sensor.hpp"
#include "relplane/tum/tum_folder.hpp"

namespace relplane::tum {

// The intrinsics of the simulator's pinhole grid: column u and row v of a width x height image
// spanning hfov x vfov, pixel centres at u + 0.5 of the image's width.
Intrinsics SimIntrinsics(const sim::SensorOptions& sensor, double depth_scale = 5000.0);

// The scan's depths (x, forward) at their pixels, value round(depth * depth_scale); 0 where the
// ray returned nothing or the depth does not fit in 16 bits. `clipped` counts the latter.
DepthImage ScanToDepthImage(const sim::Scan& scan, const sim::SensorOptions& sensor,
                            double depth_scale = 5000.0, int* clipped = nullptr);

}  // namespace relplane::tum
