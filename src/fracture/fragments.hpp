// Fragments: the pieces a body has broken into, as connected components of its live elements
// through shared nodes and intact cohesive interface elements (union–find). Theory: docs/theory/crack_insertion.md, "Fragments".
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace shard {

struct Fragment {
  std::int32_t id = 0;
  /// The part its elements belong to. A fragment lies in one part unless parts are joined: two
  /// parts meshed as one conforming mesh share nodes, and two parts tied by a cohesive interface
  /// are held by it while it is intact. Then the names of the parts it spans, joined by '+' in
  /// the scenario's order. A debris particle: the part of the element it came from.
  std::string part;
  std::int64_t elements = 0;            ///< live elements
  double mass = 0;                      ///< Σ nodal lumped mass, each node once
  std::array<double, 3> centroid{};     ///< centre of mass Σ m x / Σ m (current positions)
  std::array<double, 3> velocity{};     ///< Σ m v / Σ m
  double kinetic_energy = 0;            ///< Σ ½ m v² over its nodes (translation and the rest)
  std::int64_t particles = 0;           ///< 1 for a debris particle (a comminuted or eroded element's), else 0
};

struct Fragments {
  std::vector<Fragment> list;  ///< ordered by id
  /// The fragment of every node, −1 for a node that no live element holds (such a node is in
  /// no fragment: it carries the mass of eroded elements, not a piece of the body).
  std::vector<std::int32_t> node_fragment;
  /// The fragment of every element, per part (−1: eroded).
  std::vector<std::vector<std::int32_t>> element_fragment;
};

/// The connected components of the live (not eroded) elements of all parts, joined through the
/// nodes they share and across every cohesive interface element that is not open and bounds two
/// live elements. Fragment ids are 0, 1, ... in order of each fragment's lowest element
/// (parts in order, elements in storage order), so they are the same in every run.
Fragments find_fragments(const Model& model);

/// The debris: each particle converted from an element (origin_element ≥ 0) as a fragment of
/// its own (elements 0, particles 1, its kinetic energy with its spin), ids from `first_id` on,
/// in particle part and storage order; its part is the one the particle part `<part>_particles`
/// holds the debris of.
std::vector<Fragment> debris_fragments(const Model& model, std::int32_t first_id);

/// Writes `fragments.csv`: id,part,elements,mass,centroid_x,centroid_y[,centroid_z],
/// velocity_x,velocity_y[,velocity_z],kinetic_energy,particles (SI units, full precision).
void write_fragments_csv(const std::filesystem::path& path, const std::vector<Fragment>& fragments, int dim);

}  // namespace shard
