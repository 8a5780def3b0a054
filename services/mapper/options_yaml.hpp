#pragma once
// The scenario's `mapper` section -> MapperOptions (the one options loader, config::Reader).

#include <string>

#include "relplane/common/options.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// Reads the options from `r` (a `mapper` section); throws config::ConfigError.
MapperOptions ReadMapperOptions(config::Reader& r);
// Loads the `mapper` section of `file` (defaults when `file` is empty) and checks that no key
// is unknown.
MapperOptions LoadMapperOptions(const std::string& file);

}  // namespace relplane::mapper
