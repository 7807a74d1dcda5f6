#include "core/principal.hpp"

#include <algorithm>
#include <cmath>

#include "core/voigt.hpp"

namespace shard {

void from_principal(const double value[3], const double vector[3][3], double* t) {
  for (int k = 0; k < kTensorSize; ++k) t[k] = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double* n = vector[i];
    t[xx] += value[i] * n[0] * n[0];
    t[yy] += value[i] * n[1] * n[1];
    t[zz] += value[i] * n[2] * n[2];
    t[xy] += value[i] * n[0] * n[1];
    t[yz] += value[i] * n[1] * n[2];
    t[zx] += value[i] * n[2] * n[0];
  }
}

void principal(const double* t, double value[3], double vector[3][3]) {
  if (t[yz] == 0.0 && t[zx] == 0.0) {
    const double mean = 0.5 * (t[xx] + t[yy]), half = 0.5 * (t[xx] - t[yy]);
    const double radius = std::hypot(half, t[xy]);
    const double theta = 0.5 * std::atan2(t[xy], half);
    const double c = std::cos(theta), s = std::sin(theta);
    double v[3][3] = {{c, s, 0}, {-s, c, 0}, {0, 0, 1}};
    double d[3] = {mean + radius, mean - radius, t[zz]};
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int a, int b) { return d[a] > d[b]; });
    for (int i = 0; i < 3; ++i) {
      value[i] = d[order[i]];
      for (int k = 0; k < 3; ++k) vector[i][k] = v[order[i]][k];
    }
    return;
  }
  double a[3][3] = {{t[xx], t[xy], t[zx]}, {t[xy], t[yy], t[yz]}, {t[zx], t[yz], t[zz]}};
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // columns: eigenvectors
  const double scale = std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2]) +
                       std::abs(a[0][1]) + std::abs(a[1][2]) + std::abs(a[0][2]);
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = std::abs(a[0][1]) + std::abs(a[1][2]) + std::abs(a[0][2]);
    if (off <= 1e-16 * scale) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // Rotation that zeroes a[p][q] (Golub & Van Loan, algorithm 8.4.1).
        const double tau = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double tt = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
        const double c = 1.0 / std::sqrt(1.0 + tt * tt), s = tt * c;
        for (int k = 0; k < 3; ++k) {  // A ← A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A ← Jᵀ A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // V ← V J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int i, int j) { return a[i][i] > a[j][j]; });
  for (int i = 0; i < 3; ++i) {
    value[i] = a[order[i]][order[i]];
    for (int k = 0; k < 3; ++k) vector[i][k] = v[k][order[i]];
  }
}

double major_principal(const double* t) {
  if (t[yz] == 0.0 && t[zx] == 0.0)
    return std::max(0.5 * (t[xx] + t[yy]) + std::hypot(0.5 * (t[xx] - t[yy]), t[xy]), t[zz]);
  const double p1 = t[xy] * t[xy] + t[yz] * t[yz] + t[zx] * t[zx];
  const double q = (t[xx] + t[yy] + t[zz]) / 3.0;
  const double dx = t[xx] - q, dy = t[yy] - q, dz = t[zz] - q;
  const double p = std::sqrt((dx * dx + dy * dy + dz * dz + 2.0 * p1) / 6.0);
  if (!(p > 0.0)) return q;
  const double bxx = dx / p, byy = dy / p, bzz = dz / p, bxy = t[xy] / p, byz = t[yz] / p, bzx = t[zx] / p;
  const double det = bxx * (byy * bzz - byz * byz) - bxy * (bxy * bzz - byz * bzx) + bzx * (bxy * byz - byy * bzx);
  const double phi = std::acos(std::clamp(0.5 * det, -1.0, 1.0)) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

}  // namespace shard
