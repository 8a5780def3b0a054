#include "relplane/compare/organized_frame.hpp"

#include <limits>

namespace relplane::compare {

OrganizedFrame FromScan(const sim::Scan& scan, int width, int height) {
  OrganizedFrame frame;
  frame.width = width;
  frame.height = height;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  frame.points.x.assign(n, nan);
  frame.points.y.assign(n, nan);
  frame.points.z.assign(n, nan);
  for (size_t i = 0; i < scan.points.size(); ++i) {
    // The scan numbers its rays col * height + row; the image is row-major.
    const int col = scan.pixels[i] / height, row = scan.pixels[i] % height;
    const size_t at = static_cast<size_t>(row) * width + col;
    frame.points.x[at] = scan.points[i].x();
    frame.points.y[at] = scan.points[i].y();
    frame.points.z[at] = scan.points[i].z();
  }
  return frame;
}

}  // namespace relplane::compare
