// A finite speed for discrete cracks: which failed nodes may split now. Without it a node splits
// as soon as its nodal failure factor reaches the threshold, so a crack is drawn as fast as the
// material fails, and behind a stress wave that is the wave's speed. With it (docs/theory/
// crack_insertion.md, "A limit on the tip speed"):
//   - a node a crack has reached (crack_time t_p) opens its next edge only once the tip could
//     have crossed its longest edge at the limit: v_max (t − t_p) ≥ max |x_r − x_p|;
//   - a node no crack has reached starts a crack of its own (a nucleation) only if no crack node,
//     and no nucleus accepted in the same update, lies within the nucleation spacing of it: a
//     crack unloads the material around it, and new cracks start outside that zone (the
//     obscuration of Denoual & Hild 2000, Comput. Methods Appl. Mech. Eng. 183); with a seeded
//     field of weakest flaws, the candidates of one update are taken weakest flaw first.
// It acts on the nodal factor before the planner reads it, and so holds back the drawing of the
// crack, not the material: with a softening model the smeared band still fails ahead of a held
// tip; with fragmentation damage (denoual_forquin_hild) the damage carries the crack density and
// the discrete cracks are the macro-cracks that run at the limit.
#pragma once

#include <cstddef>
#include <span>

#include "fracture/crack_insertion.hpp"
#include "model/model.hpp"

namespace shard {

struct CrackSpeedLimit {
  double tip_speed = 0;  ///< v_max (m/s); 0: no limit (every failed node splits at once)
  /// A nucleus needs no crack node nearer than this (m; at least its longest edge); 0: three
  /// times its longest edge.
  double nucleation_spacing = 0;
};

/// How many failed nodes the limit held back, by rule.
struct HeldNodes {
  std::size_t tips = 0;    ///< crack nodes whose next edge the tip cannot have crossed yet
  std::size_t nuclei = 0;  ///< uncracked nodes too near a crack or an earlier nucleus
};

/// Sets to 0 the factor of the failed nodes (nodal_factor ≥ threshold) that may not split at
/// `time` under `limit`, in the planner's order (largest factor first, then lowest id), so that
/// which nuclei are accepted does not depend on threads; where a cracking part has a seeded
/// field of weakest flaws (CrackingPart::weakest_flaw_index), the candidates are taken weakest
/// flaw first (the least over the elements around the node), the planner's order breaking ties.
/// Edges are those of the live triangles of cracking parts; distances are in the current
/// configuration. The spacing is never less than a candidate's longest edge, so no nucleus opens
/// an edge onto a crack. A candidate without a crack direction (`nodal_normal`, 2 per node, zero)
/// is left to the planner, which skips it, and keeps no other from starting.
HeldNodes hold_back_cracks(const Model& model, std::span<const CrackingPart> parts, const CrackSpeedLimit& limit,
                           double time, double threshold, std::span<const double> nodal_normal,
                           std::span<double> nodal_factor);

/// In parts whose damage does not heal when a crack passes (CrackingPart::heals false), the
/// nodes a crack already passes through (split into copies) stay failed for good, and each would
/// open a branch from the crack's faces at every update until the damaged zone is cut into
/// single triangles: there only the tips extend. Sets to 0 the factor of such failed nodes;
/// returns how many.
std::size_t keep_to_crack_tips(const Model& model, std::span<const CrackingPart> parts, double threshold,
                               std::span<double> nodal_factor);

}  // namespace shard
