// From a validated scenario and its mesh to a ready Model, materials and loads.
#pragma once

#include <map>

#include <memory>
#include <optional>
#include <vector>

#include "adapt/remesh_event.hpp"
#include "contact/contact.hpp"
#include "io/gmsh_import.hpp"
#include "io/particle_sample.hpp"
#include "io/scenario.hpp"
#include "material/material.hpp"
#include "model/model.hpp"
#include "solver/crack_growth.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/loads.hpp"

namespace shard {

struct Simulation {
  Model model;
  std::vector<std::unique_ptr<Material>> materials;
  Loads loads;
  SolverSettings settings;
  std::optional<ContactSettings> contact;  ///< contact between parts and/or rigid walls
  std::optional<ContactSystem> contact_system;  ///< built from `contact`; attach it to the solver
  std::optional<CrackGrowthSettings> cracking;  ///< discrete crack insertion
  /// Contact of particles with each other and the walls (from `particle_contact`).
  std::unique_ptr<ParticleContact> particle_contact;
  /// Cohesive interfaces (from `interfaces`); null without.
  std::unique_ptr<CohesiveInterfaces> cohesive;
  /// The step events the scenario asks for beyond the solver's own (crack growth).
  std::vector<std::unique_ptr<StepEvent>> events;
  /// The ply of every element of each laminate part (by part name; element order of set-up).
  std::map<std::string, std::vector<int>> plies;
  /// The probes (`probes`): a name, an interval, and the stable ids of the nodes they average.
  struct Probe {
    std::string name;
    double interval = 0;
    std::vector<std::int64_t> nodes;
  };
  std::vector<Probe> probes;
  /// Each particle part of the scenario as built, by part name: what a run writes at t = 0 as
  /// particles_<part>_sample.csv (taken before a restart moves the automata).
  std::map<std::string, ParticleSample> samples;

  std::vector<int> part_materials() const;
  /// The step event of type Event (crack growth, remeshing, the automata's contact update), if
  /// the scenario has one.
  template <class Event>
  Event* find_event() {
    for (auto& e : events)
      if (auto* found = dynamic_cast<Event*>(e.get())) return found;
    return nullptr;
  }
  CrackGrowth* crack_growth() { return find_event<CrackGrowth>(); }
  RemeshEvent* remeshing() { return find_event<RemeshEvent>(); }
};

/// The solver of a simulation, with its contact and events attached.
std::unique_ptr<ExplicitSolver> make_solver(Simulation& sim);

/// The scenario file as the person named it on the command line, so that errors found after
/// reading read like those of the scenario reader ("bar.yaml:12: ..."). Scenario::file is
/// absolute: made from the current directory and the given path, which is recovered when it was
/// relative.
std::string shown_path(const std::filesystem::path& file);

/// Loads (or meshes) the scenario's mesh. Throws InputError naming the scenario line for bad
/// mesh files.
MeshData load_scenario_mesh(const Scenario& scenario);

/// Builds the simulation. Throws InputError (scenario file, line, key) when the scenario and
/// the mesh disagree: unknown physical group, wrong cell type for the element, ...
/// Fills derived values (element kinds chosen from the mesh) into scenario.resolved.
Simulation build_simulation(Scenario& scenario, const MeshData& mesh);

}  // namespace shard
