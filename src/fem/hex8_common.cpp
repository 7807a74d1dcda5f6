#include "fem/hex8_common.hpp"

namespace shard {

/// Row sums of the consistent mass of trilinear hexahedra, ∫ρ N_a dV, by 2×2×2 Gauss (exact for
/// the trilinear map).
void lump_hex8_masses(const Part& part, const NodeArrays& nodes, double rho, double* mass) {
  const double* X = nodes.x.data();
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::int32_t* cn = &part.connectivity[8 * e];
    double x[8][3];
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) x[a][k] = X[3 * cn[a] + k];
    for (int p = 0; p < 8; ++p) {
      double J[3][3] = {};
      for (int a = 0; a < 8; ++a)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) J[r][c] += x[a][r] * kHex8Gauss.dN[p][a][c];
      const double det = determinant3(J);
      for (int a = 0; a < 8; ++a) mass[cn[a]] += rho * kHex8Gauss.N[p][a] * det;
    }
  }
}

/// The exact volume of a trilinear hexahedron, Σ_a x_a ∂V/∂x_a.
double hex8_measure(const Part& part, const NodeArrays& nodes, std::size_t e) {
  const std::int32_t* cn = &part.connectivity[8 * e];
  double x[8][3];
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k) x[a][k] = nodes.x[3 * cn[a] + k];
  double B[8][3];
  hex8_volume_gradient(x, B);
  double volume = 0.0;
  for (int a = 0; a < 8; ++a) volume += x[a][0] * B[a][0];
  return volume;
}

ElementType hexahedron(const char* name, const char* summary, int points) {
  ElementType t;
  t.name = name;
  t.summary = summary;
  t.dim = 3;
  t.nodes = 8;
  t.points = points;
  t.cell = CellType::hex8;
  t.vtk_cell = 12;
  t.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return t;
}

}  // namespace shard
