#pragma once
// LZF decompression, the codec of PCD's binary_compressed encoding.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace relplane::pcd {

// Decompresses an LZF stream that must expand to exactly `expected_size` bytes.
// Throws std::runtime_error (one line) on a corrupt, truncated or mis-sized stream.
std::vector<uint8_t> LzfDecompress(const uint8_t* data, size_t size, size_t expected_size);

}  // namespace relplane::pcd
