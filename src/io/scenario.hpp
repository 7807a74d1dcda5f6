// The scenario file: declared keys, validation with file/line/key errors, and the resolved
// scenario (every default and derived value filled in, SI units) written next to the outputs.
// Reference (generated from the same declarations): docs/scenario.md.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "adapt/remesh_event.hpp"
#include "contact/wall_extent.hpp"
#include "core/parameters.hpp"
#include "core/time_table.hpp"
#include "fracture/cohesive_law.hpp"
#include "io/particle_sample.hpp"
#include "model/model.hpp"
#include "particle/packing.hpp"

namespace shard {

/// materials.<name>.erosion: when an element of the material fails, and what becomes of it.
struct ErosionInput {
  /// A history variable of the model; absent: its own failure variable; "none": no variable.
  std::optional<std::string> variable;
  double value = 1.0;
  double fraction = 0.25;               ///< of the element's integration points
  bool to_particles = false;            ///< on_failure: particles (else delete)
  bool inverted = false;                ///< an element turned inside out fails
  double distortion = 0;                ///< fails below this fraction of its first length (0: never)
  int line = 0;
};

struct MaterialInput {
  std::string name;
  std::string model;
  ParameterValues values;
  std::optional<ErosionInput> erosion;
  int line = 0;
};

/// particle_contact: the law particles (debris of converted elements, discrete elements) touch
/// each other and the rigid walls with.
struct ParticleContactInput {
  std::string law;
  std::vector<std::pair<std::string, double>> parameters;  ///< the law's, as given (SI)
  double skin = 0;
  double time_step_safety = 0.08;
  int line = 0;
};

/// parts.<name>.orientation or .laminate: the material axes of a part's elements.
struct PlyOrientationInput {
  std::array<double, 3> reference{1, 0, 0};  ///< the 0° direction (projected into the ply plane)
  std::array<double, 3> normal{0, 0, 1};     ///< the ply normal; a laminate stacks along it
  std::vector<double> angles;                ///< degrees: one (orientation) or one per ply (laminate)
  std::string layup;                         ///< the stacking code of a laminate
  double ply_thickness = 0;                  ///< 0: one orientation for the whole part
  std::optional<double> start;               ///< where ply 1 begins along the normal (default: the part's edge)
  int line = 0;
};

struct PartInput {
  std::string name;
  std::string group;
  std::string material;
  std::optional<std::string> element;  ///< a registered element type; absent: chosen from the cells
  double hourglass_coefficient = 0.1;
  VolumetricTreatment volumetric = VolumetricTreatment::standard;
  std::optional<PlyOrientationInput> orientation;
  int line = 0;
};

/// An initial velocity field on a part, a particle part or the nodes of a group:
/// v(x) = velocity + angular_velocity x (x - center) + velocity_gradient (x - center).
struct InitialVelocityInput {
  std::string part;   ///< a part or particle part (or empty)
  std::string group;  ///< a Gmsh physical group (or empty)
  std::array<double, 3> velocity{0, 0, 0};
  std::array<double, 3> angular_velocity{0, 0, 0};  ///< in 2D only [2], about z
  std::array<double, 3> center{0, 0, 0};
  std::array<double, 9> velocity_gradient{};  ///< row-major 3 x 3 (2 x 2 used in 2D)
  int line = 0;

  /// The velocity at `x` (dim components).
  std::array<double, 3> at(const double* x, int dim) const {
    std::array<double, 3> r{0, 0, 0}, v = velocity;
    for (int k = 0; k < dim; ++k) r[k] = x[k] - center[k];
    const auto& w = angular_velocity;
    const std::array<double, 3> spin{w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]};
    for (int i = 0; i < dim; ++i) {
      v[i] += spin[i];
      for (int j = 0; j < dim; ++j) v[i] += velocity_gradient[3 * i + j] * r[j];
    }
    return v;
  }
  /// The spin of the field, ½ curl v: what a particle's rotation starts at (in 2D only [2]).
  std::array<double, 3> spin() const {
    const auto& L = velocity_gradient;
    return {angular_velocity[0] + 0.5 * (L[7] - L[5]), angular_velocity[1] + 0.5 * (L[2] - L[6]),
            angular_velocity[2] + 0.5 * (L[3] - L[1])};
  }
};

struct BoundaryConditionInput {
  std::string group;
  std::array<std::optional<TimeTable>, 3> velocity;  ///< prescribed (fixed = constant 0)
  /// A rigid rotation of the group about an axis through `centre` at `rate` (rad/s).
  struct Rotation {
    std::array<double, 3> centre{0, 0, 0};
    std::array<double, 3> axis{0, 0, 1};
    TimeTable rate;
  };
  std::optional<Rotation> rotation;
  int line = 0;
};

struct PressureInput {
  std::string group;
  TimeTable pressure;
  int line = 0;
};

struct OutputSettings {
  double frame_interval = 0;
  double history_interval = 0;
  double checkpoint_interval = 0;
  double log_interval = 0;  ///< wall seconds between progress lines when not on a terminal
  bool compress = true;           ///< frames' data compressed with zlib
  bool single_precision = false;  ///< frames' real values as Float32
  std::vector<std::string> fields;
};

/// crash: what a crash engineer reads off a crush test (docs/outputs.md, "Crash outputs").
struct CrashInput {
  std::string wall;          ///< the rigid wall that measures the crushing force
  std::string stroke_part;   ///< its mean displacement towards the wall is the stroke
  std::string crushed_part;  ///< SEA: the energy over its mass per unit length × the stroke
  double cfc = 600;          ///< SAE J211 channel class of the force filter
  double sample_interval = 1e-6;
  double scale = 1;          ///< multiplies forces and energies (a slice of a wider specimen)
  double peak_window = 0;    ///< the largest mean force over a window this long is reported; 0: not
  int line = 0;
};

/// A point history: the node nearest `point` at the start (followed through cracks by its id), or
/// the mean over the nodes of a physical group, written every `interval`.
struct ProbeInput {
  std::string name;
  std::optional<std::array<double, 3>> point;
  std::string group;
  double interval = 0;  ///< 0: every step
  int line = 0;
};

struct FrictionInput {
  std::string material_a, material_b;
  double static_coefficient = 0, dynamic_coefficient = 0;
  int line = 0;
};

struct ContactInput {
  bool all_pairs = false;
  bool self_contact = false;
  std::vector<std::pair<std::string, std::string>> pairs;
  double friction = 0, dynamic_friction = 0;
  std::vector<FrictionInput> material_friction;
  double penalty_scale = 1, time_step_reduction = 0.1;
  double damping = 0.2;  ///< fraction of the critical damping of a node-facet pair
  int line = 0;
};

/// interfaces[]: cohesive interfaces between two parts or between the plies of a laminate part.
struct InterfaceInput {
  std::vector<std::string> between;  ///< two parts that share a surface; or empty and:
  std::string plies_of;              ///< a laminate part: every boundary between two plies
  CohesiveLaw law;
  double friction = 0;               ///< Coulomb coefficient once failed (contact between the sides)
  int line = 0;
};

struct WallInput {
  std::string name;
  std::array<double, 3> point{0, 0, 0}, normal{0, 0, 0};
  std::array<std::optional<TimeTable>, 3> velocity;
  double friction = 0, dynamic_friction = 0;
  std::vector<std::string> parts;  ///< empty: all
  WallExtent extent;               ///< the whole plane unless `extent:` is given
  int line = 0;
};

/// A material of movable cellular automata (`model: automaton`).
struct AutomatonMaterialInput {
  std::string name;
  MCAMaterial material;
  int line = 0;
};

/// The bond law between automata of two materials (the order of the two does not matter).
struct BondInput {
  std::string material_a, material_b;
  BondLaw law;
  int line = 0;
};

/// A region of a particle sample: a box, a ball (disc in 2D), or the layer at one side of the
/// sample's bounding box.
struct RegionInput {
  enum class Kind { everywhere, box, ball, side } kind = Kind::everywhere;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0}, centre{0, 0, 0};
  double radius = 0;
  int axis = 0;
  bool at_max = false;
  double depth = 0;  ///< side: automata whose centre is within this of the extreme
  bool contains(const double* x, int dim) const;
};

struct ParticlePartInput {
  std::string name;
  int line = 0;
  PackingSpec packing;              ///< lattice, size, box, angle (materials by index later)
  /// The automata read from `sample` instead of built (packing then holds only the lattice, the
  /// size, the plane and the bond tolerance; no regions, inclusions, pores or interphase).
  std::optional<ParticleSample> sample;
  std::string material;
  std::vector<std::pair<std::string, RegionInput>> material_regions;
  std::optional<InclusionSpec> inclusions;
  std::string inclusion_material;
  std::optional<PoreSpec> pores;
  std::optional<InterphaseSpec> interphase;
  double time_step_safety = 0.25;
  int contact_update_interval = 0;
  double contact_skin = 0;
  std::array<double, 3> velocity{0, 0, 0};
  bool grains = false;  ///< loose grains in particle contact, not bonded automata
  int grains_line = 0;
};

/// Conditions on a region of automata: fixed or prescribed velocity components (`rotation`
/// holds the angular velocity at zero), or none: a monitor whose mean displacement is reported.
struct ParticleBoundaryInput {
  std::string name, part;
  RegionInput region;
  std::array<std::optional<TimeTable>, 3> velocity;
  bool fix_rotation = false;
  int line = 0;
};

/// Discrete crack insertion (docs/theory/crack_insertion.md).
struct CrackingInput {
  std::vector<std::string> parts;  ///< empty: every tri3 part whose material has a failure map
  double failure_threshold = 1.0;
  int min_fragment_elements = 3;   ///< no crack cuts off a piece of fewer elements
  double friction = 0.25;          ///< Coulomb coefficient between crack faces
  /// small_pieces: particles — a piece a crack would cut off below min_fragment_elements becomes
  /// particles (comminution) instead of the crack being refused.
  bool small_pieces_to_particles = false;
  int small_pieces_line = 0;
  double tip_speed_limit = 0;     ///< m/s; 0: a node splits as soon as it fails
  double nucleation_spacing = 0;  ///< m; 0: three times the node's longest edge
  int line = 0;
};

/// remeshing: adaptive remeshing of parts of triangles (docs/theory/adaptive_remeshing.md).
struct RemeshedPartInput {
  std::string part;
  RemeshSettings settings;
  int line = 0;
};
struct RemeshingInput {
  RemeshTriggers triggers;
  std::vector<RemeshedPartInput> parts;
  int line = 0;
};

struct Scenario {
  std::filesystem::path file;
  std::string title;

  Formulation formulation = Formulation::plane_strain;
  double end_time = 0;
  int end_time_line = 0;  ///< where end_time is given (a refused step count points there)
  /// When end_time came from the command line: " (the value given by --set ...)" (and no line).
  std::string end_time_note;
  double time_step_safety = 0.9;
  double max_time_step = 0;
  double thickness = 1;
  double bulk_viscosity_linear = 0.06;
  double bulk_viscosity_quadratic = 1.5;
  double bulk_viscosity_length = 0;  ///< 0: the linear term is C_l times the element length
  double mass_damping = 0;
  double initial_temperature = 293.15;
  std::int64_t max_steps = 0;
  double energy_error_limit = 0.05;  ///< the run stops when |energy_error| exceeds it (0: never)
  std::array<double, 3> gravity{0, 0, 0};

  std::filesystem::path mesh_file;  ///< absolute
  double mesh_size = 0;             ///< m; 0: as the file says
  double mesh_unit = 1;             ///< m per coordinate unit of the file
  int mesh_line = 0;
  int mesh_size_line = 0;
  std::int64_t mesh_max_elements = 10000000;  ///< refused above this estimate (mesh.max_elements)

  bool has_mesh = true;  ///< false for a scenario of particle parts only
  std::vector<MaterialInput> materials;
  std::vector<AutomatonMaterialInput> automaton_materials;
  std::vector<BondInput> bonds;
  std::vector<ParticlePartInput> particle_parts;
  std::vector<ParticleBoundaryInput> particle_conditions;
  std::vector<PartInput> parts;
  std::vector<InitialVelocityInput> initial_velocities;
  /// Values that parse but are likely mistakes ("file:line: key 'k': ..."), said by check and run.
  std::vector<std::string> warnings;
  std::vector<BoundaryConditionInput> boundary_conditions;
  std::vector<PressureInput> pressures;
  std::optional<ContactInput> contact;
  std::optional<CrackingInput> cracking;
  std::optional<RemeshingInput> remeshing;
  std::vector<WallInput> walls;
  std::vector<InterfaceInput> interfaces;
  std::optional<ParticleContactInput> particle_contact;
  OutputSettings output;
  std::optional<CrashInput> crash;
  std::vector<ProbeInput> probes;

  YAML::Node resolved;  ///< the scenario as resolved (SI, defaults filled in)

  int dim() const { return formulation == Formulation::three_d ? 3 : 2; }
};

/// The largest scenario file read (larger ones are refused before parsing, with this figure).
inline constexpr std::uintmax_t kMaxScenarioBytes = 4u * 1024 * 1024;

/// One value put over the scenario file's before it is read (`shard run X.yaml --set key=value`,
/// the Python module's Scenario.set): `key` is a dotted path such as
/// "materials.alumina.tensile_strength" or "boundary_conditions[2].velocity.x" (list entries
/// counted from 1, as messages count them); `value` is YAML text ("450 MPa", "[0, -5 m/s]").
struct ScenarioOverride {
  std::string key;
  std::string value;
};

/// Parses "key=value" (the command line's form). Throws InputError when there is no '=' or no key.
ScenarioOverride parse_override(const std::string& text);

/// " (the value given by --set KEY=VALUE)": what an error or a warning about the value of `o`
/// says in place of a line of the file.
std::string given_by(const ScenarioOverride& o);

/// given_by the override when `key` (a reader's key, such as
/// "parts.bar.group") is, or lies under or above, one of `overrides`; "" otherwise. An error
/// about such a value has no line in the file: it names the override instead.
std::string override_note(const std::string& key, const std::vector<ScenarioOverride>& overrides);

/// Reads and validates a scenario file (not the mesh), with `overrides` put over it in order.
/// Throws InputError; an error in an overridden value names "--set KEY".
Scenario read_scenario(const std::filesystem::path& file, const std::vector<ScenarioOverride>& overrides = {});

/// One section of the declared scenario schema (for the generated reference).
struct SchemaSection {
  std::string path;     ///< "analysis", "parts.<name>", "boundary_conditions[]", ...
  std::string summary;
  KeyList keys;
};
std::vector<SchemaSection> scenario_schema();

/// The scenario reference in Markdown, generated from the declarations (docs/scenario.md).
std::string scenario_reference_markdown();

/// Writes `node` as YAML text.
std::string to_yaml_text(const YAML::Node& node);

}  // namespace shard
