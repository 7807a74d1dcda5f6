// The element size a remesh aims at (docs/theory/adaptive_remeshing.md, "Size prediction"):
//   - from a piecewise-linear table of a measure per element: the effective total strain rate
//     (the ceramics paper's choice for brittle material, tables IV–IX of Cottrell, Yu, Wei & Owen
//     2003, Eng. Computations 20) or the equivalent inelastic strain (its choice for metals);
//   - or from the Zienkiewicz–Zhu energy-norm error with stresses recovered by superconvergent
//     patch recovery (Zienkiewicz & Zhu 1992, IJNME 33; eqs. 3–8 of the ceramics paper);
//   - or uniform;
// then bounded by h_min and h_max, by how much one remesh may refine or coarsen, graded so that
// neighbouring sizes differ by at most a slope, and scaled up if the mesh would exceed an element
// budget (Abaqus's adaptive remeshing rules work the same way).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "adapt/transfer.hpp"
#include "material/material.hpp"
#include "model/model.hpp"

namespace shard {

enum class SizeMeasure : std::uint8_t { uniform, strain_rate, inelastic_strain, error };

const char* name_of(SizeMeasure measure);

struct SizeRule {
  SizeMeasure measure = SizeMeasure::uniform;
  /// (measure value, size) pairs, values increasing: the size is linear between them and constant
  /// beyond the ends (strain_rate in 1/s, inelastic_strain dimensionless).
  std::vector<std::array<double, 2>> table;
  double error_target = 0.05;  ///< η̄: the relative energy-norm error aimed at (error)
  double uniform_size = 0;     ///< the size of a uniform rule (0: the part's sizes as they are)
  double h_min = 0, h_max = 0; ///< bounds (0: none)
  double max_refinement = 4;   ///< one remesh makes an element at most this much smaller
  double max_coarsening = 2;   ///< … and at most this much larger
  std::int64_t max_elements = 0;  ///< budget of the part's new mesh (0: none)
  double gradation = 0.3;      ///< the size grows by at most this much per unit distance
  /// Refine ahead (m): an element takes the smallest size asked for within this distance of it
  /// along the mesh, so that a wave arriving before the next assessment finds the mesh already
  /// fine (0: each element its own).
  double refine_ahead = 0;
};

/// The size measure and target of each listed element, and its size now (equilateral edge of its
/// area).
struct ElementSizes {
  std::vector<double> current, measure, target;
};

/// The size-table lookup: linear between points, constant beyond the ends.
double size_from_table(const SizeRule& rule, double value);

/// Each listed element's target becomes the smallest target of the listed elements within
/// `reach` of it, the distance measured from centroid to centroid across shared nodes; the others'
/// targets rounded down to steps of 2^(1/8), and taken only if a step or more below its own.
void spread_smallest_sizes(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                           std::vector<double>& target, double reach);

/// Effective total strain rate sqrt(2/3 D:D) of a triangle from its nodes' velocities (the hoop
/// rate v_r/r in axisymmetry).
double effective_strain_rate(const Part& part, const NodeArrays& nodes, std::size_t element, Formulation formulation);

/// Per listed element: its measure and the size the rule asks for, bounded (before grading).
ElementSizes element_target_sizes(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                                  const Material& material, Formulation formulation, const SizeRule& rule);

/// Zienkiewicz–Zhu error per listed element ‖e‖_k (energy norm, J^½) with the stresses recovered
/// by superconvergent patch recovery at the nodes, and ‖σ‖² over them; the relative error η.
struct EnergyNormError {
  std::vector<double> element;  ///< ‖e‖_k
  double error_squared = 0, stress_squared = 0;
  double relative() const;
};
EnergyNormError energy_norm_error(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                                  const ElasticModuli& moduli, Formulation formulation, double thickness);

/// The size at each node of the listed elements (indexed by model node; 0 elsewhere): the
/// smallest target of the elements around it, graded across edges, within the element budget.
std::vector<double> nodal_sizes(const Part& part, const std::vector<std::int32_t>& elements, const NodeArrays& nodes,
                                const ElementSizes& sizes, const SizeRule& rule);

/// The size field of an old mesh at any point: its nodal sizes interpolated in the triangle that
/// holds the point (or the nearest).
class SizeField {
 public:
  SizeField(const TriangleLocator& mesh, const std::vector<double>& node_size) : mesh_(mesh), size_(node_size) {}
  double at(const double* p) const;

 private:
  const TriangleLocator& mesh_;
  const std::vector<double>& size_;
};

}  // namespace shard
