// Reference data of the trilinear 8-node hexahedron (node order of Gmsh and VTK: 0–3 the face
// ζ = −1 counter-clockwise from (−1,−1,−1), 4–7 the face ζ = +1).
#pragma once

namespace shard {

struct Hex8Reference {
  double corner[8][3];          ///< (ξ, η, ζ) of each node
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

/// The node pairs of ∂V/∂x_a as compile-time constants (so the kernel unrolls with fixed
/// indices); hex8_reference() recomputes them by integration and refuses to start if they differ.
struct Hex8VolumePair {
  int j, k, sign;
};
inline constexpr Hex8VolumePair kHex8VolumePairs[8][9] = {
    {{1, 2, -1}, {1, 3, -1}, {1, 4, 1}, {1, 5, 1}, {2, 3, -1}, {3, 4, -1}, {3, 7, -1}, {4, 5, -1}, {4, 7, 1}},
    {{0, 2, 1}, {0, 3, 1}, {0, 4, -1}, {0, 5, -1}, {2, 3, -1}, {2, 5, 1}, {2, 6, 1}, {4, 5, -1}, {5, 6, -1}},
    {{0, 1, -1}, {0, 3, 1}, {1, 3, 1}, {1, 5, -1}, {1, 6, -1}, {3, 6, 1}, {3, 7, 1}, {5, 6, -1}, {6, 7, -1}},
    {{0, 1, -1}, {0, 2, -1}, {0, 4, 1}, {0, 7, 1}, {1, 2, -1}, {2, 6, -1}, {2, 7, -1}, {4, 7, 1}, {6, 7, -1}},
    {{0, 1, 1}, {0, 3, -1}, {0, 5, 1}, {0, 7, -1}, {1, 5, 1}, {3, 7, -1}, {5, 6, 1}, {5, 7, 1}, {6, 7, 1}},
    {{0, 1, 1}, {0, 4, -1}, {1, 2, 1}, {1, 4, -1}, {1, 6, 1}, {2, 6, 1}, {4, 6, -1}, {4, 7, -1}, {6, 7, 1}},
    {{1, 2, 1}, {1, 5, -1}, {2, 3, 1}, {2, 5, -1}, {2, 7, 1}, {3, 7, 1}, {4, 5, 1}, {4, 7, -1}, {5, 7, -1}},
    {{0, 3, -1}, {0, 4, 1}, {2, 3, 1}, {2, 6, -1}, {3, 4, 1}, {3, 6, -1}, {4, 5, 1}, {4, 6, 1}, {5, 6, 1}}

};

/// Shape functions and their ξ-derivatives at the 2×2×2 Gauss points (points in the node
/// order, weights 1), as compile-time constants so that the kernels fold them into code.
struct Hex8GaussTable {
  double N[8][8];      ///< N[p][a]
  double dN[8][8][3];  ///< ∂N_a/∂ξ at point p
};
constexpr Hex8GaussTable make_hex8_gauss_table() {
  constexpr int xi[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
  constexpr int et[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
  constexpr int ze[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  constexpr double g = 0.57735026918962576451;  // 1/√3
  Hex8GaussTable t{};
  for (int p = 0; p < 8; ++p) {
    const double s = g * xi[p], u = g * et[p], w = g * ze[p];
    for (int a = 0; a < 8; ++a) {
      t.N[p][a] = (1 + xi[a] * s) * (1 + et[a] * u) * (1 + ze[a] * w) / 8.0;
      t.dN[p][a][0] = xi[a] * (1 + et[a] * u) * (1 + ze[a] * w) / 8.0;
      t.dN[p][a][1] = et[a] * (1 + xi[a] * s) * (1 + ze[a] * w) / 8.0;
      t.dN[p][a][2] = ze[a] * (1 + xi[a] * s) * (1 + et[a] * u) / 8.0;
    }
  }
  return t;
}
inline constexpr Hex8GaussTable kHex8Gauss = make_hex8_gauss_table();

/// Hourglass base vectors Γ (ηζ, ζξ, ξη, ξηζ at the nodes) as compile-time constants; equal to
/// Hex8Reference::hourglass (checked at start-up).
inline constexpr double kHex8HourglassBase[4][8] = {{1, 1, -1, -1, -1, -1, 1, 1},
                                                    {1, -1, -1, 1, -1, 1, 1, -1},
                                                    {1, -1, 1, -1, 1, -1, 1, -1},
                                                    {-1, 1, -1, 1, 1, -1, 1, -1}};

/// B[a] = ∂V/∂x_a (exact). B̄ = B/V is the uniform gradient; V = Σ_a x_a B[a][0].
inline void hex8_volume_gradient(const double x[8][3], double B[8][3]) {
#pragma GCC unroll 8
  for (int a = 0; a < 8; ++a) {
    double bx = 0, by = 0, bz = 0;
#pragma GCC unroll 9
    for (const auto& p : kHex8VolumePairs[a]) {
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
