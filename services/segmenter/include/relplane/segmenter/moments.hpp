#pragma once
// Point moments accumulated cheaply in float about a nearby reference point, then combined in
// double: the per-point cost of a plane fit over a whole cloud without losing precision.

#include <Eigen/Core>

namespace relplane::segmenter {

struct LocalMoments {
  Eigen::Vector3f ref = Eigen::Vector3f::Zero();  // the first point added
  int n = 0;
  float sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0, syy = 0, syz = 0, szz = 0;

  void Add(const Eigen::Vector3f& p) {
    if (n == 0) ref = p;
    AddAboutRef(p);
  }

  // Adds a point about the reference already set (`ref`), even as the first point.
  void AddAboutRef(const Eigen::Vector3f& p) {
    const float x = p.x() - ref.x(), y = p.y() - ref.y(), z = p.z() - ref.z();
    ++n;
    sx += x;
    sy += y;
    sz += z;
    sxx += x * x;
    sxy += x * y;
    sxz += x * z;
    syy += y * y;
    syz += y * z;
    szz += z * z;
  }

  // These moments without `part`'s, taken about the same reference.
  LocalMoments Minus(const LocalMoments& part) const {
    LocalMoments m = *this;
    m.n -= part.n;
    m.sx -= part.sx;
    m.sy -= part.sy;
    m.sz -= part.sz;
    m.sxx -= part.sxx;
    m.sxy -= part.sxy;
    m.sxz -= part.sxz;
    m.syy -= part.syy;
    m.syz -= part.syz;
    m.szz -= part.szz;
    return m;
  }

  // Adds these moments, taken about `origin` instead, to double sums:
  // sum (o + q)(o + q)^T = n o o^T + o s^T + s o^T + S, with o = ref - origin. Only the lower
  // triangle of `sum_sq` is accumulated (the upper one stays as it was): the sums are symmetric,
  // and their reader mirrors it before use.
  void AddTo(const Eigen::Vector3f& origin, int* count, Eigen::Vector3d* sum,
             Eigen::Matrix3d* sum_sq) const {
    if (n == 0) return;
    const Eigen::Vector3f of = ref - origin;
    const double o[3] = {of.x(), of.y(), of.z()};
    const double s[3] = {sx, sy, sz};
    const double ss[3][3] = {{sxx, sxy, sxz}, {sxy, syy, syz}, {sxz, syz, szz}};
    *count += n;
    for (int i = 0; i < 3; ++i) {
      const double no = n * o[i];
      (*sum)(i) += no + s[i];
      // The terms in the order the expression n o o^T + o s^T + s o^T + S adds them.
      for (int j = 0; j <= i; ++j) {
        (*sum_sq)(i, j) += ((no * o[j] + o[i] * s[j]) + s[i] * o[j]) + ss[i][j];
      }
    }
  }
};

}  // namespace relplane::segmenter
