// A particle sample as a file: the automata a sample builder made, with their places, sizes and
// materials (pores are the automata that are not there), so that a study runs the same sample
// again without replaying the builder's random draws. A run writes one per particle part
// (particles_<part>_sample.csv); `particles.<name>.sample` reads one back. Format:
// docs/outputs.md, "Particle samples".
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "particle/packing.hpp"

namespace shard {

struct ParticleSample {
  int dim = 2;
  Lattice lattice = Lattice::hexagonal_2d;
  double automaton_size = 0;  ///< d: with the lattice, the volume and contact area of every automaton
  /// The graded materials of an interphase, which the automata may name
  /// (<matrix>_interphase_<level>, level 0 next to the inclusion): made again from these.
  struct Interphase {
    std::string matrix, inclusion;
    int levels = 0;
  };
  std::optional<Interphase> interphase;
  std::vector<std::int64_t> id;             ///< within the part (a run adds the ids of the parts before)
  std::vector<double> x;                    ///< centres, dim per automaton (m)
  std::vector<double> radius;               ///< m
  std::vector<std::string> material_names;  ///< the names the automata use
  std::vector<int> material;                ///< per automaton, into material_names

  std::size_t count() const { return radius.size(); }
};

/// Writes the sample (through a temporary and a rename; OutputError when it cannot). `about`
/// goes into the first comment line (which part of which scenario).
void write_particle_sample(const std::filesystem::path& path, const ParticleSample& sample, const std::string& about);

/// Where a sample file is named in the scenario: errors in the file are reported there, with
/// the file's own line and column in the reason.
struct SampleReference {
  std::string scenario;  ///< the scenario file as shown
  int line = 0;          ///< of the `sample` key
  std::string key;       ///< particles.<name>.sample
  std::string shown;     ///< the sample file as the scenario names it
};

/// Reads a sample file of a `dim`-dimensional model. Every material an automaton names must be
/// one of `materials` (the scenario's automaton materials) or a level of the interphase the
/// file declares. Throws InputError at `where`.
ParticleSample read_particle_sample(const std::filesystem::path& path, int dim,
                                    const std::vector<std::string>& materials, const SampleReference& where);

}  // namespace shard
