#include "relplane/pcd/lzf.hpp"

#include <string>

namespace relplane::pcd {

// LZF streams are a sequence of chunks. A control byte below 32 starts a literal run of
// (ctrl + 1) bytes; otherwise it is a back reference: the top three bits hold the length - 2
// (7 means "one more length byte follows"), the low five bits and the next byte the offset - 1.
std::vector<uint8_t> LzfDecompress(const uint8_t* data, size_t size, size_t expected_size) {
  std::vector<uint8_t> out(expected_size);
  size_t in = 0;
  size_t pos = 0;
  auto fail = [](const std::string& why) { throw std::runtime_error("LZF: " + why); };
  while (in < size) {
    const unsigned ctrl = data[in++];
    if (ctrl < 32) {
      const size_t run = ctrl + 1;
      if (in + run > size) fail("literal run past the end of the input");
      if (pos + run > expected_size) fail("output larger than the declared size");
      for (size_t i = 0; i < run; ++i) out[pos++] = data[in++];
      continue;
    }
    size_t length = ctrl >> 5;
    if (length == 7) {
      if (in >= size) fail("truncated back reference");
      length += data[in++];
    }
    length += 2;
    if (in >= size) fail("truncated back reference");
    const size_t offset = ((ctrl & 0x1fu) << 8) + data[in++] + 1;
    if (offset > pos) fail("back reference before the start of the output");
    if (pos + length > expected_size) fail("output larger than the declared size");
    // Byte by byte: a reference may overlap the bytes it produces (run-length style).
    for (size_t i = 0; i < length; ++i, ++pos) out[pos] = out[pos - offset];
  }
  if (pos != expected_size) {
    fail("expanded to " + std::to_string(pos) + " bytes, header says " +
         std::to_string(expected_size));
  }
  return out;
}

}  // namespace relplane::pcd
