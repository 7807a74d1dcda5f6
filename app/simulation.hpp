// From a validated scenario and its mesh to a ready Model, materials and loads.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "contact/contact.hpp"
#include "io/gmsh_import.hpp"
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
  std::optional<CrackGrowth> crack_growth;      ///< built from `cracking`; attach it to the solver

  std::vector<int> part_materials() const;
};

/// Loads (or meshes) the scenario's mesh. Throws InputError naming the scenario line for bad
/// mesh files.
MeshData load_scenario_mesh(const Scenario& scenario);

/// Builds the simulation. Throws InputError (scenario file, line, key) when the scenario and
/// the mesh disagree: unknown physical group, wrong cell type for the element, ...
/// Fills derived values (element kinds chosen from the mesh) into scenario.resolved.
Simulation build_simulation(Scenario& scenario, const MeshData& mesh);

}  // namespace shard
