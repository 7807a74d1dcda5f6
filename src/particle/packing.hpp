// Sample builders for MCA: close-packed lattices of a box (optionally rotated, for isotropy
// checks), materials by region, random equiaxed inclusions, pores, graded interphase zones.
// Random choices use std::mt19937_64 with an explicit seed and our own mapping to [0, 1), so a
// sample is the same on every platform.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "particle/mca_state.hpp"

namespace shard {

enum class Lattice { hexagonal_2d, square_2d, fcc, simple_cubic };

struct PackingSpec {
  Lattice lattice = Lattice::fcc;
  double size = 1e-3;               ///< automaton size d (nearest-neighbour distance), m
  double lo[3] = {0, 0, 0};         ///< box corners (2D: z ignored)
  double hi[3] = {1e-2, 1e-2, 1e-2};
  double angle = 0;                 ///< lattice rotated about z by this angle (rad)
  PlaneMode plane = PlaneMode::plane_strain;  ///< 2D only
  double thickness = 1;             ///< 2D only, m
  int material = 0;
  double bond_tolerance = 0.1;      ///< neighbours within (1 + tol) d are bonded
};

/// A particle part of automata (an MCA state) on the lattice points inside the box, with the
/// volume and face area of the lattice's Voronoi cell. No pairs yet: call finish_sample() after
/// materials, pores etc.
ParticlePart build_packing(const PackingSpec& spec, std::vector<MCAMaterial> materials);

/// The scenario's name of a lattice ("hexagonal", "square", "fcc", "simple_cubic").
const char* lattice_name(Lattice lattice);

/// Automata at the given centres (dim per automaton) and radii, ids and materials, each with the
/// volume and face area of the lattice's Voronoi cell of `spec.size`, as build_packing gives its
/// sites: a sample read back from a file. No pairs yet: call finish_sample().
ParticlePart place_automata(const PackingSpec& spec, std::vector<MCAMaterial> materials, std::vector<double> x,
                            const std::vector<double>& radius, const std::vector<std::int64_t>& id,
                            const std::vector<int>& material);

/// Bonds neighbours, computes the fabric and finalizes (masses, pair laws, adjacency).
void finish_sample(ParticlePart& ps, double bond_tolerance = 0.1);

/// Material `material` for every automaton whose centre satisfies `inside`.
void assign_material(ParticlePart& ps, const std::function<bool(const double*)>& inside, int material);

/// Uniform number in [0, 1) from the top 53 bits of a 64-bit draw (portable).
double uniform01(std::mt19937_64& rng);

struct InclusionSpec {
  int material = 1;
  double volume_fraction = 0.5;  ///< of the automata
  double diameter = 3e-6;        ///< equiaxed (spherical / circular) inclusions
  std::uint64_t seed = 1;
  int max_tries = 100000;
};
/// Places non-overlapping inclusions at random until the fraction of inclusion automata reaches
/// the target, or max_tries draws have been made; returns the number of inclusions, and in
/// `fraction` (when given) the fraction of the automata that are of the inclusion material then.
int add_inclusions(ParticlePart& ps, const InclusionSpec& spec, double* fraction = nullptr);

struct PoreSpec {
  double porosity = 0.1;        ///< fraction of automata removed
  bool with_neighbours = false;  ///< remove an automaton and its nearest neighbours (larger pore)
  std::uint64_t seed = 1;
};
/// Removes automata at random (before bonding); returns the number of pores made.
int add_pores(ParticlePart& ps, const PoreSpec& spec);

struct InterphaseSpec {
  int inclusion_material = 1, matrix_material = 0;
  double width = 1e-6;  ///< matrix automata closer than this (gap between cells) grade
  int levels = 3;       ///< number of graded materials
};
/// Matrix automata within `width` of an inclusion automaton get graded materials (properties
/// linear from inclusion to matrix over the width). Bond laws of the graded materials copy the
/// matrix–inclusion law, or the matrix law. Returns the number of automata changed.
int add_interphase(ParticlePart& ps, const InterphaseSpec& spec);

/// The graded materials of an interphase (named <matrix>_interphase_<level>, appended to the
/// part's materials) and their bond laws, without choosing automata: what add_interphase adds,
/// for a sample whose automata already name their levels. Returns the index of level 0.
int add_interphase_materials(ParticlePart& ps, const InterphaseSpec& spec);

/// Automata whose coordinate `axis` is within `tol` of the extreme (min or max) of the sample.
std::vector<int> boundary_layer(const ParticlePart& ps, int axis, bool at_max, double tol);

}  // namespace shard
