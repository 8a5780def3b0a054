#pragma once
// The scenario's `segmenter` section -> segmenter options (the one options loader).

#include <cstdint>
#include <string>

#include "relplane/common/options.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// What the service needs beyond the algorithm's options.
struct ServiceOptions {
  Options segmenter;
  int64_t max_points = 1000000;  // larger clouds are rejected (a 640x480 frame is 307200)
};

// Reads the options from `r` (a `segmenter` section); throws config::ConfigError.
ServiceOptions ReadServiceOptions(config::Reader& r);
// Loads the `segmenter` section of `file` (defaults when `file` is empty) and checks that no
// key is unknown.
ServiceOptions LoadServiceOptions(const std::string& file);

}  // namespace relplane::segmenter
