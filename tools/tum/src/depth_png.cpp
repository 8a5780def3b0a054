#include "relplane/tum/depth_png.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

namespace relplane::tum {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng's error callback records the message and returns; libpng then longjmps to the
// setjmp of the step that failed. The steps below keep no C++ object alive across their
// setjmp, so nothing is skipped by the jump.
struct ErrorText {
  char text[200] = "";
};

void RecordError(png_structp png, png_const_charp message) {
  auto* error = static_cast<ErrorText*>(png_get_error_ptr(png));
  std::snprintf(error->text, sizeof error->text, "%s", message);
}

void IgnoreWarning(png_structp, png_const_charp) {}

bool LittleEndian() {
  const uint16_t probe = 1;
  uint8_t first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

struct Header {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bit_depth = 0;
  int colour = 0;
};

bool ReadHeader(png_structp png, png_infop info, std::FILE* file, Header* header) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  header->width = png_get_image_width(png, info);
  header->height = png_get_image_height(png, info);
  header->bit_depth = png_get_bit_depth(png, info);
  header->colour = png_get_color_type(png, info);
  // PNG stores 16-bit samples big-endian.
  if (header->bit_depth == 16 && LittleEndian()) png_set_swap(png);
  png_read_update_info(png, info);
  return true;
}

bool ReadRows(png_structp png, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

bool WriteRows(png_structp png, png_infop info, std::FILE* file, png_uint_32 width,
               png_uint_32 height, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_IHDR(png, info, width, height, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (LittleEndian()) png_set_swap(png);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

DepthImage ReadDepthPng(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw DepthImageError(path + ": cannot open it");
  png_byte signature[8];
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    throw DepthImageError(path + ": not a PNG file");
  }
  ErrorText error;
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, RecordError, IgnoreWarning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  struct Release {
    png_structp* png;
    png_infop* info;
    ~Release() {
      if (*png != nullptr) png_destroy_read_struct(png, info, nullptr);
    }
  } release{&png, &info};
  if (info == nullptr) throw DepthImageError(path + ": libpng could not start");
  Header header;
  if (!ReadHeader(png, info, file.get(), &header)) {
    throw DepthImageError(path + ": " + error.text);
  }
  if (header.colour != PNG_COLOR_TYPE_GRAY) {
    throw DepthImageError(path + ": not a single-channel (greyscale) image");
  }
  if (header.bit_depth != 16 && header.bit_depth != 8) {
    throw DepthImageError(path + ": " + std::to_string(header.bit_depth) +
                          "-bit greyscale, expected 16");
  }
  if (header.width > 16384 || header.height > 16384) {
    throw DepthImageError(path + ": impossible size " + std::to_string(header.width) + "x" +
                          std::to_string(header.height));
  }
  DepthImage image;
  image.width = static_cast<int>(header.width);
  image.height = static_cast<int>(header.height);
  const size_t n = static_cast<size_t>(header.width) * header.height;
  image.values.assign(n, 0);
  const size_t bytes_per_sample = header.bit_depth == 16 ? 2 : 1;
  std::vector<png_byte> bytes(bytes_per_sample == 1 ? n : 0);
  std::vector<png_bytep> rows(header.height);
  for (png_uint_32 v = 0; v < header.height; ++v) {
    const size_t start = static_cast<size_t>(v) * header.width;
    rows[v] = bytes_per_sample == 2 ? reinterpret_cast<png_bytep>(&image.values[start])
                                    : &bytes[start];
  }
  if (!ReadRows(png, rows.data())) throw DepthImageError(path + ": " + error.text);
  for (size_t i = 0; i < bytes.size(); ++i) image.values[i] = bytes[i];
  return image;
}

void WriteDepthPng(const std::string& path, const DepthImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.values.size() != static_cast<size_t>(image.width) * image.height) {
    throw DepthImageError(path + ": the image's size does not match its values");
  }
  File file(std::fopen(path.c_str(), "wb"));
  if (!file) throw DepthImageError(path + ": cannot create it");
  ErrorText error;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, RecordError, IgnoreWarning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  struct Release {
    png_structp* png;
    png_infop* info;
    ~Release() {
      if (*png != nullptr) png_destroy_write_struct(png, info);
    }
  } release{&png, &info};
  if (info == nullptr) throw DepthImageError(path + ": libpng could not start");
  std::vector<png_bytep> rows(static_cast<size_t>(image.height));
  for (int v = 0; v < image.height; ++v) {
    rows[static_cast<size_t>(v)] = reinterpret_cast<png_bytep>(
        const_cast<uint16_t*>(&image.values[static_cast<size_t>(v) * image.width]));
  }
  if (!WriteRows(png, info, file.get(), static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), rows.data())) {
    throw DepthImageError(path + ": " + error.text);
  }
  if (std::fflush(file.get()) != 0) throw DepthImageError(path + ": writing failed");
}

}  // namespace relplane::tum
