// The failure map: nodal failure factor and fracture direction, weighted averages of the
// integration points around each node (Cottrell, Yu, Wei & Owen 2003, eqs. 13–14). Crack
// insertion (fracture/crack_insertion.hpp) reads it. Theory: docs/theory/crack_insertion.md.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "model/model.hpp"

namespace shard {

/// The failure variables of one part's integration points, read in place: F of point q is
/// factor[stride·q], its fracture direction is direction[stride·q + k], k < dim. The direction
/// is the normal to the crack (the maximum principal, softening direction); its sign and length
/// do not matter. A part's own state gives factor = state + i_F, direction = state + i_n,
/// stride = state size (failure_field_from_state).
struct PointFailureField {
  const double* factor = nullptr;
  const double* direction = nullptr;  ///< null: the part gives no direction
  std::size_t stride = 1;
};

/// The view of `part.state` for a material whose state keeps F at `factor_index` and the first
/// direction component at `direction_index` (−1: none).
PointFailureField failure_field_from_state(const Part& part, int factor_index, int direction_index);

/// One part's contribution to the map.
struct PartFailureField {
  std::size_t part = 0;  ///< index into Model::parts
  PointFailureField field;
};

struct NodalFailureMap {
  std::vector<double> factor;     ///< F̄ per node; 0 where every adjacent point has F = 0
  std::vector<double> direction;  ///< dim per node: unit crack normal; 0 where F̄ = 0 or undefined
  std::vector<double> weight;     ///< Σ w per node; computed (non-zero) where F̄ is
  std::vector<char> active;       ///< 1 at the nodes next to a point with F ≠ 0 (the ones computed)
  /// Per node: Σ w F, Σ w and the upper triangle of Σ w n⊗n (the sums the values come from;
  /// kept so that a map reused every step allocates nothing).
  std::vector<double> sums;
};

/// Nodal failure factor F̄_p = Σ w_k F_k / Σ w_k over the integration points k of the live
/// (not eroded) elements that hold node p, with w_k the element's current area (2D, also
/// axisymmetric) or volume (3D) shared equally among its points. The direction is the same
/// weighted average taken on the axis tensor, N_p = Σ w_k n_k⊗n_k / Σ w_k with unit n_k, and
/// the nodal direction its major eigenvector: directions are axes (n ≡ −n), and a plain vector
/// average of n and −n would cancel. Sign: the largest component is made positive; an isotropic
/// N_p (no preferred axis) gives no direction. Nodes whose adjacent points all have F = 0 are
/// skipped (F̄ = 0, no direction, weight 0): the sums then cost in proportion to the damaged
/// region, after one sequential scan of the points.
NodalFailureMap nodal_failure_map(const Model& model, std::span<const PartFailureField> parts);
/// The same into `map`, reusing its storage (for a call every step).
void nodal_failure_map(const Model& model, std::span<const PartFailureField> parts, NodalFailureMap& map);

/// The largest F over the live points of a part. A node can fail only where a point has failed
/// (F̄ is a weighted mean), so a step whose parts all stay below 1 needs no map: this sequential
/// scan costs a small fraction of the map's scattered sums.
double max_point_factor(const Part& part, const PointFailureField& field);

/// The map of a single part.
NodalFailureMap nodal_failure_map(const Model& model, std::size_t part, const PointFailureField& field);

}  // namespace shard
