#include "app/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <tuple>
#include <sstream>

#include "app/crack_band_check.hpp"
#include "core/disjoint_sets.hpp"
#include "core/error.hpp"
#include "model/assembly.hpp"
#include "particle/mca_contact_update.hpp"
#include "particle/packing.hpp"
#include "io/particle_sample.hpp"
#include "solver/element_conversion.hpp"
#include "fracture/interface_split.hpp"
#include "material/denoual_forquin_hild.hpp"
#include "material/laminate.hpp"
#include "solver/setup.hpp"

namespace shard {

std::string shown_path(const std::filesystem::path& file) {
  std::error_code ec;
  const std::string cwd = std::filesystem::current_path(ec).string();
  const std::string full = file.string();
  if (!ec && !cwd.empty() && full.size() > cwd.size() + 1 && full.compare(0, cwd.size(), cwd) == 0 &&
      full[cwd.size()] == std::filesystem::path::preferred_separator)
    return full.substr(cwd.size() + 1);
  return full;
}

std::unique_ptr<ExplicitSolver> make_solver(Simulation& sim) {
  auto solver = std::make_unique<ExplicitSolver>(sim.model, sim.materials, sim.loads, sim.settings);
  solver->attach_contact(sim.contact_system ? &*sim.contact_system : nullptr);
  solver->attach_particle_contact(sim.particle_contact.get());
  solver->attach_cohesive(sim.cohesive.get());
  for (auto& e : sim.events) solver->add_event(*e);
  return solver;
}

std::vector<int> Simulation::part_materials() const {
  std::vector<int> m;
  for (const auto& p : model.parts) m.push_back(p.material);
  return m;
}

MeshData load_scenario_mesh(const Scenario& sc) {
  if (!sc.has_mesh) return MeshData{};  // particle parts only
  GmshOptions options;
  options.scale = sc.mesh_unit;
  options.mesh_size = sc.mesh_size > 0 ? sc.mesh_size / sc.mesh_unit : 0.0;
  options.dimension = sc.dim();
  options.max_elements = static_cast<double>(sc.mesh_max_elements);
  try {
    return load_gmsh_mesh(sc.mesh_file, options);
  } catch (const InputError& e) {
    if (e.key() == "mesh.size") throw InputError(shown_path(sc.file), sc.mesh_size_line, e.key(), e.reason());
    // Keep the importer's reason (and its line in the mesh file, if any), and point at the
    // scenario key that named the file.
    std::string where = e.file().empty() ? std::string("the mesh file") : "mesh file '" + e.file() + "'";
    if (e.line() > 0) where += " line " + std::to_string(e.line());
    throw InputError(shown_path(sc.file), sc.mesh_line, "mesh.file",
                     "problem in " + where + ": " + e.reason());
  }
}

namespace {

const char* dimension_word(int dim) {
  switch (dim) {
    case 0: return "point";
    case 1: return "curve";
    case 2: return "surface";
    default: return "volume";
  }
}

std::string group_list(const MeshData& mesh, int dim) {
  std::string s;
  for (const auto& g : mesh.groups)
    if (dim < 0 || g.dim == dim) s += (s.empty() ? "" : ", ") + g.name;
  return s.empty() ? "(none)" : s;
}

const MeshGroup& find_group(const Scenario& sc, const MeshData& mesh, const std::string& name,
                            int line, const std::string& key, int wanted_dim) {
  const MeshGroup* found = nullptr;
  for (const auto& g : mesh.groups)
    if (g.name == name && (wanted_dim < 0 || g.dim == wanted_dim)) found = found ? found : &g;
  if (found) return *found;
  std::vector<std::string> names;
  for (const auto& g : mesh.groups)
    if (wanted_dim < 0 || g.dim == wanted_dim) names.push_back(g.name);
  std::string reason;
  if (mesh.find_group(name)) {
    const int found_dim = mesh.find_group(name)->dim;
    reason = "physical group '" + name + "' is a " + dimension_word(found_dim) + " (dimension " +
             std::to_string(found_dim) + "), but this needs a " + dimension_word(wanted_dim) +
             " group (dimension " + std::to_string(wanted_dim) + ")";
  } else {
    reason = "the mesh '" + sc.mesh_file.filename().string() + "' has no physical group '" + name + "'";
    const std::string close = closest_match(name, names);
    if (!close.empty()) reason += " (did you mean '" + close + "'?)";
  }
  reason += wanted_dim < 0 ? "; groups of the mesh: " + group_list(mesh, wanted_dim)
                           : std::string("; ") + dimension_word(wanted_dim) +
                                 " groups of the mesh: " + group_list(mesh, wanted_dim);
  throw InputError(shown_path(sc.file), line, key, reason);
}


/// "triangles", "hexahedra", ...: the cells of a mesh group, in words.
std::string cell_words(CellType cell) {
  switch (cell) {
    case CellType::line2: return "lines";
    case CellType::tri3: return "triangles";
    case CellType::quad4: return "quadrilaterals";
    case CellType::tet4: return "tetrahedra";
    case CellType::hex8: return "hexahedra";
  }
  return "cells";
}

/// The part of a scenario entry: the cells of its physical group (in mesh node numbers), the
/// element formulation (chosen from the cells or checked against them) and its material.
Part part_of(Scenario& sc, const MeshData& mesh, const PartInput& pin) {
  const std::string file = shown_path(sc.file);
  const std::string key = "parts." + pin.name + ".group";
  const MeshGroup& group = find_group(sc, mesh, pin.group, pin.line, key, sc.dim());
  if (group.blocks.size() != 1) {
    throw InputError(file, pin.line, key,
                     "physical group '" + pin.group +
                         "' mixes cell types; a part holds one element type (split it into "
                         "several physical groups and parts)");
  }
  const CellBlock& block = group.blocks[0];
  const ElementType* type = default_element_type(block.type);
  if (!type)
    throw InputError(file, pin.line, key,
                     "physical group '" + pin.group + "' is meshed with " + cell_words(block.type) +
                         ", on which shard builds no element" +
                         (block.type == CellType::quad4
                              ? "; remove 'Recombine' from the .geo to mesh it with triangles"
                              : ""));
  if (pin.element) {
    const ElementType& wanted = element_type(*pin.element);
    if (wanted.cell != block.type) {
      std::string fitting;
      for (const auto& n : element_type_names())
        if (element_type(n).cell == block.type) fitting += (fitting.empty() ? "" : " or ") + n;
      throw InputError(file, pin.line, "parts." + pin.name + ".element",
                       "element '" + wanted.name + "' does not fit the cells of group '" + pin.group +
                           "': it is meshed with " + cell_words(block.type) + " (use " + fitting +
                           "), or leave 'element' out to take it from the mesh");
    }
    type = &wanted;
  }
  sc.resolved["parts"][pin.name]["element"] = type->name;
  Part part;
  part.name = pin.name;
  part.type = type;
  part.hourglass_coefficient = pin.hourglass_coefficient;
  part.volumetric = pin.volumetric;
  if (!type->offers(pin.volumetric)) {
    std::string offers;
    for (const auto t : {VolumetricTreatment::average_nodal_pressure, VolumetricTreatment::mean_dilatation}) {
      std::string by;
      for (const auto& n : element_type_names())
        if (element_type(n).offers(t)) by += (by.empty() ? "" : " and ") + n;
      offers += (offers.empty() ? "" : ", ") + std::string(name_of(t)) + " is for " + (by.empty() ? "none" : by);
    }
    throw InputError(file, pin.line, "parts." + pin.name + ".volumetric",
                     std::string("'") + name_of(pin.volumetric) + "' does not apply to " + type->name +
                         " elements: " + offers);
  }
  for (std::size_t m = 0; m < sc.materials.size(); ++m)
    if (sc.materials[m].name == pin.material) part.material = static_cast<int>(m);
  part.connectivity = block.connectivity;
  return part;
}

}  // namespace

namespace {

/// A packed sample turned into loose grains: spheres (discs of the model's thickness in 2D) of
/// the automaton size and the material's density, without bonds or automaton forces.
void make_grains(ParticlePart& part, const std::vector<MCAMaterial>& materials, double thickness) {
  part.model = ParticleModelHolder{};
  for (std::size_t i = 0; i < part.count(); ++i) {
    const double r = part.radius[i], rho = materials[part.material[i]].density;
    const double m = part.dim == 3 ? rho * 4.0 / 3.0 * std::numbers::pi * r * r * r : rho * std::numbers::pi * r * r * thickness;
    part.mass[i] = m;
    part.inertia[i] = (part.dim == 3 ? 0.4 : 0.5) * m * r * r;
  }
}

/// The index of the automaton material `name` among a part's materials (those of the scenario,
/// then an interphase's graded ones); −1 if none.
int material_index(const std::vector<MCAMaterial>& materials, const std::string& name) {
  for (std::size_t m = 0; m < materials.size(); ++m)
    if (materials[m].name == name) return static_cast<int>(m);
  return -1;
}

/// The bond laws of the scenario on the part's materials (before an interphase, which copies
/// them onto its graded materials).
void add_bond_laws(const Scenario& sc, ParticlePart& part) {
  MCAState& ms = mca_state(part);
  for (const auto& b : sc.bonds) {
    ms.bond_laws.push_back(b.law);
    ms.set_bond_law(material_index(ms.materials, b.material_a), material_index(ms.materials, b.material_b),
                    static_cast<int>(ms.bond_laws.size()) - 1);
  }
}

/// A sample from the builder: the lattice in its box, materials by region, inclusions and their
/// interphase, pores (the random draws, from the seeds).
ParticlePart build_sample(const Scenario& sc, const ParticlePartInput& in, const std::vector<MCAMaterial>& materials,
                          std::vector<std::string>& warnings) {
  const int dim = sc.dim();
  const std::string file = shown_path(sc.file), path = "particles." + in.name;
  PackingSpec spec = in.packing;
  spec.material = material_index(materials, in.material);
  ParticlePart part = build_packing(spec, materials);
  if (part.count() == 0) throw InputError(file, in.line, path, "the sample box holds no automaton");
  for (const auto& [name, region] : in.material_regions) {
    const auto& box = region;  // clang 14 cannot capture a structured binding in a lambda
    assign_material(part, [&](const double* x) { return box.contains(x, dim); }, material_index(materials, name));
  }
  add_bond_laws(sc, part);
  if (in.inclusions) {
    InclusionSpec inc = *in.inclusions;
    inc.material = material_index(materials, in.inclusion_material);
    double reached = 0;
    const int made = add_inclusions(part, inc, &reached);
    if (made == 0)
      throw InputError(file, in.line, path + ".inclusions",
                       "no inclusion fits the sample (diameter larger than the sample?)");
    // The draws stop after max_tries: a fraction that random non-overlapping discs or spheres of
    // this size cannot reach (about 0.55 of a square, 0.38 of a cube) is not silently short.
    auto percent = [](double f) {
      char text[32];
      std::snprintf(text, sizeof text, "%.1f %%", 100 * f);
      return std::string(text);
    };
    if (reached < inc.volume_fraction - 0.5 / static_cast<double>(part.count()))
      warnings.push_back(InputError(file, in.line, path + ".inclusions.volume_fraction",
                                    "the inclusions mark " + percent(reached) + " of the automata, not " +
                                        percent(inc.volume_fraction) + ": " + std::to_string(made) +
                                        " inclusions placed, and after " + std::to_string(inc.max_tries) +
                                        " draws no more fit without overlapping")
                             .what());
    if (in.interphase) {
      InterphaseSpec g = *in.interphase;
      g.inclusion_material = inc.material;
      g.matrix_material = spec.material;
      add_interphase(part, g);
    }
  }
  if (in.pores) add_pores(part, *in.pores);
  return part;
}

/// A sample read from a file: its automata as they are, the graded materials of its interphase
/// made again from the scenario's, so that the part equals the one the builder made.
ParticlePart import_sample(const Scenario& sc, const ParticlePartInput& in, const std::vector<MCAMaterial>& materials) {
  const ParticleSample& f = *in.sample;
  ParticlePart part = place_automata(in.packing, materials, f.x, f.radius, f.id, std::vector<int>(f.count(), 0));
  add_bond_laws(sc, part);
  if (f.interphase) {
    InterphaseSpec g;
    g.matrix_material = material_index(materials, f.interphase->matrix);
    g.inclusion_material = material_index(materials, f.interphase->inclusion);
    g.levels = f.interphase->levels;
    add_interphase_materials(part, g);
  }
  std::vector<int> index;
  for (const auto& name : f.material_names) index.push_back(material_index(mca_state(part).materials, name));
  for (std::size_t i = 0; i < f.count(); ++i) part.material[i] = index[f.material[i]];
  return part;
}

/// The part as built, for its sample file: ids within the part, its materials by name, the
/// interphase whose graded materials it names.
ParticleSample sample_of(const ParticlePart& part, const ParticlePartInput& in, std::int64_t first_id) {
  ParticleSample s;
  s.dim = part.dim;
  s.lattice = in.packing.lattice;
  s.automaton_size = in.packing.size;
  if (in.sample) s.interphase = in.sample->interphase;
  if (in.interphase && in.inclusions) s.interphase = {in.material, in.inclusion_material, in.interphase->levels};
  for (const auto id : part.id) s.id.push_back(id - first_id);
  s.x = part.x;
  s.radius = part.radius;
  for (const auto& m : mca_state(part).materials) s.material_names.push_back(m.name);
  s.material = part.material;
  return s;
}

/// Particle parts from their packing specifications or sample files, then bonding; and the
/// constraints of particle_boundary_conditions.
void build_particle_parts(Scenario& sc, Simulation& sim) {
  Model& model = sim.model;
  const int dim = sc.dim();
  const std::string file = shown_path(sc.file);
  std::vector<MCAMaterial> materials;
  for (const auto& m : sc.automaton_materials) materials.push_back(m.material);
  for (const auto& in : sc.particle_parts) {
    ParticlePart part = in.sample ? import_sample(sc, in, materials) : build_sample(sc, in, materials, sc.warnings);
    part.name = in.name;
    part.time_step_safety = in.time_step_safety;
    part.contact_update_interval = in.contact_update_interval;
    part.contact_skin = in.contact_skin;
    // Ids after every particle of the parts before (a pair is keyed by its automata's ids).
    const std::int64_t first_id = model.next_particle_id;
    for (auto& id : part.id) id += first_id;
    finish_sample(part, in.packing.bond_tolerance);
    sim.samples[in.name] = sample_of(part, in, first_id);
    if (in.grains) make_grains(part, materials, sc.thickness);
    for (std::size_t i = 0; i < part.count(); ++i)
      for (int k = 0; k < dim; ++k) part.v[dim * i + k] = in.velocity[k];
    part.x0 = part.x;
    part.x_old = part.x;
    for (const auto id : part.id) model.next_particle_id = std::max(model.next_particle_id, id + 1);
    model.particle_parts.push_back(std::move(part));
  }
  if (std::any_of(model.particle_parts.begin(), model.particle_parts.end(),
                  [](const ParticlePart& p) { return p.contact_update_interval > 0; }))
    sim.events.push_back(std::make_unique<MCAContactUpdate>());

  // Conditions on regions: one constraint per (automaton, component); a later entry overrides.
  std::map<std::tuple<int, std::int32_t, int>, std::pair<int, int>> constraint;  // → (table, group)
  for (std::size_t c = 0; c < sc.particle_conditions.size(); ++c) {
    const auto& in = sc.particle_conditions[c];
    int p = 0;
    while (model.particle_parts[p].name != in.part) ++p;
    ParticlePart& part = model.particle_parts[p];
    ParticleSet set;
    set.name = in.name;
    if (in.region.kind == RegionInput::Kind::side) {
      for (int a : boundary_layer(part, in.region.axis, in.region.at_max, in.region.depth)) set.members.push_back(a);
    } else {
      for (std::size_t i = 0; i < part.count(); ++i)
        if (in.region.contains(&part.x[dim * i], dim)) set.members.push_back(static_cast<std::int32_t>(i));
    }
    if (set.members.empty())
      throw InputError(file, in.line, "particle_boundary_conditions[" + std::to_string(c + 1) + "].region",
                       "the region holds no automaton of part '" + in.part + "'");
    const int g = static_cast<int>(sim.loads.particle_groups.size());
    for (int k = 0; k < 3; ++k) {
      if (!in.velocity[k]) continue;
      sim.loads.tables.push_back(*in.velocity[k]);
      for (auto a : set.members) constraint[{p, a, k}] = {static_cast<int>(sim.loads.tables.size()) - 1, g};
    }
    if (in.fix_rotation) {
      sim.loads.tables.push_back(TimeTable::constant(0.0));
      for (auto a : set.members)
        for (int r = 0; r < part.rot_dim(); ++r)
          constraint[{p, a, dim + r}] = {static_cast<int>(sim.loads.tables.size()) - 1, g};
    }
    sim.loads.particle_groups.push_back({in.name, p});
    part.sets.push_back(std::move(set));
  }
  for (const auto& [key, value] : constraint) {
    ParticlePart& pp = model.particle_parts[std::get<0>(key)];
    const std::size_t width = static_cast<std::size_t>(dim + pp.rot_dim());
    pp.prescribed[width * std::get<1>(key) + std::get<2>(key)] = sim.loads.prescription(value.first, value.second);
  }
}

}  // namespace

namespace {

// The node set of a physical group on the kept nodes, made once and shared by every condition
// that names the group.
struct GroupNodeSets {
  Model& model;
  const std::vector<std::int32_t>& renumber;
  const std::string& file;

  const NodeSet& of(const MeshGroup& g, int line, const std::string& key) {
    if (const NodeSet* s = model.find_node_set(g.name)) return *s;
    try {
      model.node_sets.push_back(node_set_of(g, renumber));
    } catch (const AssemblyError& e) {
      throw InputError(file, line, key, e.what());
    }
    return model.node_sets.back();
  }
};

/// Plies that the mesh does not resolve (empty when it does): elements that straddle a ply
/// boundary by more than 1 % of a ply on each side, which take the ply of their centroid (the
/// plies are then as thick as the element rows, not as the layup says, and `plies_of` interfaces
/// lie on the rows' faces), and plies that hold no element (thinner than the rows).
template <class Along>
std::string plies_off_the_mesh(const Part& part, const std::vector<int>& ply, Along along, double start,
                               double thickness, int count) {
  const std::size_t npe = static_cast<std::size_t>(part.type->nodes);
  std::size_t straddling = 0;
  double example = 0;
  std::vector<char> held(static_cast<std::size_t>(count), 0);
  for (std::size_t e = 0; e < ply.size(); ++e) {
    held[static_cast<std::size_t>(ply[e])] = 1;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t a = 0; a < npe; ++a) {
      const double s = (along(part.connectivity[npe * e + a]) - start) / thickness;
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    const double boundary = std::floor(hi - 0.01);
    if (boundary > lo + 0.01 && boundary >= 0) {  // ply 1's start too, when `start` is above the lowest node
      if (straddling++ == 0) example = boundary;
    }
  }
  const auto empty = static_cast<std::size_t>(std::count(held.begin(), held.end(), 0));
  if (straddling == 0 && empty == 0) return "";
  std::ostringstream out;
  out << "the mesh does not follow the plies of " << thickness * 1e3 << " mm:";
  if (straddling > 0)
    out << " " << straddling << " of its " << ply.size() << " elements cross a ply boundary (the first the boundary "
        << example * thickness * 1e3 << " mm from where ply 1 begins) and take the ply of their centroid;";
  if (empty > 0) out << " " << empty << " of the " << count << " plies hold no element;";
  out << " the plies are then those of the element rows, not of the layup: mesh rows of one ply (or a whole "
         "number of rows per ply) along the normal";
  return out.str();
}

/// The ply of each element of a laminate part: its centroid's place along the stacking normal.
std::vector<int> plies_of_elements(const Scenario& sc, const Model& model, std::size_t p,
                                   std::vector<std::string>& warnings) {
  const Part& part = model.parts[p];
  const PlyOrientationInput& o = *sc.parts[p].orientation;
  const std::size_t ne = part.element_count(), npe = static_cast<std::size_t>(part.type->nodes);
  const int dim = model.dim();
  const double nn = std::sqrt(o.normal[0] * o.normal[0] + o.normal[1] * o.normal[1] + o.normal[2] * o.normal[2]);
  auto along = [&](std::int32_t node) {
    double s = 0;
    for (int k = 0; k < dim; ++k) s += model.nodes.x0[dim * node + k] * o.normal[k] / nn;
    return s;
  };
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (auto n : part.connectivity) {
    lowest = std::min(lowest, along(n));
    highest = std::max(highest, along(n));
  }
  const double start = o.start.value_or(lowest);
  const int count = static_cast<int>(o.angles.size());
  if (o.ply_thickness == 0) return std::vector<int>(ne, 0);
  std::vector<int> ply(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    double c = 0;
    for (std::size_t a = 0; a < npe; ++a) c += along(part.connectivity[npe * e + a]) / static_cast<double>(npe);
    const int k = static_cast<int>(std::floor((c - start) / o.ply_thickness));
    if (k < 0 || k >= count) {
      std::ostringstream out;
      out << "an element of part '" << part.name << "' lies " << (c - start) * 1e3 << " mm along the normal from "
          << "where ply 1 begins, outside the " << count << " plies of " << o.ply_thickness * 1e3
          << " mm (" << count * o.ply_thickness * 1e3 << " mm); the part spans " << (highest - lowest) * 1e3
          << " mm: check ply_thickness, start and normal";
      throw InputError(shown_path(sc.file), o.line, "parts." + part.name + ".laminate", out.str());
    }
    ply[e] = k;
  }
  // The other way round: plies beyond the part's far face would hold no element, and a layup
  // code cut short (a symmetric one loses its symmetry) is as wrong as one too short.
  const double total = count * o.ply_thickness, span = highest - start;
  if (total > span + 0.5 * o.ply_thickness) {
    std::ostringstream out;
    out << "the " << count << " plies of " << o.ply_thickness * 1e3 << " mm (" << total * 1e3
        << " mm) are thicker than part '" << part.name << "' (" << span * 1e3 << " mm from where ply 1 begins): plies "
        << static_cast<int>(std::floor(span / o.ply_thickness + 0.5)) + 1 << " to " << count
        << " would hold no element; check the layup, ply_thickness and the mesh";
    throw InputError(shown_path(sc.file), o.line, "parts." + part.name + ".laminate", out.str());
  }
  if (const std::string why = plies_off_the_mesh(part, ply, along, start, o.ply_thickness, count); !why.empty())
    warnings.push_back(InputError(shown_path(sc.file), o.line, "parts." + part.name + ".laminate", why).what());
  return ply;
}

/// Material axes of a part from its orientation or laminate.
void orient_part(Scenario& sc, Simulation& sim, std::size_t p) {
  Part& part = sim.model.parts[p];
  const Material& material = *sim.materials[part.material];
  const PlyOrientationInput& o = *sc.parts[p].orientation;
  if (material.material_axes_index() < 0)
    throw InputError(shown_path(sc.file), o.line, "parts." + part.name + (o.layup.empty() ? ".orientation" : ".laminate"),
                     "material '" + material.name() + "' (" + std::string(material.model()) +
                         ") is isotropic and has no material axes; orientation and laminate are for "
                         "orthotropic_elastic and composite_damage");
  const std::vector<int> ply = plies_of_elements(sc, sim.model, p, sc.warnings);
  std::vector<std::array<double, 6>> axes;
  for (double angle : o.angles) axes.push_back(ply_axes(o.reference, o.normal, angle));
  set_material_axes(part, material, [&](std::size_t e) { return axes[static_cast<std::size_t>(ply[e])]; });
  sim.plies[part.name] = ply;
}

// Parts: elements from the physical groups, in mesh node numbering until assembled. Returns the
// mesh-to-model node numbering.
std::vector<std::int32_t> build_parts(Scenario& sc, const MeshData& mesh, Simulation& sim) {
  Model& model = sim.model;
  std::vector<Part> parts;
  for (const auto& pin : sc.parts) parts.push_back(part_of(sc, mesh, pin));
  std::vector<std::int32_t> renumber = assemble_nodes_and_parts(model, mesh, sc.dim(), std::move(parts));
  if (sc.formulation == Formulation::axisymmetric) {
    for (std::size_t i = 0; i < model.nodes.count(); ++i)
      if (model.nodes.x0[2 * i] < -1e-12) {
        std::ostringstream out;
        out << "axisymmetric models lie at r = x >= 0; node at (" << model.nodes.x0[2 * i] << ", "
            << model.nodes.x0[2 * i + 1] << ") has x < 0";
        throw InputError(shown_path(sc.file), sc.mesh_line, "mesh.file", out.str());
      }
  }
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    prepare_part(model, p, *sim.materials[model.parts[p].material], sc.initial_temperature);
    if (sc.parts[p].orientation) orient_part(sc, sim, p);
  }
  return renumber;
}

// Initial velocity fields on the nodes of a part or a group, in the order given (a later entry
// overrides an earlier one where they share nodes).
void apply_initial_velocities(const Scenario& sc, const MeshData& mesh, Model& model, GroupNodeSets& sets) {
  const int dim = sc.dim();
  auto start = [&](const InitialVelocityInput& ic, std::int32_t n) {
    const auto v = ic.at(&model.nodes.x[static_cast<std::size_t>(dim) * n], dim);
    for (int k = 0; k < dim; ++k) model.nodes.v[dim * n + k] = v[k];
  };
  for (std::size_t i = 0; i < sc.initial_velocities.size(); ++i) {
    const auto& ic = sc.initial_velocities[i];
    if (!ic.group.empty()) {
      const std::string key = "initial_conditions[" + std::to_string(i + 1) + "].group";
      for (auto n : sets.of(find_group(sc, mesh, ic.group, ic.line, key, -1), ic.line, key).nodes) start(ic, n);
    }
    for (const auto& part : model.parts)
      if (part.name == ic.part)
        for (auto n : part.connectivity) start(ic, n);
  }
}

// Bonded automata of two materials that no `bonds` entry names never break, as with `criterion:
// none`, which says it is meant: a warning per such pair of materials, with how many bonds it covers.
std::vector<std::string> unbreakable_bond_warnings(const Scenario& sc, const Simulation& sim) {
  std::vector<std::string> out;
  for (const auto& part : sim.model.particle_parts) {
    const MCAState* ms = find_mca_state(part);
    if (!ms) continue;
    const std::size_t nm = ms->materials.size();
    std::vector<std::size_t> count(nm * nm, 0);
    for (std::size_t p = 0; p < ms->pairs.count(); ++p) {
      if (ms->pairs.law[p] >= 0 || ms->pairs.state_of(p) == PairState::unlinked) continue;
      const auto a = static_cast<std::size_t>(part.material[ms->pairs.i[p]]);
      const auto b = static_cast<std::size_t>(part.material[ms->pairs.j[p]]);
      ++count[std::min(a, b) * nm + std::max(a, b)];
    }
    for (std::size_t a = 0; a < nm; ++a)
      for (std::size_t b = a; b < nm; ++b) {
        const std::size_t n = count[a * nm + b];
        if (n == 0) continue;
        const std::string &ma = ms->materials[a].name, &mb = ms->materials[b].name;
        out.push_back(InputError(shown_path(sc.file), 0, "particles." + part.name,
                                 std::to_string(n) + " of its " + std::to_string(ms->pairs.count()) +
                                     " bonded pairs join '" + ma + "' and '" + mb +
                                     "', which no bonds entry names: they never break (give them a bond law in "
                                     "bonds, or {materials: [" + ma + ", " + mb + "], criterion: none} to say so)")
                          .what());
      }
  }
  return out;
}

// The longest edge of the elements around node n at the start (0 for a node of no element).
double longest_edge_at(const Model& model, std::size_t n) {
  const int dim = model.dim();
  double longest = 0;
  for (const auto& part : model.parts) {
    const std::size_t npe = static_cast<std::size_t>(part.type->nodes);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const std::int32_t* c = &part.connectivity[npe * e];
      if (std::find(c, c + npe, static_cast<std::int32_t>(n)) == c + npe) continue;
      for (std::size_t a = 0; a < npe; ++a)
        for (std::size_t b = a + 1; b < npe; ++b) {
          double d2 = 0;
          for (int k = 0; k < dim; ++k) d2 += std::pow(model.nodes.x0[dim * c[a] + k] - model.nodes.x0[dim * c[b] + k], 2);
          longest = std::max(longest, std::sqrt(d2));
        }
    }
  }
  return longest;
}

// Probes: the node nearest each point at the start, or a group's nodes, by their stable ids (a
// crack that splits a probe's node keeps the id on one of the copies). A point farther from its
// node than the elements around the node are long is likely outside the body: a warning.
void build_probes(Scenario& sc, const MeshData& mesh, Simulation& sim, GroupNodeSets& sets) {
  const Model& model = sim.model;
  const int dim = sc.dim();
  for (std::size_t i = 0; i < sc.probes.size(); ++i) {
    const auto& in = sc.probes[i];
    Simulation::Probe p{in.name, in.interval, {}};
    if (in.point) {
      if (model.nodes.count() == 0)
        throw InputError(shown_path(sc.file), in.line, "probes[" + std::to_string(i + 1) + "].point",
                         "a probe at a point needs a mesh (this scenario has particles only)");
      std::size_t nearest = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t n = 0; n < model.nodes.count(); ++n) {
        double d2 = 0;
        for (int k = 0; k < dim; ++k) d2 += std::pow(model.nodes.x0[dim * n + k] - (*in.point)[k], 2);
        if (d2 < best) best = d2, nearest = n;
      }
      p.nodes.push_back(model.nodes.id[nearest]);
      const double off = std::sqrt(best), edge = longest_edge_at(model, nearest);
      if (off > edge) {
        std::ostringstream what;
        what.precision(3);
        what << "the nearest node is " << 1e3 * off << " mm from the point, farther than the elements around it are long ("
             << 1e3 * edge << " mm): the point is likely outside the body (the probe follows that node)";
        sc.warnings.push_back(InputError(shown_path(sc.file), in.line, "probes[" + std::to_string(i + 1) + "].point",
                                         what.str()).what());
      }
    } else {
      const std::string key = "probes[" + std::to_string(i + 1) + "].group";
      for (auto n : sets.of(find_group(sc, mesh, in.group, in.line, key, -1), in.line, key).nodes)
        p.nodes.push_back(model.nodes.id[n]);
    }
    sim.probes.push_back(std::move(p));
  }
}

// Initial velocity fields on particle parts: each particle moves with the field at its centre and
// spins with the field's spin (a rigidly rotating body's particles turn with it).
void apply_initial_particle_velocities(const Scenario& sc, Model& model) {
  const int dim = sc.dim();
  for (const auto& ic : sc.initial_velocities)
    for (auto& pp : model.particle_parts) {
      if (pp.name != ic.part) continue;
      const auto spin = ic.spin();
      const int r = pp.rot_dim();
      for (std::size_t i = 0; i < pp.count(); ++i) {
        const auto v = ic.at(&pp.x[static_cast<std::size_t>(dim) * i], dim);
        for (int k = 0; k < dim; ++k) pp.v[dim * i + k] = v[k];
        for (int k = 0; k < r; ++k) pp.omega[r * i + k] = r == 1 ? spin[2] : spin[k];
      }
    }
}

// Boundary conditions: one constraint per (node, component); a later entry overrides, and its
// group then reports the node's reaction.
void apply_boundary_conditions(const Scenario& sc, const MeshData& mesh, Simulation& sim, GroupNodeSets& sets) {
  // (node, component) -> (table, group, rotation)
  std::map<std::pair<std::int32_t, int>, std::array<int, 3>> constraint_table;
  auto& groups = sim.loads.node_groups;
  for (std::size_t i = 0; i < sc.boundary_conditions.size(); ++i) {
    const auto& bc = sc.boundary_conditions[i];
    const std::string key = "boundary_conditions[" + std::to_string(i + 1) + "].group";
    const MeshGroup& g = find_group(sc, mesh, bc.group, bc.line, key, -1);
    const NodeSet& set = sets.of(g, bc.line, key);
    const auto named = std::find(groups.begin(), groups.end(), bc.group);
    const int group = static_cast<int>(named - groups.begin());
    if (named == groups.end()) groups.push_back(bc.group);
    int rotation = -1;
    if (bc.rotation) {
      sim.loads.rotations.push_back(Rotation{bc.rotation->centre, bc.rotation->axis});
      rotation = static_cast<int>(sim.loads.rotations.size()) - 1;
      sim.loads.tables.push_back(bc.rotation->rate);
    }
    for (int k = 0; k < sc.dim(); ++k) {
      if (!bc.velocity[k] && rotation < 0) continue;
      if (rotation < 0) sim.loads.tables.push_back(*bc.velocity[k]);
      const int table = static_cast<int>(sim.loads.tables.size()) - 1;
      for (auto n : set.nodes) constraint_table[{n, k}] = {table, group, rotation};
    }
  }
  for (const auto& [dof, p] : constraint_table) prescribe_node(sim.model, sim.loads, dof.first, dof.second, p[0], p[1], p[2]);
}

// Pressure loads on boundary facets.
void apply_pressures(const Scenario& sc, const MeshData& mesh, Simulation& sim, GroupNodeSets& sets,
                     const std::vector<std::int32_t>& renumber) {
  Model& model = sim.model;
  for (std::size_t i = 0; i < sc.pressures.size(); ++i) {
    const auto& p = sc.pressures[i];
    const std::string key = "loads[" + std::to_string(i + 1) + "].group";
    const MeshGroup& g = find_group(sc, mesh, p.group, p.line, key, sc.dim() - 1);
    sets.of(g, p.line, key);
    FacetSet fs;
    try {
      fs = facet_set_of(model, g, renumber);
    } catch (const AssemblyError& e) {
      throw InputError(shown_path(sc.file), p.line, key, e.what());
    }
    model.facet_sets.push_back(std::move(fs));
    sim.loads.tables.push_back(p.pressure);
    sim.loads.pressures.push_back({static_cast<int>(model.facet_sets.size()) - 1,
                                   static_cast<int>(sim.loads.tables.size()) - 1});
  }
}

int part_index(const Model& model, const std::string& name) {
  for (std::size_t p = 0; p < model.parts.size(); ++p)
    if (model.parts[p].name == name) return static_cast<int>(p);
  return -1;
}

/// What a cracking part's failure map needs: a threshold below the bound of its factor, and, for a
/// damage that does not heal (denoual_forquin_hild), a tip-speed limit (without it every failed
/// node beside a crack starts a crack that joins it).
void check_lasting_damage_part(const Scenario& sc, const Part& part, const Material& m) {
  const auto slots = m.failure_map_slots();
  const std::string file = shown_path(sc.file);
  const std::string who = "part '" + part.name + "' ('" + std::string(m.model()) + "')";
  if (sc.cracking->failure_threshold >= slots->factor_bound) {
    std::ostringstream t;
    t << sc.cracking->failure_threshold;
    throw InputError(file, sc.cracking->line, "cracking.failure_threshold",
                     who + " cannot crack at the threshold " + t.str() +
                         ": its failure factor is its largest damage, which reaches 1 only where a point is "
                         "wholly damaged; give the damage at which a crack is drawn (e.g. failure_threshold: 0.5)");
  }
  if (slots->heals) return;
  if (!(sc.cracking->tip_speed_limit > 0)) {
    const auto* dfh = dynamic_cast<const DenoualForquinHild*>(&m);
    std::ostringstream v;
    if (dfh) v << " (its crack speed kC0, " << dfh->parameters_in_use().crack_speed << " m/s)";
    throw InputError(file, sc.cracking->line, "cracking.tip_speed_limit",
                     who + " keeps its damage where a crack passes, so its cracks need a limit on the tip speed" +
                         v.str() + ": without it every failed node beside a crack starts a crack of its own");
  }
}

// Cracking parts: those named (or, when none is named, every part that can crack and whose
// damage heals where a crack passes: a fragmentation damage is cracked only when named).
std::vector<int> cracking_parts(const Scenario& sc, Simulation& sim) {
  std::vector<int> out;
  if (!sc.cracking) return out;
  const std::string file = shown_path(sc.file);
  for (std::size_t p = 0; p < sim.model.parts.size(); ++p) {
    const Part& part = sim.model.parts[p];
    const bool named = std::find(sc.cracking->parts.begin(), sc.cracking->parts.end(), part.name) !=
                       sc.cracking->parts.end();
    const auto slots = sim.materials[part.material]->failure_map_slots();
    const bool can = part.type->is_triangle() && slots;
    if (named && !can)
      throw InputError(file, sc.cracking->line, "cracking.parts",
                       "part '" + part.name + "' cannot crack: cracks are inserted in tri3 parts of "
                       "a material with a failure map (rotating_crack, denoual_forquin_hild); it has " +
                           part.type->name + " elements of '" +
                           std::string(sim.materials[part.material]->model()) + "'");
    if (named || (sc.cracking->parts.empty() && can && slots->heals)) out.push_back(static_cast<int>(p));
  }
  if (out.empty())
    throw InputError(file, sc.cracking->line, "cracking",
                     "no part can crack: cracks are inserted in tri3 parts of a material with a "
                     "failure map (rotating_crack; denoual_forquin_hild when named in cracking.parts)");
  for (const int p : out) check_lasting_damage_part(sc, sim.model.parts[p], *sim.materials[sim.model.parts[p].material]);
  CrackGrowthSettings cracking;
  cracking.parts = out;
  cracking.failure_threshold = sc.cracking->failure_threshold;
  cracking.min_fragment_elements = sc.cracking->min_fragment_elements;
  cracking.speed_limit = {sc.cracking->tip_speed_limit, sc.cracking->nucleation_spacing};
  sim.cracking = cracking;
  return out;
}

/// A seeded field of weakest flaws (denoual_forquin_hild's seed) orders where discrete cracks
/// start and acts nowhere else: on a part that does not crack it would do nothing, silently.
void check_weakest_flaw_fields(const Scenario& sc, const Simulation& sim, const std::vector<int>& cracking) {
  for (std::size_t p = 0; p < sim.model.parts.size(); ++p) {
    const Part& part = sim.model.parts[p];
    const auto slots = sim.materials[part.material]->failure_map_slots();
    if (!slots || slots->weakest_flaw < 0) continue;  // a field only where a seed is given
    if (std::find(cracking.begin(), cracking.end(), static_cast<int>(p)) != cracking.end()) continue;
    const MaterialInput& mi = sc.materials[part.material];
    throw InputError(shown_path(sc.file), mi.line, "materials." + mi.name + ".seed",
                     "the field of weakest flaws orders where discrete cracks start, and part '" + part.name +
                         "' draws none: name it in cracking.parts (with a tip_speed_limit), or remove the seed "
                         "(the damage itself is the mean over the flaw population and takes no seed)");
  }
}

// The pairs of parts in contact and the friction of each pair of materials, from `contact:`.
void contact_pairs_and_friction(const Scenario& sc, const Model& model, ContactSettings& cs) {
  const std::size_t np = model.parts.size(), nm = sc.materials.size();
  const ContactInput& ci = *sc.contact;
  for (std::size_t a = 0; a < np; ++a)
    for (std::size_t b = 0; b < np; ++b)
      if (ci.all_pairs && (a != b || ci.self_contact)) cs.part_pairs[a * np + b] = 1;
  for (const auto& [a, b] : ci.pairs) {
    const int ia = part_index(model, a), ib = part_index(model, b);
    cs.part_pairs[ia * np + ib] = cs.part_pairs[ib * np + ia] = 1;
  }
  std::fill(cs.friction.begin(), cs.friction.end(), FrictionLaw{ci.friction, ci.dynamic_friction});
  for (const auto& f : ci.material_friction) {
    std::size_t ma = 0, mb = 0;
    for (std::size_t m = 0; m < nm; ++m) {
      if (sc.materials[m].name == f.material_a) ma = m;
      if (sc.materials[m].name == f.material_b) mb = m;
    }
    cs.friction[ma * nm + mb] = cs.friction[mb * nm + ma] = {f.static_coefficient, f.dynamic_coefficient};
  }
  cs.penalty_scale = ci.penalty_scale;
  cs.time_step_reduction = ci.time_step_reduction;
  cs.damping = ci.damping;
}

// The crack faces a cracking part grows must close and slide, so each is in contact with itself
// (contact is switched on for them if the scenario has none), with the cracking friction unless
// `contact:` gives one for its material.
void self_contact_of_cracking_parts(const Scenario& sc, const Model& model, const std::vector<int>& cracking,
                                    ContactSettings& cs) {
  const std::size_t np = model.parts.size(), nm = sc.materials.size();
  for (int p : cracking) {
    cs.part_pairs[p * np + p] = 1;
    const std::size_t m = static_cast<std::size_t>(model.parts[p].material);
    bool given = false;
    if (sc.contact)
      for (const auto& f : sc.contact->material_friction)
        given = given || (f.material_a == sc.materials[m].name && f.material_b == f.material_a);
    if (!given) cs.friction[m * nm + m] = {sc.cracking->friction, sc.cracking->friction};
  }
}

RigidWall rigid_wall(const WallInput& wi, const Model& model) {
  RigidWall w;
  w.name = wi.name;
  w.point = wi.point;
  w.normal = wi.normal;
  for (int k = 0; k < 3; ++k)
    if (wi.velocity[k]) w.velocity[k] = *wi.velocity[k];
  w.friction = {wi.friction, wi.dynamic_friction};
  w.extent = wi.extent;
  w.parts.assign(model.parts.size(), wi.parts.empty() ? 1 : 0);
  for (const auto& name : wi.parts) w.parts[part_index(model, name)] = 1;
  return w;
}

/// A part that starts wholly behind a whole-plane wall (its normal pointing away from the part,
/// most often a sign slip) would be thrown out through the wall's face at the first step, and the
/// run would stop on an element turned inside out, blamed on the time step: said before the run.
std::vector<std::string> parts_behind_walls(const Scenario& sc, const Model& model) {
  std::vector<std::string> out;
  const int dim = model.dim();
  for (const WallInput& wi : sc.walls) {
    if (std::isfinite(wi.extent.depth) || std::isfinite(wi.extent.length) || std::isfinite(wi.extent.width)) continue;
    for (const Part& part : model.parts) {
      if (!wi.parts.empty() && std::find(wi.parts.begin(), wi.parts.end(), part.name) == wi.parts.end()) continue;
      // On the face or behind it, and some node behind (a body resting on the face is in front).
      bool none_in_front = part.element_count() > 0, some_behind = false;
      for (std::size_t i = 0; i < part.connectivity.size() && none_in_front; ++i) {
        double gap = 0;
        for (int k = 0; k < dim; ++k)
          gap += (model.nodes.x0[dim * part.connectivity[i] + k] - wi.point[k]) * wi.normal[k];
        none_in_front = gap <= 0;
        some_behind = some_behind || gap < 0;
      }
      if (none_in_front && some_behind)
        out.push_back(InputError(shown_path(sc.file), wi.line, "walls",
                                 "part '" + part.name + "' starts wholly behind wall '" + wi.name +
                                     "' (its normal points away from the part): the wall would push it out "
                                     "through its face at the first step; the normal points to the side where "
                                     "the bodies are")
                          .what());
    }
  }
  return out;
}

/// Bodies that would pass through each other: without a contact: section, parts that share no
/// node (nor a cohesive interface) meet nowhere, and one of them moving at the start will run
/// through the others silently (a new user's rod went 4 mm into its tile with its kinetic energy
/// unchanged).
std::vector<std::string> bodies_without_contact(const Scenario& sc, const Model& model) {
  if (sc.contact || model.parts.size() < 2) return {};
  const std::size_t np = model.parts.size();
  DisjointSets body(np);  // parts joined by a shared node or an interface
  std::vector<std::int32_t> first(model.nodes.count(), -1);
  for (std::size_t p = 0; p < np; ++p)
    for (auto n : model.parts[p].connectivity) {
      if (first[n] < 0) first[n] = static_cast<std::int32_t>(p);
      else body.join(first[n], static_cast<std::int32_t>(p));
    }
  for (const InterfaceInput& in : sc.interfaces)
    if (in.between.size() == 2) body.join(part_index(model, in.between[0]), part_index(model, in.between[1]));
  const int dim = model.dim();
  std::vector<char> moving(np, 0);
  for (std::size_t p = 0; p < np; ++p)
    for (auto n : model.parts[p].connectivity)
      for (int k = 0; k < dim; ++k) moving[p] = moving[p] || model.nodes.v[dim * n + k] != 0.0;
  std::vector<std::string> out;
  for (std::size_t p = 0; p < np; ++p) {
    if (!moving[p]) continue;
    std::string others;
    for (std::size_t q = 0; q < np; ++q)
      if (body.find(static_cast<std::int32_t>(q)) != body.find(static_cast<std::int32_t>(p))) others += (others.empty() ? "'" : ", '") + model.parts[q].name + "'";
    if (others.empty()) continue;
    out.push_back(InputError(shown_path(sc.file), 0, "contact",
                             "part '" + model.parts[p].name + "' starts moving and shares no node with " + others +
                                 ", and the scenario has no contact: section: the bodies pass through each other "
                                 "without a force (add contact: {pairs: all}, or name the pairs that meet)")
                      .what());
    break;  // one word is enough
  }
  return out;
}

/// A body that moves away from everything it could meet (a velocity given with the wrong sign):
/// with contact on, a moving part none of whose partners lies ahead along its velocity relative
/// to them, and no wall it runs towards. Judged on the parts' mean initial velocities and
/// centroids; a run whose bodies only separate was mostly not what was meant.
std::vector<std::string> bodies_moving_apart(const Scenario& sc, const Model& model) {
  // Particles (a granular bed, automata) are targets too, not judged here.
  if (!sc.contact || model.parts.size() + sc.walls.size() < 2 || !model.particle_parts.empty()) return {};
  const int dim = model.dim();
  const std::size_t np = model.parts.size();
  std::vector<std::array<double, 3>> centre(np), velocity(np);
  for (std::size_t p = 0; p < np; ++p) {
    const auto& nodes = model.parts[p].connectivity;
    for (auto n : nodes)
      for (int k = 0; k < dim; ++k) {
        centre[p][k] += model.nodes.x0[dim * n + k] / static_cast<double>(nodes.size());
        velocity[p][k] += model.nodes.v[dim * n + k] / static_cast<double>(nodes.size());
      }
  }
  auto dot = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double d = 0;
    for (int k = 0; k < dim; ++k) d += a[k] * b[k];
    return d;
  };
  for (std::size_t p = 0; p < np; ++p) {
    if (dot(velocity[p], velocity[p]) == 0) continue;
    bool approaches = false;
    for (std::size_t q = 0; q < np && !approaches; ++q) {
      if (q == p) continue;
      std::array<double, 3> towards{}, relative{};
      for (int k = 0; k < dim; ++k) {
        towards[k] = centre[q][k] - centre[p][k];
        relative[k] = velocity[p][k] - velocity[q][k];
      }
      approaches = dot(towards, relative) > 0;
    }
    for (const WallInput& w : sc.walls) approaches = approaches || dot(velocity[p], w.normal) < 0;
    if (approaches) continue;
    return {InputError(shown_path(sc.file), 0, "initial_conditions",
                       "part '" + model.parts[p].name +
                           "' moves away from every other body and wall it could meet: nothing will touch it "
                           "(check the sign of its velocity)")
                .what()};
  }
  return {};
}

/// Once an interface fails its two sides touch as ordinary contact, with the interface's
/// friction unless `contact:` gives one for their materials.
void contact_across_interfaces(const Scenario& sc, const Model& model, ContactSettings& cs) {
  const std::size_t np = model.parts.size(), nm = sc.materials.size();
  for (const InterfaceInput& in : sc.interfaces) {
    const std::vector<std::string> names = in.between.empty() ? std::vector<std::string>{in.plies_of, in.plies_of} : in.between;
    const int a = part_index(model, names[0]), b = part_index(model, names[1]);
    cs.part_pairs[a * np + b] = cs.part_pairs[b * np + a] = 1;
    const std::size_t ma = static_cast<std::size_t>(model.parts[a].material), mb = static_cast<std::size_t>(model.parts[b].material);
    bool given = false;
    if (sc.contact)
      for (const auto& f : sc.contact->material_friction)
        given = given || (f.material_a == sc.materials[ma].name && f.material_b == sc.materials[mb].name) ||
                (f.material_b == sc.materials[ma].name && f.material_a == sc.materials[mb].name);
    if (!given) cs.friction[ma * nm + mb] = cs.friction[mb * nm + ma] = {in.friction, in.friction};
  }
}

/// Splits the nodes of the surfaces the scenario's interfaces tie and makes their elements.
void build_interfaces(const Scenario& sc, Simulation& sim) {
  if (sc.interfaces.empty()) return;
  Model& model = sim.model;
  InterfaceLayout layout;
  std::vector<int> first(model.parts.size());
  int groups = 0;
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    first[p] = groups;
    const auto ply = sim.plies.find(model.parts[p].name);
    std::vector<int> g(model.parts[p].element_count(), groups);
    int count = 1;
    if (ply != sim.plies.end()) {
      for (std::size_t e = 0; e < g.size(); ++e) g[e] = groups + ply->second[e];
      count = static_cast<int>(sc.parts[p].orientation->angles.size());
    }
    layout.group.push_back(std::move(g));
    groups += count;
  }
  auto plies = [&](int p) {
    const auto it = sim.plies.find(model.parts[p].name);
    return it == sim.plies.end() ? 1 : static_cast<int>(sc.parts[p].orientation->angles.size());
  };
  std::vector<CohesiveLaw> laws;
  for (const InterfaceInput& in : sc.interfaces) {
    const int law = static_cast<int>(laws.size());
    laws.push_back(in.law);
    if (in.between.empty()) {
      const int p = part_index(model, in.plies_of);
      for (int i = 0; i < plies(p); ++i)
        for (int j = i + 1; j < plies(p); ++j) layout.law_of[{first[p] + i, first[p] + j}] = law;
      continue;
    }
    const int a = part_index(model, in.between[0]), b = part_index(model, in.between[1]);
    for (int i = 0; i < plies(a); ++i)
      for (int j = 0; j < plies(b); ++j)
        layout.law_of[{std::min(first[a] + i, first[b] + j), std::max(first[a] + i, first[b] + j)}] = law;
  }
  for (const InterfaceInput& in : sc.interfaces)
    for (const std::string& name : in.between.empty() ? std::vector<std::string>{in.plies_of} : in.between)
      if (sim.cracking && std::count(sim.cracking->parts.begin(), sim.cracking->parts.end(), part_index(model, name)))
        throw InputError(shown_path(sc.file), in.line, "interfaces",
                         "part '" + name + "' cracks (cracking:) and has a cohesive interface: crack insertion "
                         "moves element corners onto new nodes that the interface does not follow");
  InterfaceSplit made;
  try {
    made = insert_cohesive_interfaces(model, layout);
  } catch (const std::invalid_argument& e) {
    throw InputError(shown_path(sc.file), sc.interfaces.front().line, "interfaces", e.what());
  }
  for (const InterfaceInput& in : sc.interfaces) {
    std::size_t count = 0;
    const int law = static_cast<int>(&in - sc.interfaces.data());
    for (const auto& [pair, l] : layout.law_of)
      if (l == law) count += made.elements_of.count(pair) ? made.elements_of.at(pair) : 0;
    if (count == 0)
      throw InputError(shown_path(sc.file), in.line, "interfaces",
                       in.between.empty() ? "the plies of part '" + in.plies_of + "' share no face (a ply thinner "
                                                "than one element, or elements that cross plies?)"
                                          : "parts '" + in.between[0] + "' and '" + in.between[1] +
                                                "' share no face: an interface needs a conforming mesh "
                                                "(Gmsh: fragment the volumes so that they share the surface)");
  }
  sim.cohesive = std::make_unique<CohesiveInterfaces>(std::move(laws));
}

void build_contact(const Scenario& sc, Simulation& sim, const std::vector<int>& cracking) {
  if (!sc.contact && sc.walls.empty() && cracking.empty() && sc.interfaces.empty()) return;
  const std::size_t np = sim.model.parts.size(), nm = sim.materials.size();
  ContactSettings cs;
  cs.part_pairs.assign(np * np, 0);
  cs.friction.assign(nm * nm, FrictionLaw{});
  if (sc.contact) contact_pairs_and_friction(sc, sim.model, cs);
  self_contact_of_cracking_parts(sc, sim.model, cracking, cs);
  contact_across_interfaces(sc, sim.model, cs);
  for (const auto& wi : sc.walls) cs.walls.push_back(rigid_wall(wi, sim.model));
  sim.contact = cs;
}

/// Each part takes its material's erosion rule; a part whose elements become particles gets its
/// (empty) debris particle part now, so that the model has the same parts from the start and a
/// restart finds them.
void erosion_rules(const Scenario& sc, Simulation& sim, const std::string& file) {
  for (Part& part : sim.model.parts) {
    const MaterialInput& mi = sc.materials[part.material];
    if (!mi.erosion) continue;
    const ErosionInput& in = *mi.erosion;
    const std::string path = "materials." + mi.name + ".erosion";
    const Material& material = *sim.materials[part.material];
    const std::vector<std::string> names = material.state_names();
    std::string listed;
    for (const auto& n : names) listed += (listed.empty() ? "" : ", ") + n;
    ErosionRule rule;
    if (in.variable == "none") {
      rule.state_index = ErosionRule::kNoVariable;
      if (!in.inverted && !(in.distortion > 0) && !in.to_particles)
        throw InputError(file, in.line, path + ".variable",
                         "variable: none leaves the element no way to fail: give inverted: true or a distortion");
    } else if (in.variable) {
      const auto it = std::find(names.begin(), names.end(), *in.variable);
      if (it == names.end())
        throw InputError(file, in.line, path + ".variable",
                         "model " + mi.model + " has no history variable '" + *in.variable + "' (its variables: " +
                             (listed.empty() ? std::string("none") : listed) + ")");
      rule.state_index = static_cast<int>(it - names.begin());
    } else if (material.failure_state_index() < 0) {
      throw InputError(file, in.line, path,
                       "model " + mi.model + " has no failure variable of its own: name one with 'variable' (" +
                           (listed.empty() ? std::string("it has no history variables") : "one of " + listed) + ")");
    }
    rule.threshold = in.value;  // the model's own variable too (it had been held at 1 there)
    rule.point_fraction = in.fraction;
    rule.to_particles = in.to_particles;
    rule.on_inversion = in.inverted;
    rule.min_length_ratio = in.distortion;
    if (rule.to_particles) {
      if (!sc.particle_contact)
        throw InputError(file, in.line, path + ".on_failure",
                         "on_failure: particles needs a particle_contact section (the law the particles collide with)");
      (void)conversion_point_weights(*part.type);  // throws for a type it does not know
      ParticlePart debris;
      debris.name = part.name + "_particles";
      debris.dim = sim.model.dim();
      sim.model.particle_parts.push_back(std::move(debris));
    }
    part.erosion = rule;
  }
}

/// cracking.small_pieces: particles: the cracking parts must be able to make particles.
void comminution(const Scenario& sc, Simulation& sim, const std::string& file) {
  if (!sim.cracking || !sc.cracking->small_pieces_to_particles) return;
  for (const int p : sim.cracking->parts) {
    const Part& part = sim.model.parts[p];
    if (!part.erosion.to_particles)
      throw InputError(file, sc.cracking->small_pieces_line, "cracking.small_pieces",
                       "small pieces of part '" + part.name + "' cannot become particles: give its material '" +
                           sc.materials[part.material].name +
                           "' an erosion rule with on_failure: particles (variable: none if nothing else should "
                           "make its elements fail)");
  }
  sim.cracking->comminution = true;
}

void build_particle_contact(const Scenario& sc, Simulation& sim) {
  for (const auto& in : sc.particle_parts)
    if (in.grains && !sc.particle_contact)
      throw InputError(shown_path(sc.file), in.grains_line, "particles." + in.name + ".grains",
                       "loose grains need a particle_contact section (the law they collide with)");
  if (!sc.particle_contact) return;
  const ParticleContactInput& in = *sc.particle_contact;
  ParticleContactSettings s;
  s.law = find_pair_law(in.law);
  s.params = pair_law_parameters(*s.law, in.parameters);
  s.skin = in.skin;
  s.time_step_safety = in.time_step_safety;
  s.axis = sc.formulation == Formulation::axisymmetric;
  // Bonded automata meet walls, the mesh and other parts through it; their own pairs are their
  // model's.
  for (const ParticlePart& pp : sim.model.particle_parts) s.walls_only.push_back(pp.model ? 1 : 0);
  if (sim.contact) {
    s.walls = sim.contact->walls;
  } else {
    for (const auto& wi : sc.walls) s.walls.push_back(rigid_wall(wi, sim.model));
  }
  sim.particle_contact = std::make_unique<ParticleContact>(std::move(s));
}

// Adaptive remeshing (remeshing:): each part named must be of triangles, own its nodes, and
// have no cohesive interface; the probes' nodes stay through every remesh.
void build_remeshing(const Scenario& sc, Simulation& sim) {
  if (!sc.remeshing) return;
  const std::string file = shown_path(sc.file);
  const Model& model = sim.model;
  std::vector<RemeshedPart> parts;
  for (std::size_t i = 0; i < sc.remeshing->parts.size(); ++i) {
    const RemeshedPartInput& in = sc.remeshing->parts[i];
    const std::string key = "remeshing.parts[" + std::to_string(i + 1) + "].part";
    const std::size_t p = static_cast<std::size_t>(part_index(model, in.part));
    const Part& part = model.parts[p];
    if (!part.type->is_triangle() || model.formulation == Formulation::three_d)
      throw InputError(file, in.line, key,
                       "part '" + in.part + "' is made of " + part.type->name +
                           " elements: remeshing meshes parts of triangles (tri3) in 2D");
    std::vector<char> mine(model.nodes.count(), 0);
    for (const auto n : part.connectivity) mine[n] = 1;
    for (const Part& other : model.parts)
      if (&other != &part)
        for (const auto n : other.connectivity)
          if (mine[n])
            throw InputError(file, in.line, key,
                             "part '" + in.part + "' shares nodes with part '" + other.name +
                                 "' (one conforming mesh): a remeshed part must be a body of its own, in "
                                 "contact with the others");
    if (sim.cohesive)
      throw InputError(file, in.line, key, "remeshing does not carry cohesive interfaces: remove `interfaces` or `remeshing`");
    parts.push_back(RemeshedPart{p, in.settings});
  }
  std::vector<std::int64_t> kept;
  for (const auto& probe : sim.probes) kept.insert(kept.end(), probe.nodes.begin(), probe.nodes.end());
  sim.events.push_back(std::make_unique<RemeshEvent>(sim.materials, std::move(parts), sc.remeshing->triggers, std::move(kept)));
}

void solver_settings(const Scenario& sc, SolverSettings& s) {
  s.gravity = sc.gravity;
  s.end_time = sc.end_time;
  s.time_step_safety = sc.time_step_safety;
  s.q_linear = sc.bulk_viscosity_linear;
  s.q_quadratic = sc.bulk_viscosity_quadratic;
  s.q_length = sc.bulk_viscosity_length;
  s.mass_damping = sc.mass_damping;
  s.max_time_step = sc.max_time_step;
}

}  // namespace

Simulation build_simulation(Scenario& sc, const MeshData& mesh) {
  Simulation sim;
  Model& model = sim.model;
  const std::string file = shown_path(sc.file);
  model.formulation = sc.formulation;
  model.thickness = sc.thickness;
  model.nodes.dim = sc.dim();
  for (const auto& m : sc.materials)
    sim.materials.push_back(MaterialRegistry::find(m.model)->create(m.name, m.values));

  const std::vector<std::int32_t> renumber = build_parts(sc, mesh, sim);
  GroupNodeSets sets{model, renumber, file};
  apply_initial_velocities(sc, mesh, model, sets);
  apply_boundary_conditions(sc, mesh, sim, sets);
  apply_pressures(sc, mesh, sim, sets, renumber);
  const std::vector<int> cracking = cracking_parts(sc, sim);
  check_weakest_flaw_fields(sc, sim, cracking);
  build_contact(sc, sim, cracking);
  build_particle_parts(sc, sim);
  apply_initial_particle_velocities(sc, model);
  erosion_rules(sc, sim, file);
  comminution(sc, sim, file);
  build_particle_contact(sc, sim);
  solver_settings(sc, sim.settings);

  model.assign_ids();
  build_probes(sc, mesh, sim, sets);
  build_interfaces(sc, sim);
  if (sim.contact)
    sim.contact_system.emplace(sim.model, *sim.contact, sim.part_materials(),
                               static_cast<int>(sim.materials.size()));
  if (sim.cracking) sim.events.push_back(std::make_unique<CrackGrowth>(sim.model, sim.materials, *sim.cracking));
  build_remeshing(sc, sim);
  for (auto& w : crack_band_warnings(sc, sim)) sc.warnings.push_back(std::move(w));
  for (auto& w : loading_rate_warnings(sc, sim)) sc.warnings.push_back(std::move(w));
  for (auto& w : unbreakable_bond_warnings(sc, sim)) sc.warnings.push_back(std::move(w));
  for (auto& w : parts_behind_walls(sc, sim.model)) sc.warnings.push_back(std::move(w));
  for (auto& w : bodies_without_contact(sc, sim.model)) sc.warnings.push_back(std::move(w));
  for (auto& w : bodies_moving_apart(sc, sim.model)) sc.warnings.push_back(std::move(w));
  return sim;
}

}  // namespace shard
