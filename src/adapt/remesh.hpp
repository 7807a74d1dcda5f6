// A remesh of one part of triangles: the largest topology change there is. The part's current
// boundary (crack lips included) is resampled to the size field and meshed again by Gmsh, and
// every field of the old mesh is carried to the new one through the remap
// (src/model/remap.hpp): velocities and reference positions by barycentric weights,
// integration-point state by moving least squares (src/adapt/transfer.hpp). What the remap's
// generic rules cannot know is then set here: positions, crack lineage, prescribed motion and
// node sets on the new boundary, facet sets, contact history, lumped masses restored per body,
// linear momentum restored per body, and each material's own consistency (after_transfer).
// Theory and the rules: docs/theory/adaptive_remeshing.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "adapt/size_field.hpp"
#include "adapt/transfer.hpp"
#include "adapt/triangulate.hpp"
#include "material/material.hpp"
#include "model/model.hpp"
#include "model/remap.hpp"

namespace shard {

struct RemeshSettings {
  SizeRule size;
  PointTransfer transfer = PointTransfer::least_squares;
  /// Gmsh's Delaunay is 1.3 times as fast as its Frontal-Delaunay for the same smallest angle
  /// (bench/bench_remesh); the frontal one makes more regular triangles.
  MeshAlgorithm algorithm = MeshAlgorithm::delaunay;
  /// Laplacian smoothing passes of Gmsh's mesh. Each lifts the worst triangles, which set the
  /// explicit step (a Taylor bar remeshed every 100 steps took 830 steps to 10 µs without, 700
  /// with one, 540 on its structured mesh), but costs 0.3 s for 30 000 triangles, and moves the
  /// new nodes further from the old ones (a wave loses more energy in the transfer).
  int smoothing = 0;
  /// Keep the elements with a node on a crack face as they are, and remesh only the material
  /// around them: Gmsh then never meshes between lips (which are kept node for node and would give
  /// it thin triangles there), and a cracked zone keeps the elements it cracked in.
  bool keep_cracked = false;
  /// A boundary node where the boundary turns by more than this (radians) is kept as a corner.
  double feature_angle = 0.5235987755982988;  // 30°
  /// A boundary node is dropped (coarsening) only if the nodes dropped between two kept ones lie
  /// within this fraction of the chord from it (keeps the area of curved boundaries).
  double chord_tolerance = 0.002;
};

/// What a remesh did (or why it did not).
struct RemeshOutcome {
  bool remeshed = false;
  std::string skipped;  ///< why the part was left as it was (remeshed false)
  std::size_t elements_before = 0, elements_after = 0, nodes_before = 0, nodes_after = 0;
  std::size_t bodies = 0;
  /// Where a body's boundary crosses itself (lips pressed into each other, a fragment folded
  /// over), which Gmsh cannot mesh, or where a closed crack's lips turn a new triangle over or
  /// Gmsh makes a sliver, a patch of its elements around the place is kept as it was (or the whole
  /// body, if the patch would hold most of it): how many such patches, and elements.
  std::size_t bodies_kept = 0, elements_kept = 0;
  /// Small fragments (fewer than 16 elements) kept whole, as they were.
  std::size_t fragments_kept = 0;
  /// With RemeshSettings::keep_cracked: the elements kept because they touch a crack face (and
  /// uncracked pieces of fewer than 16 elements between them).
  std::size_t cracked_kept = 0;
  double area_before = 0, area_after = 0;      ///< of the part (m²)
  double mass_before = 0, mass_after = 0;      ///< of the part's nodes (kg)
  std::array<double, 2> momentum_before{0, 0}, momentum_after{0, 0};
  double kinetic_before = 0, kinetic_after = 0;  ///< ½ m v² of the part's nodes at the half step
  double stored_before = 0, stored_after = 0;    ///< Σ ψ V of its points
  double min_angle = 0;                          ///< smallest corner angle of the new mesh (rad)
  MeshAlgorithm algorithm = MeshAlgorithm::frontal_delaunay;  ///< the one that succeeded
  int attempts = 0;
  /// Wall-clock seconds of its phases: size field and new boundary; Gmsh; locating and weights;
  /// applying the remap and what follows it.
  double seconds_boundary = 0, seconds_gmsh = 0, seconds_transfer = 0, seconds_apply = 0;
};

/// Remeshes part `part` (triangles; its elements must not be eroded, and it must not share nodes
/// with another part) and applies the change to every field of the model. Nodes whose ids are in
/// `kept_nodes` (probes) stay. On success `remap` is the change for the topology listeners (an
/// empty Remap: everything may have changed); on failure the model is unchanged and the outcome
/// says why.
RemeshOutcome remesh_part(Model& model, std::size_t part, const Material& material, const RemeshSettings& settings,
                          const std::vector<std::int64_t>& kept_nodes);

/// The patch a local remesh replaces around `seeds` (elements of part `part`): the seeds and
/// `rings` rings of elements sharing a node with it (in element order), none that would give the
/// patch a second copy of a crack node (the other lip). Empty when the seeds themselves hold
/// both lips of a crack.
std::vector<std::int32_t> grow_patch(const Model& model, std::size_t part, const std::vector<std::int32_t>& seeds,
                                     int rings);

/// Remeshes a patch of part `part` (element indices; it may reach a crack from one side, its
/// lip kept node for node, but not hold both lips): the patch's
/// boundary nodes stay, node for node, so the elements outside it fit the new ones unchanged; its
/// inner nodes and elements are made again by Gmsh against the size rule and take their state
/// from the old patch as remesh_part's do. The nodes of the patch keep its mass (to round-off)
/// and linear momentum. The outcome's counts and sums are the patch's (its area and stored energy
/// the part's). A new mesh with an angle below `min_angle` (rad) is refused: a patch keeps its
/// boundary's short edges, which the whole-part remesh would coarsen. On failure the model is
/// unchanged.
RemeshOutcome remesh_patch(Model& model, std::size_t part, const Material& material, const RemeshSettings& settings,
                           const std::vector<std::int32_t>& patch, const std::vector<std::int64_t>& kept_nodes,
                           double min_angle = 0);

/// The elastic energy the points of a part store, Σ ψ V (ψ the material's stored energy per unit
/// volume, or p²/2K + s:s/4G of the stress).
double stored_energy(const Part& part, const Material& material, const NodeArrays& nodes, Formulation formulation,
                     double thickness);

}  // namespace shard
