// Reference data of the trilinear 8-node hexahedron (node order of Gmsh and VTK: 0–3 the face
// ζ = −1 counter-clockwise from (−1,−1,−1), 4–7 the face ζ = +1).
#pragma once

namespace shard {

struct Hex8Reference {
  double corner[8][3];          ///< (ξ, η, ζ) of each node
  double gauss_dN[8][8][3];     ///< ∂N_a/∂ξ at the 2×2×2 Gauss points (weights 1)
  double gauss_N[8][8];         ///< N_a at the Gauss points
  double hourglass[4][8];       ///< Γ vectors ηζ, ζξ, ξη, ξηζ (Flanagan & Belytschko 1981)
  /// ∂V/∂x_a = Σ_p s_p (y_j z_k − y_k z_j) / 12 over 9 node pairs (j, k) per node: the closed
  /// form of the exact volume derivative, found by integrating the triple products of
  /// ∂N/∂ξ (so exact for any trilinear hexahedron).
  struct Pair {
    int j, k;
    double sign;
  } volume_pairs[8][9];
};

const Hex8Reference& hex8_reference();

/// B[a] = ∂V/∂x_a (exact). B̄ = B/V is the uniform gradient; V = Σ_a x_a B[a][0].
inline void hex8_volume_gradient(const double x[8][3], double B[8][3]) {
  const auto& pairs = hex8_reference().volume_pairs;
  for (int a = 0; a < 8; ++a) {
    double bx = 0, by = 0, bz = 0;
    for (const auto& p : pairs[a]) {
      const double* u = x[p.j];
      const double* w = x[p.k];
      bx += p.sign * (u[1] * w[2] - w[1] * u[2]);
      by += p.sign * (u[2] * w[0] - w[2] * u[0]);
      bz += p.sign * (u[0] * w[1] - w[0] * u[1]);
    }
    B[a][0] = bx / 12.0;
    B[a][1] = by / 12.0;
    B[a][2] = bz / 12.0;
  }
}

}  // namespace shard
