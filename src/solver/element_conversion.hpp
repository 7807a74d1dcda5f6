// Failed elements that become particles (the CFRP paper's section 3.1): each eroded element of a
// part whose erosion rule says `to_particles` turns into one particle per integration point, in
// the part's debris particle part ("<part>_particles", made on the first conversion). The
// particles take exactly the mass the nodes lose, and exactly their momentum; the nodes no
// element holds any more leave with the element. Everything happens in one remap (elements out,
// orphan nodes out, particles born). Theory: docs/theory/element_conversion.md.
#pragma once

#include <memory>
#include <vector>

#include "material/material.hpp"
#include "model/model.hpp"
#include "model/remap.hpp"

namespace shard {

/// What one conversion did.
struct ConversionResult {
  std::int64_t elements = 0;   ///< elements converted
  std::int64_t particles = 0;  ///< particles made
  double mass = 0;             ///< given to the particles (kg) = taken from the nodes
  double kinetic_taken = 0;    ///< ½ Σ Δm_a |v_a|² the nodes lost with that mass (J)
  double kinetic_given = 0;    ///< ½ Σ m_q |v_q|² of the new particles (J)
};

/// Per integration point q of an element type, the shape function values N_a(ξ_q) (points ×
/// nodes, row-major): where its particles sit and what velocity they take. Throws for a type
/// conversion does not know.
std::vector<double> conversion_point_weights(const ElementType& type);

/// The eroded elements of the converting parts become particles. Fills `remap` with the element
/// removals of every part with eroded elements (converted or not), the orphan nodes and the
/// born particles; the caller applies it, then calls finish_conversion. Particle parts it needs
/// are appended to the model first.
class ElementConversion {
 public:
  ConversionResult prepare(Model& model, const std::vector<std::unique_ptr<Material>>& materials, Remap& remap);
  /// After the remap: the new particles' positions, velocities, masses, radii and origins.
  void finish(Model& model);

 private:
  struct Born {
    int particle_part;
    double x[3], v[3], mass, radius, inertia;
    double ring_length;  ///< axisymmetric: 2π r of the ring (0 otherwise)
    std::int64_t element_id;
    int material;
  };
  std::vector<Born> born_;
  std::vector<std::size_t> first_new_;  ///< per particle part: its count before the remap
};

}  // namespace shard
