#include "fem/hex8_shape.hpp"

#include <cmath>
#include <stdexcept>

namespace shard {

namespace {

Hex8Reference make_reference() {
  Hex8Reference r{};
  const int xi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
  const int et[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
  const int ze[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  for (int a = 0; a < 8; ++a) {
    r.corner[a][0] = xi[a];
    r.corner[a][1] = et[a];
    r.corner[a][2] = ze[a];
    r.hourglass[0][a] = et[a] * ze[a];
    r.hourglass[1][a] = ze[a] * xi[a];
    r.hourglass[2][a] = xi[a] * et[a];
    r.hourglass[3][a] = xi[a] * et[a] * ze[a];
  }
  for (int al = 0; al < 4; ++al)
    for (int a = 0; a < 8; ++a)
      if (r.hourglass[al][a] != kHex8HourglassBase[al][a])
        throw std::logic_error("kHex8HourglassBase differs from the corner products");
  // V = Σ C_abc x_a y_b z_c with C_abc = ∫ det[∇ξN_a; ∇ξN_b; ∇ξN_c] dξ (C is antisymmetric);
  // the integrand is at most quadratic in each ξ, so 2×2×2 Gauss is exact. Each C is 0 or ±1/12.
  for (int a = 0; a < 8; ++a) {
    int count = 0;
    for (int b = 0; b < 8; ++b)
      for (int c = b + 1; c < 8; ++c) {
        double sum = 0;
        for (int p = 0; p < 8; ++p) {
          const double(*d)[3] = kHex8Gauss.dN[p];
          sum += d[a][0] * (d[b][1] * d[c][2] - d[b][2] * d[c][1]) -
                 d[a][1] * (d[b][0] * d[c][2] - d[b][2] * d[c][0]) +
                 d[a][2] * (d[b][0] * d[c][1] - d[b][1] * d[c][0]);
        }
        if (std::abs(sum) < 1e-9) continue;
        if (count == 9 || std::abs(std::abs(sum) * 12.0 - 1.0) > 1e-9)
          throw std::logic_error("hex8 volume table is not the expected one");
        r.volume_pairs[a][count++] = {b, c, sum > 0 ? 1.0 : -1.0};
      }
    if (count != 9) throw std::logic_error("hex8 volume table is not the expected one");
    for (int q = 0; q < 9; ++q) {
      const auto& c = kHex8VolumePairs[a][q];
      const auto& r2 = r.volume_pairs[a][q];
      if (c.j != r2.j || c.k != r2.k || c.sign != static_cast<int>(r2.sign))
        throw std::logic_error("kHex8VolumePairs differs from the integrated volume table");
    }
  }
  return r;
}

}  // namespace

const Hex8Reference& hex8_reference() {
  static const Hex8Reference reference = make_reference();
  return reference;
}

}  // namespace shard
