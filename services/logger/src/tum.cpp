#include "relplane/eval/tum.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace relplane::eval {

std::string FormatTum(const std::vector<PoseSample>& poses) {
  std::string out;
  out.reserve(poses.size() * 100);
  char line[256];
  for (const PoseSample& p : poses) {
    const Eigen::Quaterniond& q = p.orientation;
    // utime is integral microseconds: print seconds with all six decimals, no rounding loss.
    const int64_t whole = p.utime / 1000000;
    const int64_t micros = std::llabs(p.utime % 1000000);
    std::snprintf(line, sizeof(line), "%s%lld.%06lld %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n",
                  (p.utime < 0 && whole == 0) ? "-" : "", static_cast<long long>(whole),
                  static_cast<long long>(micros), p.position.x(), p.position.y(), p.position.z(),
                  q.x(), q.y(), q.z(), q.w());
    out += line;
  }
  return out;
}

bool ParseTum(const std::string& text, std::vector<PoseSample>* poses, std::string* reason) {
  poses->clear();
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    std::istringstream fields(line);
    double v[8];
    for (double& x : v) {
      if (!(fields >> x) || !std::isfinite(x)) {
        *reason = "line " + std::to_string(line_number) + ": expected 8 numbers";
        return false;
      }
    }
    std::string extra;
    if (fields >> extra) {
      *reason = "line " + std::to_string(line_number) + ": more than 8 fields";
      return false;
    }
    PoseSample p;
    p.utime = std::llround(v[0] * 1e6);
    p.seq = static_cast<int64_t>(poses->size());
    p.position = {v[1], v[2], v[3]};
    p.orientation = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);
    poses->push_back(p);
  }
  return true;
}

}  // namespace relplane::eval
