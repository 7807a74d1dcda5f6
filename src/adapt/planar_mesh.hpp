// What remeshing reads of a part of triangles: its bodies (pieces joined by shared nodes), their
// boundary loops traced through each node's fan of triangles (so a crack, whose lips hold
// different nodes, is part of the boundary, and a body pinched at one node keeps one loop per
// lobe), and the shape of each triangle (angles, area) for the distortion measures of the
// ceramics paper (Cottrell, Yu, Wei & Owen 2003, Eng. Computations 20, eqs. 1–2).
// Theory: docs/theory/adaptive_remeshing.md.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/model.hpp"

namespace shard {

/// The three corner angles (radians) of triangle (a, b, c) of 2D points.
std::array<double, 3> triangle_angles(const double* a, const double* b, const double* c);
/// Twice the signed area of triangle (a, b, c): positive when counter-clockwise.
inline double twice_area(const double* a, const double* b, const double* c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}

/// The bodies of a part: its live (not eroded) elements grouped by shared nodes, each body's
/// elements in increasing order, bodies ordered by their first element.
std::vector<std::vector<std::int32_t>> bodies_of(const Part& part);

/// A closed boundary loop: model nodes in order, the body on the left (counter-clockwise around an
/// outer boundary, clockwise around a hole). Twice its signed area on the current positions.
struct BoundaryLoop {
  std::vector<std::int32_t> nodes;
  double twice_area = 0;
  bool outer() const { return twice_area > 0; }
};

/// The boundary loops of the listed elements of a part of triangles, in a fixed order (by their
/// first edge, in element order). An edge is on the boundary when no other listed element has it
/// the other way round: a crack's lips, which hold distinct copies of its nodes, are boundary.
std::vector<BoundaryLoop> boundary_loops(const Part& part, const std::vector<std::int32_t>& elements,
                                         const NodeArrays& nodes);

/// The shape a distortion is measured against: the area and the three angles of each element,
/// per element [A, α1, α2, α3].
void measure_reference_shape(const Part& part, const NodeArrays& nodes, std::vector<double>& reference);

/// The distortion of each element against its reference shape (eqs. 1–2 of the ceramics paper):
/// the relative change of its area |A − A0|/A0, or, where larger, the largest relative change of a
/// corner angle |α − α0|/α0 (a shear keeps the area). An element with no reference yet reads 0.
struct ElementDistortion {
  double area = 0;   ///< |A − A0|/A0
  double angle = 0;  ///< max over corners |α − α0|/α0
  double value() const { return area > angle ? area : angle; }
};
ElementDistortion element_distortion(const Part& part, const NodeArrays& nodes, std::size_t element);

/// The equilateral edge length of a triangle of area A: the size a mesher aims at, sqrt(4A/√3).
double equilateral_size(double area);

/// The first row of the inverse of a symmetric 3 × 3 matrix (the normal equations of a linear fit
/// a + b x + c y: the row that gives a), or false where M is singular to within `tolerance` of
/// M00³ (the points of the fit on a line).
bool first_row_of_inverse(const double M[3][3], double row[3], double tolerance);

}  // namespace shard
