#include "io/scenario.hpp"

#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "contact/pair_law.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "core/units.hpp"
#include "io/scenario_interfaces.hpp"
#include "io/scenario_remeshing.hpp"
#include "io/scenario_particles.hpp"
#include "io/scenario_section.hpp"
#include "material/laminate.hpp"
#include "material/material.hpp"

namespace shard {

using scenario_detail::key_name;
using scenario_detail::line_of;
using scenario_detail::Section;
using scenario_detail::unreadable_file_reason;
using scenario_detail::velocity_component_keys;

// ---------------------------------------------------------------------------------------------
// The schema: every key, declared once.
// ---------------------------------------------------------------------------------------------
namespace {

/// Whether `text` names `key` as a whole word ("m" is not in "mu", "density" not in
/// "flaw_density").
bool names_key(const std::string& text, const std::string& key) {
  auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const auto end = at + key.size();
    if ((at == 0 || !word(text[at - 1])) && (end == text.size() || !word(text[end]))) return true;
  }
  return false;
}

const std::vector<std::string> kFieldNames = {"displacement", "velocity", "stress",      "strain",
                                              "von_mises",    "pressure", "temperature", "state",
                                              "part"};

KeyList top_keys() {
  KeyList k;
  k.add("title", ValueKind::text, "a line describing the scenario").defaults_to("\"\"");
  k.add("analysis", ValueKind::section, "formulation, end time, time step, viscosity, damping")
      .must_be_given();
  k.add("mesh", ValueKind::section, "the Gmsh geometry or mesh file (needed by `parts`)");
  k.add("materials", ValueKind::section, "named materials: `<name>: {model: ..., ...}`")
      .must_be_given();
  k.add("parts", ValueKind::section,
        "named parts: a physical group of the mesh + a material + an element formulation "
        "(a scenario has parts, particles or both)");
  k.add("bonds", ValueKind::list, "bond laws between automaton materials (docs/theory/mca.md)")
      .defaults_to("[]");
  k.add("particles", ValueKind::section,
        "named particle parts: packed samples of movable cellular automata (docs/theory/mca.md)");
  k.add("particle_boundary_conditions", ValueKind::list,
        "fixed or prescribed motion of regions of automata, and monitors")
      .defaults_to("[]");
  k.add("initial_conditions", ValueKind::list, "initial velocity per part").defaults_to("[]");
  k.add("boundary_conditions", ValueKind::list,
        "fixed, symmetry and prescribed-velocity conditions on physical groups")
      .defaults_to("[]");
  k.add("loads", ValueKind::list, "pressure on boundary groups").defaults_to("[]");
  k.add("contact", ValueKind::section,
        "penalty contact with Coulomb friction between parts (theory: docs/theory/contact.md)");
  k.add("walls", ValueKind::list, "rigid planes, fixed or moving, with friction").defaults_to("[]");
  k.add("interfaces", ValueKind::list,
        "cohesive interfaces between parts or plies, failing in mixed mode (docs/theory/cohesive_interfaces.md)")
      .defaults_to("[]");
  k.add("particle_contact", ValueKind::section,
        "the contact law particles touch each other and the walls with (docs/theory/particle_contact.md)");
  k.add("cracking", ValueKind::section,
        "discrete crack insertion in tri3 parts of a cracking material (docs/theory/crack_insertion.md)");
  k.add("remeshing", ValueKind::section,
        "adaptive remeshing of parts of triangles: when, to what sizes, how the state is carried "
        "(docs/theory/adaptive_remeshing.md)");
  k.add("probes", ValueKind::list,
        "point histories: position, velocity, acceleration and stress at a point or a group, at their own "
        "interval, in probe_<name>.csv")
      .defaults_to("[]");
  k.add("crash", ValueKind::section,
        "crash outputs of a crush test: crushing force (SAE J211 filtered), stroke, absorbed energy, SEA, "
        "crush-force efficiency (docs/outputs.md)");
  k.add("output", ValueKind::section, "frames, history, checkpoints").defaults_to("{}");
  return k;
}

KeyList analysis_keys() {
  KeyList k;
  k.choice("formulation", {"plane_strain", "plane_stress", "axisymmetric", "3d"},
           "idealisation: 2D plane strain / plane stress (x, y), axisymmetric (x = r, y = z), or 3D")
      .must_be_given();
  k.quantity("end_time", dim::time, "simulated time to run").above(0).must_be_given();
  k.quantity("time_step_safety", dim::none, "fraction of the stable time step used")
      .above(0)
      .at_most(1)
      .defaults_to("0.9");
  k.quantity("max_time_step", dim::time, "upper limit on the time step (0: none)")
      .at_least(0)
      .defaults_to("0");
  k.quantity("thickness", dim::length, "out-of-plane thickness (plane strain / plane stress)")
      .above(0)
      .defaults_to("1 m");
  k.quantity("bulk_viscosity_linear", dim::none, "linear bulk viscosity coefficient C_l")
      .at_least(0)
      .at_most(1)
      .defaults_to("0.06");
  k.quantity("bulk_viscosity_length", dim::length,
             "the linear bulk viscosity as a length l_v instead of C_l times the element length: "
             "the same viscous pressure rho c l_v |rate| on every mesh (for rate-dependent damage, "
             "whose answer depends on how fast the wave front rises); 0: C_l")
      .at_least(0)
      .defaults_to("0");
  k.quantity("bulk_viscosity_quadratic", dim::none, "quadratic bulk viscosity coefficient C_q")
      .at_least(0)
      .at_most(4)
      .defaults_to("1.5");
  k.quantity("mass_damping", dim::rate,
             "mass-proportional damping α (force −α m v), for quasi-static runs")
      .at_least(0)
      .defaults_to("0");
  k.quantity("initial_temperature", dim::temperature, "initial temperature of every part")
      .above(0)
      .defaults_to("293.15 K");
  k.add("max_steps", ValueKind::integer,
        "stop with an error after this many steps (0: no limit; a run estimated at more than 1e9 "
        "steps is refused unless this is set)")
      .at_least(0)
      .defaults_to("0");
  k.quantity("energy_error_limit", dim::none,
             "stop with an error when the energy balance's relative error (history.csv's energy_error) "
             "exceeds this, at a history row from 5 % of end_time on, naming the terms that moved most since the last row; "
             "0: never stop")
      .at_least(0)
      .defaults_to("0.05");
  KeySpec& g = k.add("gravity", ValueKind::vector, "body force per unit mass, e.g. [0, -9.81 m/s^2]");
  g.dimension = dim::acceleration;
  g.defaults_to("[0, 0, 0]");
  return k;
}

KeyList contact_keys() {
  KeyList k;
  k.add("pairs", ValueKind::list,
        "parts in contact: `all` (every pair of different parts) or a list of pairs [[a, b], ...]; "
        "[a, a] is self-contact")
      .must_be_given();
  k.add("self_contact", ValueKind::boolean, "with `pairs: all`, also each part with itself")
      .defaults_to("false");
  k.quantity("friction", dim::none, "Coulomb coefficient μ_s of every pair (static)")
      .at_least(0)
      .defaults_to("0");
  k.quantity("dynamic_friction", dim::none, "sliding coefficient μ_d")
      .at_least(0)
      .defaults_to("friction");
  k.add("material_friction", ValueKind::list,
        "per pair of materials: [{materials: [a, b], static: 0.3, dynamic: 0.25}]")
      .defaults_to("[]");
  k.quantity("penalty_scale", dim::none, "multiplies the automatic penalty stiffness").above(0).defaults_to("1");
  k.quantity("time_step_reduction", dim::none,
             "the automatic penalty keeps the stable time step within this fraction of the elements' one")
      .above(0)
      .below(1)
      .defaults_to("0.1");
  k.quantity("damping", dim::none,
             "normal contact damping: a dashpot beside each penalty spring, this fraction of the critical "
             "damping of the node-facet pair (0: the bare penalty, which rings after an impact)")
      .at_least(0)
      .defaults_to("0.2");
  return k;
}

KeyList cracking_keys() {
  KeyList k;
  k.add("parts", ValueKind::list, "the parts that crack")
      .defaults_to("every tri3 part whose material has a failure map (rotating_crack; a denoual_forquin_hild part only when named)");
  k.quantity("failure_threshold", dim::none, "nodal failure factor at which a node splits")
      .above(0)
      .defaults_to("1");
  k.add("min_fragment_elements", ValueKind::integer,
        "no crack opens that would cut off a piece of fewer elements (1: no limit); the material of "
        "smaller pieces stays a smeared crack")
      .at_least(1)
      .defaults_to("3");
  k.quantity("friction", dim::none,
             "Coulomb coefficient between crack faces (they close and slide in contact)")
      .at_least(0)
      .defaults_to("0.25");
  k.choice("small_pieces", {"smeared", "particles"},
           "what becomes of a piece a crack would cut off below min_fragment_elements: smeared (the "
           "crack is refused, the material stays a smeared crack) or particles (comminution: the "
           "piece's elements become particles; the material needs erosion with on_failure: particles)")
      .defaults_to("smeared");
  k.quantity("tip_speed_limit", dim::velocity,
             "the fastest a crack tip may run (e.g. 4300 m/s): a node a crack has reached opens its next "
             "edge only once the tip could have crossed it at this speed, and a new crack starts only "
             "nucleation_spacing away from every crack; not given: a node splits as soon as it fails")
      .above(0);
  k.quantity("nucleation_spacing", dim::length,
             "with tip_speed_limit: no new crack starts nearer than this to a crack node or to another "
             "new crack of the same update")
      .above(0)
      .defaults_to("three times the node's longest edge");
  return k;
}

KeyList material_friction_keys() {
  KeyList k;
  k.add("materials", ValueKind::list, "two material names").must_be_given();
  k.quantity("static", dim::none, "static coefficient μ_s").at_least(0).must_be_given();
  k.quantity("dynamic", dim::none, "dynamic coefficient μ_d").at_least(0).defaults_to("static");
  return k;
}

KeyList erosion_keys() {
  KeyList k;
  k.add("variable", ValueKind::text,
        "the history variable a point fails on (a name from the model's state, or none: the "
        "element fails only by its shape or by comminution); default: the model's own failure "
        "variable (Johnson–Cook: damage)");
  k.quantity("value", dim::none, "the value at which a point has failed (of the variable named, or of the model's own)")
      .above(0)
      .defaults_to("1");
  k.quantity("fraction", dim::none, "the fraction of the element's integration points that must have failed")
      .above(0)
      .at_most(1)
      .defaults_to("0.25");
  k.add("inverted", ValueKind::boolean,
        "an element that turns inside out fails (false: the run stops there with an error)")
      .defaults_to("false");
  k.quantity("distortion", dim::none,
             "an element fails when its characteristic length (smallest altitude) falls below this "
             "fraction of its length at its first step (0: never)")
      .at_least(0)
      .below(1)
      .defaults_to("0");
  k.choice("on_failure", {"delete", "particles"},
           "delete: the element leaves, its nodes keep the mass; particles: it becomes one particle "
           "per integration point that keeps its mass and momentum")
      .defaults_to("delete");
  return k;
}

/// The dimension of a pair-law parameter from its declared unit.
Dimension law_parameter_dimension(const std::string& unit) {
  if (unit == "Pa") return dim::pressure;
  if (unit == "N/m") return dim::force / dim::length;
  return dim::none;
}

KeyList particle_contact_keys() {
  KeyList k;
  k.choice("law", pair_law_names(), "the contact law of particles (docs/theory/contact_laws.md)").must_be_given();
  k.quantity("skin", dim::length, "neighbour-list skin (0: a tenth of the smallest radius)").at_least(0).defaults_to("0");
  k.quantity("time_step_safety", dim::none, "fraction of the stiffest contact's stable step 2/ω")
      .above(0)
      .at_most(1)
      .defaults_to("0.08");
  // Every law's parameters (each checked against the chosen law once it is known).
  for (const auto& name : pair_law_names())
    for (const auto& p : find_pair_law(name)->parameters)
      if (!k.find(p.name)) k.quantity(p.name, law_parameter_dimension(p.unit), p.description);
  return k;
}

KeyList wall_keys() {
  KeyList k;
  k.add("name", ValueKind::text, "name used in history.csv columns").must_be_given();
  KeySpec& p = k.add("point", ValueKind::vector, "a point of the plane at t = 0");
  p.dimension = dim::length;
  p.must_be_given();
  KeySpec& n = k.add("normal", ValueKind::vector, "normal pointing to the side where the bodies are");
  n.must_be_given();
  k.quantity("friction", dim::none, "Coulomb coefficient (static)").at_least(0).defaults_to("0");
  k.quantity("dynamic_friction", dim::none, "sliding coefficient").at_least(0).defaults_to("friction");
  k.add("velocity", ValueKind::section, "wall velocity per component: {y: -1 m/s} or time tables");
  k.add("parts", ValueKind::list, "the mesh parts it acts on (default: all); particles meet every wall").defaults_to("all");
  k.add("extent", ValueKind::section, "a finite wall: a rigid plate, the rectangle of the plane from `point` as its corner and `depth` behind it (default: the whole plane)");
  return k;
}

KeyList wall_extent_keys() {
  KeyList k;
  KeySpec& a = k.add("along", ValueKind::vector, "a direction in the plane, from `point` along the rectangle's length");
  a.dimension = dim::none;
  a.must_be_given();
  k.quantity("length", dim::length, "the rectangle's length along `along`").above(0).must_be_given();
  k.quantity("width", dim::length, "3D: its width along normal × along (default: unbounded)").above(0);
  k.quantity("depth", dim::length, "the thickness of the wall's plate behind its plane: a point behind it is pushed out through the plate's nearest face (the wall's face, its back or an edge face), a point deeper has gone past it (default: unbounded)").above(0);
  return k;
}

KeyList mesh_keys() {
  KeyList k;
  k.add("file", ValueKind::text,
        "Gmsh file, relative to the scenario: .geo (meshed at load time) or .msh")
      .must_be_given();
  k.quantity("size", dim::length, "element size for meshing a .geo (Mesh.MeshSizeMax)").above(0);
  k.quantity("unit", dim::length, "length of one coordinate unit of the file (e.g. 1 mm)")
      .above(0)
      .defaults_to("1 m");
  k.add("max_elements", ValueKind::integer,
        "largest element count a .geo may be meshed into at `size`, estimated from its bounding box "
        "before meshing (raise it for a larger mesh)")
      .at_least(1)
      .defaults_to("10000000");
  return k;
}

KeyList part_keys() {
  KeyList k;
  k.add("group", ValueKind::text, "the Gmsh physical group (surface in 2D, volume in 3D)")
      .defaults_to("the part's name");
  k.add("material", ValueKind::text, "name of a material in `materials`").must_be_given();
  k.choice("element", element_type_names(),
           "element formulation (default from the mesh: tri3, tet4, or hex8_reduced for hexahedra)");
  k.quantity("hourglass_coefficient", dim::none,
             "viscous hourglass control κ (hex8_reduced)")
      .at_least(0)
      .at_most(0.5)
      .defaults_to("0.1");
  k.choice("volumetric", {"standard", "average_nodal_pressure", "mean_dilatation"},
           "treatment of the dilatation against volumetric locking in plastic flow: "
           "average_nodal_pressure for tri3/tet4, mean_dilatation (B-bar) for hex8")
      .defaults_to("standard");
  k.add("orientation", ValueKind::section,
        "material axes of an orthotropic material, the same for every element: {reference, normal, "
        "angle} (docs/theory/composite_damage.md)");
  k.add("laminate", ValueKind::section,
        "material axes ply by ply from a stacking sequence through the part: {layup, ply_thickness, "
        "normal, reference, start} (docs/theory/composite_damage.md)");
  return k;
}

KeyList orientation_keys(bool laminate) {
  KeyList k;
  KeySpec& r = k.add("reference", ValueKind::vector,
                     "the 0° fibre direction, three components even in 2D (projected into the ply's plane)");
  r.defaults_to("[1, 0, 0]");
  KeySpec& n = k.add("normal", ValueKind::vector,
                     laminate ? "the ply normal, three components: plies stack along it, ply 1 first"
                              : "the ply normal (axis 3), three components");
  n.defaults_to("[0, 0, 1]");
  if (!laminate) {
    k.quantity("angle", dim::none, "the fibre angle in degrees, about the normal from the reference")
        .at_least(-180)
        .at_most(180)
        .defaults_to("0");
    return k;
  }
  k.add("layup", ValueKind::text, "the stacking sequence, e.g. \"[(0/45/90/-45/0)2]s\" (angles in degrees)")
      .must_be_given();
  k.quantity("ply_thickness", dim::length, "the thickness of one ply").above(0).must_be_given();
  k.quantity("start", dim::length,
             "where ply 1 begins, as a coordinate along the normal (default: the part's lowest node)");
  return k;
}

KeyList initial_condition_keys() {
  KeyList k;
  k.add("part", ValueKind::text, "a part or particle part whose nodes or particles start moving (or give `group`)");
  k.add("group", ValueKind::text, "a Gmsh physical group whose nodes start moving (instead of `part`)");
  KeySpec& v = k.add("velocity", ValueKind::vector,
                     "velocity [vx, vy(, vz)] at `center` (of every point when nothing else is given)");
  v.dimension = dim::velocity;
  v.default_text = "[0, 0(, 0)]";
  KeySpec& w = k.add("angular_velocity", ValueKind::vector,
                     "rigid rotation about `center`: a rate in 2D (about z, counter-clockwise), [wx, wy, wz] "
                     "in 3D; particles also spin at it");
  w.dimension = dim::rate;
  KeySpec& c = k.add("center", ValueKind::vector, "the point the rotation and the velocity gradient are about");
  c.dimension = dim::length;
  c.default_text = "[0, 0(, 0)]";
  KeySpec& l = k.add("velocity_gradient", ValueKind::list,
                     "a linear velocity field v = velocity + L (x - center): L as rows [[dvx/dx, dvx/dy], [dvy/dx, "
                     "dvy/dy]] (3 x 3 in 3D), each a rate");
  l.dimension = dim::rate;
  return k;
}

KeyList boundary_condition_keys() {
  KeyList k;
  k.add("group", ValueKind::text, "a Gmsh physical group (any dimension)").must_be_given();
  k.add("fix", ValueKind::list, "components held at zero velocity, e.g. [x, y] (one condition per component)");
  k.choice("symmetry", {"x", "y", "z"},
           "symmetry plane normal to this axis (its normal velocity is zero)");
  k.add("velocity", ValueKind::section,
        "prescribed velocity per component: {x: 10 m/s} or {y: [[0, 0], [1 us, -5 m/s]]}");
  k.add("rotation", ValueKind::section,
        "a rigid rotation of the group: {centre: [0, 0], rate: 100 rad/s} (3D: also axis: [0, 0, 1]); each node "
        "moves along the chord of its circle, so a turn of any size keeps it on the circle");
  return k;
}

KeyList rotation_keys() {
  KeyList k;
  KeySpec& c = k.add("centre", ValueKind::vector, "a point of the axis, e.g. [0, 0]");
  c.dimension = dim::length;
  c.must_be_given();
  KeySpec& r = k.add("rate", ValueKind::table, "angular velocity (counter-clockwise about the axis), or a time table");
  r.dimension = dim::rate;
  r.must_be_given();
  KeySpec& a = k.add("axis", ValueKind::vector, "the axis direction (3D; 2D turns about z)");
  a.dimension = dim::none;
  a.defaults_to("[0, 0, 1]");
  return k;
}

}  // namespace

KeyList scenario_detail::velocity_component_keys() {
  KeyList k;
  for (const char* c : {"x", "y", "z"}) {
    KeySpec& s = k.add(c, ValueKind::table, std::string("velocity along ") + c);
    s.dimension = dim::velocity;
  }
  return k;
}

namespace {

KeyList load_keys() {
  KeyList k;
  k.add("group", ValueKind::text, "a boundary physical group (curves in 2D, surfaces in 3D)")
      .must_be_given();
  KeySpec& p = k.add("pressure", ValueKind::table, "pressure, positive pushing into the body");
  p.dimension = dim::pressure;
  p.must_be_given();
  return k;
}

KeyList output_keys() {
  KeyList k;
  k.quantity("frame_interval", dim::time, "time between VTU frames").above(0).defaults_to(
      "end_time / 20");
  k.quantity("history_interval", dim::time, "time between history.csv rows (0: every step)")
      .at_least(0)
      .defaults_to("end_time / 1000");
  k.quantity("checkpoint_interval", dim::time,
             "time between checkpoints (0: only at the end)")
      .at_least(0)
      .defaults_to("end_time / 10");
  k.choice("compression", {"zlib", "none"},
           "frames' data arrays compressed with zlib, as ParaView writes them (or not)")
      .defaults_to("zlib");
  k.choice("precision", {"double", "single"},
           "frames' real values as Float64 or Float32 (half the size, 7 digits; history, probes and checkpoints "
           "stay exact)")
      .defaults_to("double");
  k.quantity("log_interval", dim::time,
             "wall-clock seconds between progress lines when the output is not a terminal")
      .above(0)
      .defaults_to("10 s");
  std::string all;
  for (const auto& f : kFieldNames) all += (all.empty() ? "" : ", ") + f;
  k.add("fields", ValueKind::list,
        "frame fields, any of: " + all + ", or a history variable of a material a part uses (e.g. damage)")
      .defaults_to("all");
  return k;
}

// ---------------------------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------------------------

Formulation formulation_from(const std::string& s) {
  if (s == "plane_strain") return Formulation::plane_strain;
  if (s == "plane_stress") return Formulation::plane_stress;
  if (s == "axisymmetric") return Formulation::axisymmetric;
  return Formulation::three_d;
}

/// yaml-cpp's reason for a syntax error, with what usually causes it. yaml-cpp notices some
/// mistakes only on a later line, so the hint names the lines before too. A tab in an
/// indentation is reported at its own line.
std::pair<int, std::string> yaml_syntax_error(const std::string& file, int line, const std::string& msg) {
  std::ifstream in(file);
  std::string text;
  for (int n = 1; n <= line && std::getline(in, text); ++n) {
    const auto indent_end = text.find_first_not_of(" \t");
    if (indent_end != std::string::npos && text[indent_end] != '#' && text.find('\t') < indent_end)
      return {n, "not valid YAML: this line is indented with a tab; YAML indentation must use spaces"};
  }
  std::string hint;
  if (msg == YAML::ErrorMsg::END_OF_MAP_FLOW)
    hint = "a '{' on this line or before it is not closed by '}'";
  else if (msg == YAML::ErrorMsg::END_OF_SEQ_FLOW)
    hint = "a '[' on this line or before it is not closed by ']'";
  else if (msg == YAML::ErrorMsg::FLOW_END)
    hint = "a '}' or ']' that does not match the bracket it closes";
  else if (msg == YAML::ErrorMsg::MAP_VALUE)
    hint = "a ':' where none can be: a key on this line or the line before may lack its ':' as "
           "in 'key: value', or a value holding ': ' needs quotes";
  else if (msg == YAML::ErrorMsg::END_OF_MAP || msg == YAML::ErrorMsg::END_OF_SEQ ||
           msg == YAML::ErrorMsg::BLOCK_ENTRY)
    hint = "the indentation of this line does not match the lines before it: the keys of one "
           "section line up, and so do the '- ' entries of a list";
  return {line, "not valid YAML: " + msg + (hint.empty() ? "" : " (" + hint + ")")};
}

int component_index(const std::string& c) { return c == "x" ? 0 : c == "y" ? 1 : c == "z" ? 2 : -1; }

}  // namespace

namespace {

/// Reads the sections of a scenario in order; what later sections check against (the dimension,
/// the material and part names) is kept between them.
class ScenarioReader {
 public:
  ScenarioReader(const YAML::Node& root, const std::filesystem::path& path, Scenario& scenario)
      : file(path.string()), sc(scenario), top_list(top_keys()), top(root, file, "", top_list, sc.resolved, 0) {}

  void read() {
    sc.title = top.text("title");
    analysis();
    mesh();
    materials();
    parts();
    boundary_conditions();
    loads();
    contact();
    walls();
    scenario_detail::read_interfaces(top, sc);
    particle_contact();
    cracking();
    scenario_detail::read_remeshing(top, sc);
    scenario_detail::read_particle_sections(top, sc);
    initial_conditions();  // after the particle parts, which it may name
    scenario_detail::read_crash(top, sc);
    output();
    scenario_detail::read_probes(top, sc);  // after output: its interval defaults to the history's
  }

 private:
  YAML::Node list_of(const std::string& key) {
    const YAML::Node n = top.value(key);
    if (!n.IsDefined() || n.IsNull()) return YAML::Node(YAML::NodeType::Sequence);
    if (!n.IsSequence())
      top.fail(key, "expected a list (entries starting with '- '), got " + Section::shape(n));
    return n;
  }
  void check_part(Section& sec, const std::string& key, const std::string& name) {
    if (std::find(part_names.begin(), part_names.end(), name) == part_names.end()) {
      std::string reason = "no part named '" + name + "'";
      const std::string close = closest_match(name, part_names);
      if (!close.empty()) reason += " (did you mean '" + close + "'?)";
      sec.fail(key, reason);
    }
  }

  void analysis() {
  // analysis
  const KeyList a_keys = analysis_keys();
  Section analysis(top.value("analysis"), file, "analysis", a_keys, sc.resolved["analysis"], top.line("analysis"));
  sc.formulation = formulation_from(*analysis.choice("formulation"));
  sc.end_time = analysis.number("end_time");
  sc.end_time_line = analysis.line("end_time");
  sc.time_step_safety = analysis.number("time_step_safety");
  sc.max_time_step = analysis.number("max_time_step");
  sc.thickness = analysis.number("thickness");
  if (sc.formulation == Formulation::axisymmetric) {
    if (analysis.has("thickness"))
      analysis.warn(0, "thickness", "not used by an axisymmetric run: its masses, energies and forces are those "
                                    "of the whole body of revolution (360°)");
    sc.resolved["analysis"].remove("thickness");  // not in use: resolved.yaml runs as given
  }
  sc.bulk_viscosity_linear = analysis.number("bulk_viscosity_linear");
  sc.bulk_viscosity_quadratic = analysis.number("bulk_viscosity_quadratic");
  sc.bulk_viscosity_length = analysis.number("bulk_viscosity_length");
  if (sc.bulk_viscosity_length > 0) {
    if (analysis.has("bulk_viscosity_linear"))
      analysis.fail("bulk_viscosity_length",
                    "give the linear bulk viscosity either as a coefficient (bulk_viscosity_linear) or as "
                    "a length (bulk_viscosity_length), not both");
    sc.resolved["analysis"].remove("bulk_viscosity_linear");  // not in use: resolved.yaml runs as given
  }
  sc.mass_damping = analysis.number("mass_damping");
  sc.initial_temperature = analysis.number("initial_temperature");
  sc.max_steps = analysis.integer("max_steps");
  sc.energy_error_limit = analysis.number("energy_error_limit");
  dim = static_cast<std::size_t>(sc.dim());
  if (analysis.has("gravity")) {
    const auto g = analysis.vector("gravity", dim);
    std::copy(g.begin(), g.end(), sc.gravity.begin());
  } else {
    YAML::Node zero(YAML::NodeType::Sequence);
    zero.SetStyle(YAML::EmitterStyle::Flow);
    for (std::size_t k = 0; k < dim; ++k) zero.push_back(0.0);
    sc.resolved["analysis"]["gravity"] = zero;
  }
  components = dim == 3 ? std::vector<std::string>{"x", "y", "z"} : std::vector<std::string>{"x", "y"};

  }

  void mesh() {
  // mesh: needed by finite-element parts; a scenario of particle parts alone has none
  if (!top.has("parts") && !top.has("particles"))
    throw InputError(file, 1, "parts",
                     "a scenario needs 'parts' (finite elements on a mesh), 'particles' (movable "
                     "cellular automata) or both");
  if (top.has("parts") && !top.has("mesh"))
    throw InputError(file, top.line("parts"), "mesh", "missing required key 'mesh': 'parts' are physical groups of a mesh");
  sc.has_mesh = top.has("mesh");
  const KeyList m_keys = mesh_keys();
  if (sc.has_mesh) {
  Section mesh(top.value("mesh"), file, "mesh", m_keys, sc.resolved["mesh"], top.line("mesh"));
  sc.mesh_line = mesh.line("file");
  std::filesystem::path mesh_file = mesh.text("file");
  if (mesh_file.is_relative()) mesh_file = sc.file.parent_path() / mesh_file;
  sc.mesh_file = mesh_file.lexically_normal();
  sc.resolved["mesh"]["file"] = sc.mesh_file.string();
  if (const std::string why = unreadable_file_reason(sc.mesh_file); !why.empty())
    mesh.fail("file", "mesh file '" + sc.mesh_file.string() + "' " + why +
                          " (a relative path is taken from the scenario file's folder)");
  sc.mesh_unit = mesh.number("unit");
  sc.mesh_size = mesh.optional_number("size").value_or(0.0);
  sc.mesh_size_line = mesh.line("size");
  sc.mesh_max_elements = mesh.integer("max_elements");
  }

  }

  void materials() {
  // materials
  const YAML::Node materials = top.value("materials");
  if (!materials.IsMap() || materials.size() == 0)
    top.fail("materials", "expected a map of named materials, e.g.\n  materials:\n    steel: {model: linear_elastic, density: 7830 kg/m^3, youngs_modulus: 210 GPa, poissons_ratio: 0.3}");
  for (auto it = materials.begin(); it != materials.end(); ++it) {
    MaterialInput mat;
    mat.name = key_name(it->first, file, "materials");
    mat.line = line_of(it->first);
    const YAML::Node body = it->second;
    const std::string path = "materials." + mat.name;
    for (const auto& other : sc.materials)
      if (other.name == mat.name)
        throw InputError(file, mat.line, path,
                         "a second material named '" + mat.name + "' (the first is at line " +
                             std::to_string(other.line) + "); material names must differ");
    if (!body.IsMap()) throw InputError(file, mat.line, path, "expected a map with 'model:' and the model's parameters");
    if (!body["model"].IsDefined())
      throw InputError(file, mat.line, path + ".model",
                       "missing required key 'model' (one of: " + [] {
                         std::string s;
                         for (const auto& n : MaterialRegistry::names()) s += (s.empty() ? "" : ", ") + n;
                         return s;
                       }() + ")");
    mat.model = body["model"].Scalar();
    if (mat.model == "automaton") {
      for (const auto& other : sc.automaton_materials)
        if (other.name == mat.name)
          throw InputError(file, mat.line, path, "a second material named '" + mat.name + "'");
      sc.automaton_materials.push_back(scenario_detail::read_automaton_material(
          body, file, mat.name, mat.line, sc.resolved["materials"][mat.name]));
      continue;
    }
    const MaterialModelInfo* info = MaterialRegistry::find(mat.model);
    if (!info) {
      std::string reason = "unknown material model '" + mat.model + "'";
      auto candidates = MaterialRegistry::names();
      candidates.push_back("automaton");
      const std::string close = closest_match(mat.model, candidates);
      if (!close.empty()) reason += " (did you mean '" + close + "'?)";
      reason += "; models: ";
      auto models = MaterialRegistry::names();
      models.push_back("automaton");
      for (std::size_t i = 0; i < models.size(); ++i) reason += (i ? ", " : "") + models[i];
      throw InputError(file, line_of(body["model"]), path + ".model", reason);
    }
    const KeyList keys = material_keys(*info);
    Section s(body, file, path, keys, sc.resolved["materials"][mat.name], mat.line);
    s.choice("model");
    if (s.has("erosion")) mat.erosion = erosion(s, mat.name);
    for (const auto& spec : keys.keys()) {
      if (spec.name == "model" || spec.name == "erosion") continue;
      if (spec.kind == ValueKind::number) {
        if (s.has(spec.name) || spec.default_text) mat.values.numbers[spec.name] = s.number(spec.name);
      } else if (spec.kind == ValueKind::choice) {
        if (const auto c = s.choice(spec.name)) mat.values.texts[spec.name] = *c;
      } else if (s.has(spec.name)) {
        mat.values.texts[spec.name] = s.text(spec.name);
      }
    }
    try {
      const auto made = info->create(mat.name, mat.values);  // the model's own consistency checks
      if (mat.model == "johnson_cook") warn_unlikely_johnson_cook(s, mat.values, made->elastic());
    } catch (const ParameterError& e) {
      // A consistency check names one key but often others as the likely cause ("or check
      // hugoniot_elastic_limit, ..."): a --set of one of those is said, since the key named may
      // be the file's untouched value.
      std::string reason = e.what();
      if (const auto& note = scenario_detail::ScenarioWarnings::override_note())
        for (const auto& spec : keys.keys())
          if (spec.name != e.key() && names_key(e.what(), spec.name))
            if (const std::string n = note(path + "." + spec.name); n.size() > 3)  // " (the value given by ...)"
              reason += " (" + spec.name + ": " + n.substr(2, n.size() - 3) + ")";
      // A model names the key at fault; when it names 'model' or a key that is not given (a
      // missing or conflicting combination), the material as a whole is at fault.
      if (e.key() != "model" && s.has(e.key())) s.fail(e.key(), reason);
      // A reason about a given key that needs a missing one ("weibull_modulus needs
      // weibull_volume ...") points at the given key's line.
      for (const auto& spec : keys.keys())
        if (spec.name != "model" && s.has(spec.name) && reason.rfind(spec.name + " ", 0) == 0) s.fail(spec.name, reason);
      throw InputError(file, mat.line, path, reason);
    }
    sc.materials.push_back(std::move(mat));
  }
  for (const auto& m : sc.materials) material_names.push_back(m.name);

  }

  void parts() {
  // parts
  const YAML::Node parts = top.value_or_null("parts");
  if (top.has("parts") && (!parts.IsMap() || parts.size() == 0))
    top.fail("parts", "expected a map of named parts, e.g.\n  parts:\n    plate: {group: plate, material: alumina, element: tri3}");
  const KeyList p_keys = part_keys();
  for (auto it = parts.IsMap() ? parts.begin() : YAML::const_iterator(); parts.IsMap() && it != parts.end(); ++it) {
    PartInput part;
    part.name = key_name(it->first, file, "parts");
    part.line = line_of(it->first);
    for (const auto& other : sc.parts)
      if (other.name == part.name)
        throw InputError(file, part.line, "parts." + part.name,
                         "a second part named '" + part.name + "' (the first is at line " +
                             std::to_string(other.line) + "); part names must differ");
    Section s(it->second, file, "parts." + part.name, p_keys, sc.resolved["parts"][part.name], part.line);
    part.group = s.text("group", part.name);
    part.material = s.text("material");
    for (const auto& a : sc.automaton_materials)
      if (a.name == part.material)
        s.fail("material", "'" + part.material + "' is an automaton material (model: automaton); "
                           "it is for particle parts, not for elements");
    if (std::find(material_names.begin(), material_names.end(), part.material) == material_names.end()) {
      std::string reason = "no material named '" + part.material + "'";
      const std::string close = closest_match(part.material, material_names);
      if (!close.empty()) reason += " (did you mean '" + close + "'?)";
      s.fail("material", reason);
    }
    if (auto e = s.choice("element")) {
      part.element = *e;
      if (element_type(*e).dim != static_cast<int>(dim)) {
        std::string fitting[2];
        for (const auto& n : element_type_names()) {
          std::string& list = fitting[element_type(n).dim == 2 ? 0 : 1];
          list += (list.empty() ? "" : ", ") + n;
        }
        s.fail("element", std::string("element '") + *e + "' does not fit formulation '" +
                              name_of(sc.formulation) + "' (2D: " + fitting[0] + "; 3D: " + fitting[1] + ")");
      }
    }
    part.hourglass_coefficient = s.number("hourglass_coefficient");
    if (auto v = s.choice("volumetric")) {
      part.volumetric = *v == "average_nodal_pressure" ? VolumetricTreatment::average_nodal_pressure
                        : *v == "mean_dilatation"      ? VolumetricTreatment::mean_dilatation
                                                       : VolumetricTreatment::standard;
      if (part.volumetric == VolumetricTreatment::average_nodal_pressure &&
          sc.formulation == Formulation::plane_stress)
        s.fail("volumetric", "average_nodal_pressure is for plane strain, axisymmetric and 3D "
                             "models; plane stress has no volumetric constraint to relieve");
    }
    if (s.has("orientation") && s.has("laminate"))
      s.fail("laminate", "give either 'orientation' (one set of axes) or 'laminate' (plies), not both");
    for (const char* key : {"orientation", "laminate"})
      if (s.has(key)) part.orientation = ply_orientation(s, part.name, key);
    sc.parts.push_back(std::move(part));
  }
  for (const auto& p : sc.parts) part_names.push_back(p.name);

  }

  void initial_conditions() {
  // initial conditions: a velocity field v = v0 + w x (x - c) + L (x - c) on a part or a group
  const KeyList ic_keys = initial_condition_keys();
  const YAML::Node ics = list_of("initial_conditions");
  YAML::Node ic_out(YAML::NodeType::Sequence);
  std::vector<std::string> moving = part_names;
  for (const auto& pp : sc.particle_parts) moving.push_back(pp.name);
  for (std::size_t i = 0; i < (ics.IsSequence() ? ics.size() : 0); ++i) {
    YAML::Node entry_out(YAML::NodeType::Map);
    Section s(ics[i], file, "initial_conditions[" + std::to_string(i + 1) + "]", ic_keys, entry_out, line_of(ics[i]));
    InitialVelocityInput ic;
    ic.line = s.line();
    if (s.has("part") == s.has("group")) s.fail("part", "give either 'part' or 'group' (one of them)");
    ic.part = s.text("part");
    ic.group = s.text("group");
    // resolved.yaml must run as a scenario: it keeps the one of the two that was given.
    entry_out.remove(s.has("part") ? "group" : "part");
    if (!ic.part.empty() && std::find(moving.begin(), moving.end(), ic.part) == moving.end()) {
      std::string reason = "no part or particle part named '" + ic.part + "'";
      const std::string close = closest_match(ic.part, moving);
      if (!close.empty()) reason += " (did you mean '" + close + "'?)";
      s.fail("part", reason);
    }
    if (!s.has("velocity") && !s.has("angular_velocity") && !s.has("velocity_gradient"))
      s.fail("velocity", "an initial condition needs velocity, angular_velocity or velocity_gradient");
    for (std::size_t j = 0; j < sc.initial_velocities.size(); ++j) {
      const InitialVelocityInput& earlier = sc.initial_velocities[j];
      if ((!ic.part.empty() && earlier.part == ic.part) || (!ic.group.empty() && earlier.group == ic.group))
        s.warn(0, ic.part.empty() ? "group" : "part",
               "initial_conditions[" + std::to_string(j + 1) + "] sets the velocity of '" +
                   (ic.part.empty() ? ic.group : ic.part) + "' too: this later one replaces it");
    }
    if (s.has("velocity")) copy_into(s.vector("velocity", dim), ic.velocity);
    if (s.has("center")) copy_into(s.vector("center", dim), ic.center);
    if (s.has("angular_velocity")) ic.angular_velocity = angular_velocity(s);
    if (s.has("velocity_gradient")) ic.velocity_gradient = velocity_gradient(s);
    sc.initial_velocities.push_back(ic);
    ic_out.push_back(entry_out);
  }
  sc.resolved["initial_conditions"] = ic_out;
  }

  static void copy_into(const std::vector<double>& from, std::array<double, 3>& to) {
    std::copy(from.begin(), from.end(), to.begin());
  }

  /// In 2D one rate about z (a scalar, or a list of one); in 3D a vector of three.
  std::array<double, 3> angular_velocity(Section& s) {
    std::array<double, 3> w{0, 0, 0};
    const YAML::Node n = s.value("angular_velocity");
    if (dim == 2 && n.IsScalar()) {
      w[2] = s.parse_number(n, s.spec("angular_velocity"), "angular_velocity");
      s.resolved()["angular_velocity"] = w[2];
    } else if (dim == 2) {
      s.fail("angular_velocity", "expected one rate about z in a 2D model (e.g. 100 rad/s), got " + Section::shape(n));
    } else {
      copy_into(s.vector("angular_velocity", 3), w);
    }
    return w;
  }

  /// dim rows of dim rates.
  std::array<double, 9> velocity_gradient(Section& s) {
    std::array<double, 9> L{};
    const YAML::Node rows = s.value("velocity_gradient");
    const std::string expected = "expected " + std::to_string(dim) + " rows of " + std::to_string(dim) +
                                 " rates, e.g. " + (dim == 2 ? "[[0, 100 1/s], [0, 0]]" : "[[0, 100 1/s, 0], [0, 0, 0], [0, 0, 0]]");
    if (!rows.IsSequence() || rows.size() != dim) s.fail("velocity_gradient", expected + ", got " + Section::shape(rows));
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t r = 0; r < dim; ++r) {
      if (!rows[r].IsSequence() || rows[r].size() != dim)
        s.fail("velocity_gradient", expected + "; row " + std::to_string(r + 1) + " is " + Section::shape(rows[r]));
      YAML::Node row(YAML::NodeType::Sequence);
      row.SetStyle(YAML::EmitterStyle::Flow);
      for (std::size_t c = 0; c < dim; ++c) {
        L[3 * r + c] = s.parse_number(rows[r][c], s.spec("velocity_gradient"), "velocity_gradient");
        row.push_back(L[3 * r + c]);
      }
      out.push_back(row);
    }
    s.resolved()["velocity_gradient"] = out;
    return L;
  }

  void boundary_conditions() {
  // boundary conditions
  const KeyList bc_keys = boundary_condition_keys();
  const YAML::Node bcs = list_of("boundary_conditions");
  YAML::Node bc_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < (bcs.IsSequence() ? bcs.size() : 0); ++i) {
    YAML::Node entry_out(YAML::NodeType::Map);
    const std::string path = "boundary_conditions[" + std::to_string(i + 1) + "]";
    Section s(bcs[i], file, path, bc_keys, entry_out, line_of(bcs[i]));
    BoundaryConditionInput bc;
    bc.line = s.line();
    bc.group = s.text("group");
    bool any = false;
    if (s.has("fix")) {
      const YAML::Node fix = s.value("fix");
      std::vector<std::string> list;
      if (fix.IsScalar()) list.push_back(fix.Scalar());
      else if (fix.IsSequence())
        for (const auto& c : fix) list.push_back(s.name_in_list("fix", c, "a component name (x, y, z)"));
      else
        s.fail("fix", "expected a list of components such as [x, y], got " + Section::shape(fix));
      if (list.size() == 1 && list[0] == "all") list = components;
      YAML::Node out(YAML::NodeType::Sequence);
      out.SetStyle(YAML::EmitterStyle::Flow);
      for (const auto& c : list) {
        const int k = component_index(c);
        if (k < 0 || k >= static_cast<int>(dim))
          s.fail("fix", "'" + c + "' is not a component of this " + std::to_string(dim) +
                            "D model (use " + (dim == 3 ? "x, y, z" : "x, y") + ", or all)");
        bc.velocity[k] = TimeTable::constant(0.0);
        out.push_back(c);
      }
      entry_out["fix"] = out;
      any = true;
    }
    // One component held two ways in one entry: the later (a velocity) silently won.
    std::array<const char*, 3> held_by{};
    for (std::size_t k = 0; k < 3; ++k)
      if (bc.velocity[k]) held_by[k] = "fix";
    if (auto sym = s.choice("symmetry")) {
      const int k = component_index(*sym);
      if (k >= static_cast<int>(dim)) s.fail("symmetry", "a 2D model has no z axis");
      if (held_by[k])
        s.fail("symmetry", "holds " + components[k] + ", which fix holds already: give each component one condition");
      bc.velocity[k] = TimeTable::constant(0.0);
      held_by[k] = "symmetry";
      any = true;
    }
    if (s.has("velocity")) {
      Section v(s.value("velocity"), file, path + ".velocity", vc_keys, entry_out["velocity"], s.line("velocity"));
      for (std::size_t k = 0; k < 3; ++k)
        if (v.has(components.size() > k ? components[k] : "z")) {
          if (k >= dim) v.fail("z", "a 2D model has no z component");
          if (held_by[k])
            v.fail(components[k], std::string("prescribes ") + components[k] + ", which " + held_by[k] +
                                      " holds at zero already: give each component one condition");
          bc.velocity[k] = v.table(components[k]);
        }
      any = true;
    }
    if (s.has("rotation")) {
      if (any) s.fail("rotation", "a rotation holds every component of the group: give it alone (no fix, symmetry or velocity)");
      static const KeyList r_keys = rotation_keys();
      Section r(s.value("rotation"), file, path + ".rotation", r_keys, entry_out["rotation"], s.line("rotation"));
      BoundaryConditionInput::Rotation rot;
      const auto centre = r.vector("centre", dim);
      std::copy(centre.begin(), centre.end(), rot.centre.begin());
      rot.rate = r.table("rate");
      if (dim == 3 && r.has("axis")) {
        const auto axis = r.vector("axis", 3);
        const double norm = std::hypot(axis[0], axis[1], axis[2]);
        if (!(norm > 0)) r.fail("axis", "the axis needs a direction (not [0, 0, 0])");
        for (int k = 0; k < 3; ++k) rot.axis[k] = axis[k] / norm;
      } else if (r.has("axis")) {
        r.fail("axis", "a 2D model turns about z: give no axis");
      }
      bc.rotation = rot;
      any = true;
    }
    if (!any)
      throw InputError(file, s.line(), path,
                       "a boundary condition needs 'fix', 'symmetry', 'velocity' or 'rotation' (e.g. {group: " +
                           bc.group + ", fix: [x, y]})");
    sc.boundary_conditions.push_back(bc);
    bc_out.push_back(entry_out);
  }
  sc.resolved["boundary_conditions"] = bc_out;

  }

  void loads() {
  // loads
  const KeyList l_keys = load_keys();
  const YAML::Node loads = list_of("loads");
  YAML::Node load_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < (loads.IsSequence() ? loads.size() : 0); ++i) {
    YAML::Node entry_out(YAML::NodeType::Map);
    Section s(loads[i], file, "loads[" + std::to_string(i + 1) + "]", l_keys, entry_out, line_of(loads[i]));
    PressureInput p;
    p.line = s.line();
    p.group = s.text("group");
    p.pressure = s.table("pressure");
    sc.pressures.push_back(p);
    load_out.push_back(entry_out);
  }
  sc.resolved["loads"] = load_out;

  }

  PlyOrientationInput ply_orientation(const Section& part, const std::string& name, const std::string& key) {
    const bool laminate = key == "laminate";
    const KeyList keys = orientation_keys(laminate);
    Section o(part.value(key), file, "parts." + name + "." + key, keys, sc.resolved["parts"][name][key],
              part.line(key));
    PlyOrientationInput in;
    in.line = o.line();
    for (auto [field, target] : {std::pair{"reference", &in.reference}, std::pair{"normal", &in.normal}}) {
      if (!o.has(field)) continue;
      const auto v = o.vector(field, 3);
      std::copy(v.begin(), v.end(), target->begin());
    }
    try {
      ply_axes(in.reference, in.normal, 0);
    } catch (const std::invalid_argument& e) {
      o.fail(o.has("reference") ? "reference" : "normal", std::string(e.what()) + ": give two directions that differ");
    }
    if (!laminate) {
      in.angles = {o.number("angle")};
      return in;
    }
    in.layup = o.text("layup");
    try {
      in.angles = parse_layup(in.layup);
    } catch (const LayupError& e) {
      o.fail("layup", e.what());
    }
    in.ply_thickness = o.number("ply_thickness");
    if (o.has("start")) in.start = o.number("start");
    return in;
  }

  /// Johnson–Cook constants that read but are unlikely to be meant: a yield stress that is a
  /// sizeable part of Young's modulus (a unit slip: the run then collapses its step), a hardening
  /// exponent above 1 (n given as per cent), and failure constants whose failure strain is not
  /// positive at zero triaxiality (D1 + D2 ≤ 0: every point that yields fails at once; the model
  /// floors it at 1e-12, docs/theory/johnson_cook.md).
  static void warn_unlikely_johnson_cook(const Section& s, const ParameterValues& v, const ElasticModuli& m) {
    auto number = [&](const char* key) { return v.numbers.count(key) ? v.numbers.at(key) : 0.0; };
    const double E = 9 * m.bulk * m.shear / (3 * m.bulk + m.shear), A = number("yield_stress");
    auto pressure = [](double x) {
      char text[32];
      std::snprintf(text, sizeof text, x >= 1e9 ? "%.3g GPa" : "%.3g MPa", x >= 1e9 ? x / 1e9 : x / 1e6);
      return std::string(text);
    };
    if (A > 0.05 * E)
      s.warn(0, "yield_stress",
             "A (" + pressure(A) + ") is " + std::to_string(static_cast<int>(std::lround(100 * A / E))) +
                 " % of Young's modulus (" + pressure(E) + "): metals yield at well under 1 %; a unit slipped in "
                 "one of them?");
    if (number("hardening_exponent") > 1)
      s.warn(0, "hardening_exponent",
             "n above 1: metals harden with n of 0.1 to 0.6 (given as per cent? 26 means n = 0.26)");
    if (v.numbers.count("failure_d1") && !(number("failure_d1") + number("failure_d2") > 0))
      s.warn(0, "failure_d1",
             "D1 + D2 is not positive: the failure strain at zero triaxiality is not, and every point "
             "that yields fails at once (the failure strain is held at 1e-12)");
  }

  ErosionInput erosion(const Section& material, const std::string& name) {
    const KeyList keys = erosion_keys();
    Section e(material.value("erosion"), file, "materials." + name + ".erosion", keys,
              sc.resolved["materials"][name]["erosion"], material.line("erosion"));
    ErosionInput in;
    in.line = e.line();
    if (e.has("variable")) in.variable = e.text("variable");
    in.value = e.number("value");
    in.fraction = e.number("fraction");
    in.to_particles = e.choice("on_failure").value_or("delete") == "particles";
    in.inverted = e.boolean("inverted");
    in.distortion = e.number("distortion");
    return in;
  }

  void particle_contact() {
    if (!top.has("particle_contact")) return;
    const KeyList keys = particle_contact_keys();
    Section c(top.value("particle_contact"), file, "particle_contact", keys, sc.resolved["particle_contact"],
              top.line("particle_contact"));
    ParticleContactInput in;
    in.line = c.line();
    in.law = *c.choice("law");
    in.skin = c.number("skin");
    in.time_step_safety = c.number("time_step_safety");
    const PairLaw& law = *find_pair_law(in.law);
    for (const auto& spec : keys.keys()) {
      if (spec.name == "law" || spec.name == "skin" || spec.name == "time_step_safety" || !c.has(spec.name)) continue;
      const bool own = std::any_of(law.parameters.begin(), law.parameters.end(),
                                   [&](const PairLawParameter& p) { return p.name == spec.name; });
      if (!own) {
        std::string names;
        for (const auto& p : law.parameters) names += (names.empty() ? "" : ", ") + p.name;
        c.fail(spec.name, "'" + spec.name + "' is not a parameter of the law " + in.law + " (its parameters: " + names + ")");
      }
      in.parameters.emplace_back(spec.name, c.number(spec.name));
      for (const auto& p : law.parameters)
        if (p.name == spec.name)
          if (const std::string why = out_of_range(p, in.parameters.back().second); !why.empty()) c.fail(spec.name, why);
    }
    std::string second;
    const std::string conflict = both_given(law, [&](const std::string& name) { return c.has(name); }, &second);
    if (!conflict.empty()) c.fail(second, conflict);
    try {
      (void)pair_law_parameters(law, in.parameters);
    } catch (const std::invalid_argument& e) {
      throw InputError(file, in.line, "particle_contact", e.what());
    }
    sc.particle_contact = in;
  }

  void contact() {
  if (top.has("contact")) {
    const KeyList c_keys = contact_keys();
    Section c(top.value("contact"), file, "contact", c_keys, sc.resolved["contact"], top.line("contact"));
    ContactInput ci;
    ci.line = c.line();
    const YAML::Node pairs = c.value("pairs");
    if (pairs.IsScalar() && pairs.Scalar() == "all") {
      ci.all_pairs = true;
      sc.resolved["contact"]["pairs"] = "all";
    } else if (pairs.IsSequence()) {
      YAML::Node out(YAML::NodeType::Sequence);
      for (const auto& pair : pairs) {
        if (!pair.IsSequence() || pair.size() != 2 || !pair[0].IsScalar() || !pair[1].IsScalar())
          c.fail("pairs", "each entry is a pair of part names [a, b], got " + Section::shape(pair));
        check_part(c, "pairs", pair[0].Scalar());
        check_part(c, "pairs", pair[1].Scalar());
        ci.pairs.emplace_back(pair[0].Scalar(), pair[1].Scalar());
        YAML::Node p(YAML::NodeType::Sequence);
        p.SetStyle(YAML::EmitterStyle::Flow);
        p.push_back(pair[0].Scalar());
        p.push_back(pair[1].Scalar());
        out.push_back(p);
      }
      sc.resolved["contact"]["pairs"] = out;
    } else {
      c.fail("pairs", "expected 'all' or a list of part pairs [[a, b], ...]");
    }
    ci.self_contact = c.boolean("self_contact");
    ci.friction = c.number("friction");
    ci.dynamic_friction = c.number("dynamic_friction", ci.friction);
    ci.penalty_scale = c.number("penalty_scale");
    ci.time_step_reduction = c.number("time_step_reduction");
    ci.damping = c.number("damping");
    if (c.has("material_friction")) {
      const YAML::Node list = c.value("material_friction");
      if (!list.IsSequence()) c.fail("material_friction", "expected a list of {materials: [a, b], static: ..}");
      const KeyList f_keys = material_friction_keys();
      YAML::Node out(YAML::NodeType::Sequence);
      for (std::size_t i = 0; i < list.size(); ++i) {
        YAML::Node entry(YAML::NodeType::Map);
        Section f(list[i], file, "contact.material_friction[" + std::to_string(i + 1) + "]", f_keys, entry, line_of(list[i]));
        const YAML::Node mats = f.value("materials");
        if (!mats.IsSequence() || mats.size() != 2) f.fail("materials", "expected two material names [a, b]");
        FrictionInput fi;
        fi.line = f.line();
        fi.material_a = mats[0].Scalar();
        fi.material_b = mats[1].Scalar();
        for (const auto& m : {fi.material_a, fi.material_b})
          if (std::find(material_names.begin(), material_names.end(), m) == material_names.end()) {
            std::string reason = "no material named '" + m + "'";
            const std::string close = closest_match(m, material_names);
            if (!close.empty()) reason += " (did you mean '" + close + "'?)";
            f.fail("materials", reason);
          }
        entry["materials"] = mats;
        fi.static_coefficient = f.number("static");
        fi.dynamic_coefficient = f.number("dynamic", fi.static_coefficient);
        ci.material_friction.push_back(fi);
        out.push_back(entry);
      }
      sc.resolved["contact"]["material_friction"] = out;
    }
    sc.contact = ci;
  }

  }

  /// walls[].extent: the rectangle must lie in the plane, so `along` may not lean off it.
  void wall_extent(Section& w, const std::string& path, YAML::Node& entry, WallInput& wi) {
    const KeyList keys = wall_extent_keys();
    Section e(w.value("extent"), file, path + ".extent", keys, entry["extent"], w.line("extent"));
    const auto along = e.vector("along", dim);
    double dot = 0, norm = 0;
    for (std::size_t k = 0; k < dim; ++k) dot += along[k] * wi.normal[k], norm += along[k] * along[k];
    if (!(norm > 0)) e.fail("along", "the direction must not be zero");
    if (std::abs(dot) > 1e-9 * std::sqrt(norm))
      e.fail("along", "must lie in the wall's plane: it is not at right angles to `normal`");
    WallExtent& x = wi.extent;
    for (std::size_t k = 0; k < dim; ++k) x.along[k] = along[k] / std::sqrt(norm);
    x.length = e.number("length");
    if (e.has("width")) {
      if (dim < 3) e.fail("width", "a 2D wall is a segment: it has a length and no width");
      x.width = e.number("width");
    }
    if (e.has("depth")) x.depth = e.number("depth");
  }

  void walls() {
  // rigid walls
  if (top.has("walls")) {
    const YAML::Node walls = list_of("walls");
    const KeyList w_keys = wall_keys();
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < walls.size(); ++i) {
      YAML::Node entry(YAML::NodeType::Map);
      const std::string path = "walls[" + std::to_string(i + 1) + "]";
      Section w(walls[i], file, path, w_keys, entry, line_of(walls[i]));
      WallInput wi;
      wi.line = w.line();
      wi.name = w.text("name");
      const auto point = w.vector("point", dim);
      const auto normal = w.vector("normal", dim);
      double norm = 0;
      for (double v : normal) norm += v * v;
      if (!(norm > 0)) w.fail("normal", "the normal must not be zero");
      for (std::size_t k = 0; k < dim; ++k) {
        wi.point[k] = point[k];
        wi.normal[k] = normal[k] / std::sqrt(norm);
      }
      wi.friction = w.number("friction");
      wi.dynamic_friction = w.number("dynamic_friction", wi.friction);
      if (w.has("velocity")) {
        Section v(w.value("velocity"), file, path + ".velocity", vc_keys, entry["velocity"], w.line("velocity"));
        for (std::size_t k = 0; k < 3; ++k)
          if (v.has(components.size() > k ? components[k] : "z")) {
            if (k >= dim) v.fail("z", "a 2D model has no z component");
            wi.velocity[k] = v.table(components[k]);
          }
      }
      if (w.has("parts")) {
        const YAML::Node parts_node = w.value("parts");
        if (parts_node.IsSequence()) {
          for (const auto& p : parts_node) {
            check_part(w, "parts", p.Scalar());
            wi.parts.push_back(p.Scalar());
          }
          entry["parts"] = parts_node;
        } else if (!(parts_node.IsScalar() && parts_node.Scalar() == "all")) {
          w.fail("parts", "expected 'all' or a list of part names");
        }
      }
      if (wi.parts.empty()) entry["parts"] = "all";
      if (w.has("extent")) wall_extent(w, path, entry, wi);
      sc.walls.push_back(wi);
      out.push_back(entry);
    }
    sc.resolved["walls"] = out;
  }

  }

  void cracking() {
  if (top.has("cracking")) {
    const KeyList k_keys = cracking_keys();
    Section k(top.value("cracking"), file, "cracking", k_keys, sc.resolved["cracking"], top.line("cracking"));
    CrackingInput ci;
    ci.line = top.line("cracking");
    if (k.has("parts")) {
      const YAML::Node list = k.value("parts");
      if (!list.IsSequence()) k.fail("parts", "expected a list of part names, e.g. [plate]");
      for (const auto& n : list) {
        const std::string name = k.name_in_list("parts", n, "a part name");
        if (std::find(part_names.begin(), part_names.end(), name) == part_names.end()) {
          std::string reason = "no part named '" + name + "'";
          const std::string close = closest_match(name, part_names);
          if (!close.empty()) reason += " (did you mean '" + close + "'?)";
          k.fail("parts", reason);
        }
        ci.parts.push_back(name);
      }
      sc.resolved["cracking"]["parts"] = list;
    }
    ci.failure_threshold = k.number("failure_threshold");
    ci.min_fragment_elements = static_cast<int>(k.integer("min_fragment_elements"));
    ci.friction = k.number("friction");
    ci.small_pieces_to_particles = k.choice("small_pieces").value_or("smeared") == "particles";
    ci.small_pieces_line = k.has("small_pieces") ? k.line("small_pieces") : ci.line;
    if (k.has("tip_speed_limit")) ci.tip_speed_limit = k.number("tip_speed_limit");
    if (k.has("nucleation_spacing")) {
      if (!k.has("tip_speed_limit"))
        k.fail("nucleation_spacing", "acts only with tip_speed_limit (the fastest a crack tip may run, e.g. 4300 m/s)");
      ci.nucleation_spacing = k.number("nucleation_spacing");
    }
    sc.cracking = ci;
  }

  }

  void output() {
  // output
  const KeyList o_keys = output_keys();
  Section out(top.value("output"), file, "output", o_keys, sc.resolved["output"], top.line("output"));
  sc.output.frame_interval = out.number("frame_interval", sc.end_time / 20);
  if (out.has("frame_interval") && sc.output.frame_interval > sc.end_time) {
    const auto& note = scenario_detail::ScenarioWarnings::override_note();
    const std::string end = note ? note("analysis.end_time") : "";
    out.warn(0, "frame_interval", "longer than analysis.end_time" + end + ": frames at the start and the end only");
  }
  sc.output.history_interval = out.number("history_interval", sc.end_time / 1000);
  if (out.has("history_interval") && sc.output.history_interval > sc.end_time) {
    // Two rows: the energy watchdog looks at the balance only at the end, and every force column
    // is a mean over the whole run.
    const auto& note = scenario_detail::ScenarioWarnings::override_note();
    const std::string end = note ? note("analysis.end_time") : "";
    out.warn(0, "history_interval", "longer than analysis.end_time" + end +
                                        ": history rows at the start and the end only (the energy balance is then "
                                        "checked only at the end, and each force column is a mean over the whole run)");
  }
  sc.output.checkpoint_interval = out.number("checkpoint_interval", sc.end_time / 10);
  sc.output.log_interval = out.number("log_interval");
  sc.output.compress = out.choice("compression").value_or("zlib") == "zlib";
  sc.output.single_precision = out.choice("precision").value_or("double") == "single";
  if (out.has("fields")) {
    const YAML::Node f = out.value("fields");
    if (!f.IsSequence()) out.fail("fields", "expected a list of field names, e.g. [stress, velocity]");
    YAML::Node fo(YAML::NodeType::Sequence);
    fo.SetStyle(YAML::EmitterStyle::Flow);
    // A field is one of the fixed names, or one history variable of a material in use
    // ("damage"), for a frame that holds what a study needs rather than every variable.
    std::vector<std::string> known = kFieldNames;
    for (const auto& m : sc.materials)
      if (const auto* info = MaterialRegistry::find(m.model);
          info && std::any_of(sc.parts.begin(), sc.parts.end(), [&](const PartInput& p) { return p.material == m.name; }))
        for (const auto& v : info->create(m.name, m.values)->state_names())
          if (std::find(known.begin(), known.end(), v) == known.end()) known.push_back(v);
    for (const auto& name : f) {
      const std::string n = out.name_in_list("fields", name, "a field name");
      if (std::find(known.begin(), known.end(), n) == known.end()) {
        std::string fixed;
        for (const auto& k : kFieldNames) fixed += (fixed.empty() ? "" : ", ") + k;
        std::string reason = "unknown field '" + n + "' (expected one of " + fixed +
                             ", or a history variable of a material a part uses)";
        const std::string close = closest_match(n, known);
        if (!close.empty()) reason += " (did you mean '" + close + "'?)";
        throw InputError(file, line_of(name), "output.fields", reason);
      }
      sc.output.fields.push_back(n);
      fo.push_back(n);
    }
    sc.resolved["output"]["fields"] = fo;
  } else {
    sc.output.fields = kFieldNames;
    YAML::Node fo(YAML::NodeType::Sequence);
    fo.SetStyle(YAML::EmitterStyle::Flow);
    for (const auto& n : kFieldNames) fo.push_back(n);
    sc.resolved["output"]["fields"] = fo;
  }
  }

  const std::string file;
  Scenario& sc;
  const KeyList top_list;
  Section top;
  const KeyList vc_keys = velocity_component_keys();
  std::size_t dim = 2;
  std::vector<std::string> components, material_names, part_names;
};

}  // namespace

namespace {

/// The text of a scenario file, refused before parsing when it cannot be a scenario: a folder,
/// an unreadable file, one larger than kMaxScenarioBytes (a scenario names its mesh and data
/// files; it does not hold them), or one that is not text (a NUL byte or invalid UTF-8).
std::string scenario_text(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(file, 0, "", path.is_absolute() ? "scenario file not found"
                                                     : "scenario file not found (looked for " +
                                                           std::filesystem::absolute(path, ec).string() + ")");
  if (std::filesystem::is_directory(path, ec))
    throw InputError(file, 0, "", "is a folder, not a scenario file (give the .yaml file in it)");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(file, 0, "", "cannot read the scenario file: " + ec.message());
  if (bytes > kMaxScenarioBytes)
    throw InputError(file, 0, "",
                     "the scenario file is " + std::to_string(bytes / (1024 * 1024)) +
                         " MiB; shard reads scenario files of up to " +
                         std::to_string(kMaxScenarioBytes / (1024 * 1024)) +
                         " MiB (meshes, particle samples and tables belong in files of their own)");
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw InputError(file, 0, "", "cannot read the scenario file");
  if (const auto bad = first_non_text_byte(text))
    throw InputError(file, 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(*bad), '\n')),
                     "", "not a text file: byte " + byte_hex(text[*bad]) +
                             " is not UTF-8 text (a binary file, or a file saved in another encoding)");
  return text;
}

}  // namespace

ScenarioOverride parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("", 0, "--set", "expected KEY=VALUE (e.g. materials.steel.youngs_modulus=210GPa), got '" + text + "'");
  // "key = value" (spaces around the '=', as a shell quote keeps them) means key=value.
  std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  key.erase(key.find_last_not_of(" \t") + 1);
  key.erase(0, key.find_first_not_of(" \t"));
  value.erase(0, value.find_first_not_of(" \t"));
  return {key, value};
}

namespace {

/// A section an override made because the file has none of that name: its key, and the nearest
/// name the file has beside it ("" if none is near).
struct MadeSection {
  std::string key, nearest;
};

/// `KEY=~` removes the key from its section, so that a named entry (a material, a part) goes as
/// if the file had never given it; a null left in its place would be read as an empty entry.
/// Nothing to remove is an error: a misspelt key would otherwise do nothing, silently.
template <class Fail>
MadeSection remove_key(YAML::Node& section, const std::string& name, const MadeSection& made, const Fail& fail) {
  if (!made.key.empty()) {
    const auto dot = made.key.rfind('.');
    fail("the file has no '" + made.key.substr(dot == std::string::npos ? 0 : dot + 1) + "'" +
         (made.nearest.empty() ? "" : " (did you mean '" + made.nearest + "'?)") + ", so there is nothing to remove");
  }
  const YAML::Node& given = section;  // a const look-up: a mutable one may add the key
  if (!given.IsMap() || !given[name].IsDefined()) {
    std::vector<std::string> names;
    if (section.IsMap())
      for (const auto& kv : section) names.push_back(kv.first.as<std::string>());
    const std::string nearest = closest_match(name, names);
    fail("the file gives no '" + name + "' here, so there is nothing to remove" +
         (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
  }
  section.remove(name);
  return made;
}

/// Puts one override into the scenario's YAML tree: maps on the way are made when missing (the
/// reader then checks every key as if it were in the file; the first one made is returned);
/// list entries must exist.
MadeSection apply_override(YAML::Node& root, const ScenarioOverride& o) {
  MadeSection made;
  auto fail = [&](const std::string& why) { throw InputError("", 0, "--set " + o.key, why); };
  if (o.value.find_first_not_of(" \t") == std::string::npos)
    fail("an empty value: give one, or ~ to remove the key the file gives");
  YAML::Node at = root;
  std::size_t start = 0;
  while (start <= o.key.size()) {
    const std::size_t dot = std::min(o.key.find('.', start), o.key.size());
    std::string segment = o.key.substr(start, dot - start);
    std::vector<std::size_t> entries;
    for (auto open = segment.find('['); open != std::string::npos; open = segment.find('[')) {
      const auto close = segment.find(']', open);
      const std::string number = close == std::string::npos ? "" : segment.substr(open + 1, close - open - 1);
      if (number.find_first_not_of('0') == std::string::npos && !number.empty())
        fail("list entries count from 1: " + segment.substr(0, open) + "[1] is the first");
      if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos)
        fail("'" + segment + "' is not a name with list entries such as walls[2] (counted from 1)");
      entries.push_back(std::stoul(number));
      segment.erase(open, close - open + 1);
    }
    if (segment.empty()) fail("an empty name in the key");
    if (at.IsSequence() && segment.find_first_not_of("0123456789") == std::string::npos)
      fail("list entries are written with brackets, counted from 1: " + o.key.substr(0, start - 1) + "[" +
           (segment.find_first_not_of('0') == std::string::npos ? std::string("1") : segment) + "]" +
           (segment.find_first_not_of('0') == std::string::npos ? " is the first" : ""));
    if (!at.IsMap() && !at.IsNull()) fail("'" + segment + "' is under a value that is not a section of keys");
    const bool last = dot == o.key.size();
    YAML::Node next = at[segment];
    for (std::size_t n : entries) {
      if (!next.IsDefined() || next.IsNull())
        fail("the file has no '" + segment + "', so it has no entry " + std::to_string(n) +
             ": give the whole list, e.g. --set '" + o.key.substr(0, o.key.find('[', start)) + "=[{...}]'");
      if (!next.IsSequence() || next.size() < n)
        fail("'" + segment + "' has no entry " + std::to_string(n) +
             (next.IsSequence() ? " (it has " + std::to_string(next.size()) + ")" : " (it is not a list)"));
      next.reset(next[n - 1]);
    }
    if (last) {
      YAML::Node value;
      try {
        value = YAML::Load(o.value);
      } catch (const YAML::Exception& e) {
        const bool bracketed = !o.value.empty() && o.value.front() == '[';
        fail("the value '" + o.value + "' is not valid YAML: " + e.msg +
             (bracketed ? "; text in brackets, such as a layup, needs quotes: --set '" + o.key + "=\"" + o.value + "\"'"
                        : ""));
      }
      if (value.IsNull() && !entries.empty())
        fail("~ removes a key, not a list entry: give the whole list without it, --set '" +
             o.key.substr(0, o.key.rfind('[')) + "=[...]'");
      if (value.IsNull()) return remove_key(at, segment, made, fail);
      if (entries.empty()) at[segment] = value;
      else next = value;
      return made;
    }
    if (!next.IsDefined() || next.IsNull()) {
      if (!entries.empty()) fail("'" + segment + "' has no such entry");
      if (made.key.empty() && at.IsMap() && at.size() > 0) {
        std::vector<std::string> names;
        for (const auto& kv : at) names.push_back(kv.first.as<std::string>());
        made = {o.key.substr(0, dot), closest_match(segment, names)};
      }
      at[segment] = YAML::Node(YAML::NodeType::Map);
      next.reset(at[segment]);
    }
    at.reset(next);
    start = dot + 1;
  }
}

/// The override a key of the reader is about, if any (its key, or a key below it).
const ScenarioOverride* override_of(const std::string& key, const std::vector<ScenarioOverride>& overrides) {
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {
    const std::string& plain = it->key;  // "boundary_conditions[2].velocity" is named so by the reader too
    // A key under the override ("probes[1].group" under a whole list "probes") or above it.
    if (key == plain || key.rfind(plain + ".", 0) == 0 || key.rfind(plain + "[", 0) == 0 ||
        plain.rfind(key + ".", 0) == 0)
      return &*it;
  }
  return nullptr;
}

/// An error in a section that an override made (a misspelt name on the command line makes a new,
/// incomplete section): says so, with the name the file has nearest to it.
void name_made_section(const InputError& e, const std::vector<ScenarioOverride>& overrides,
                       const std::vector<MadeSection>& made) {
  for (std::size_t i = made.size(); i-- > 0;) {
    const MadeSection& m = made[i];
    if (m.key.empty() || (e.key() != m.key && e.key().rfind(m.key + ".", 0) != 0)) continue;
    const auto dot = m.key.rfind('.');
    const std::string name = m.key.substr(dot == std::string::npos ? 0 : dot + 1);
    const std::string parent = dot == std::string::npos ? "the top level" : "'" + m.key.substr(0, dot) + "'";
    throw InputError("", 0, "--set " + overrides[i].key,
                     "the file has no '" + name + "' in " + parent +
                         (m.nearest.empty() ? "" : " (did you mean '" + m.nearest + "'?)") +
                         ", so the --set made a new one, which is incomplete: " + e.reason());
  }
}

}  // namespace

std::string given_by(const ScenarioOverride& o) { return " (the value given by --set " + o.key + "=" + o.value + ")"; }

std::string override_note(const std::string& key, const std::vector<ScenarioOverride>& overrides) {
  const ScenarioOverride* o = override_of(key, overrides);
  return o ? given_by(*o) : std::string();
}


Scenario read_scenario(const std::filesystem::path& path, const std::vector<ScenarioOverride>& overrides) {
  const std::string file = path.string();
  const std::string text = scenario_text(path);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp stops at a fixed nesting depth and calls it "bad file".
    throw InputError(file, e.mark.line + 1, "",
                     "not valid YAML here: lists or maps nested " + std::to_string(e.depth()) +
                         " levels deep, past the parser's limit (a scenario needs a few levels)");
  } catch (const YAML::ParserException& e) {
    const auto [line, reason] = yaml_syntax_error(file, e.mark.line + 1, e.msg);
    throw InputError(file, line, "", reason);
  }
  if (!root.IsMap()) throw InputError(file, 1, "", "a scenario is a YAML map of sections (analysis:, mesh:, ...)");

  std::vector<MadeSection> made;
  for (const auto& o : overrides) made.push_back(apply_override(root, o));

  Scenario sc;
  sc.file = std::filesystem::absolute(path);
  sc.resolved = YAML::Node(YAML::NodeType::Map);
  const scenario_detail::ScenarioWarnings collect(sc.warnings);
  // A value from the command line has no line in the file: errors and warnings name the override.
  auto named = [&](const std::string& key) { return override_note(key, overrides); };
  // The shell leaves [...] as it is, and YAML reads it as a list: text such as a layup code needs
  // quotes of its own inside the shell's.
  auto quoting = [&](const InputError& e) -> std::string {
    const ScenarioOverride* o = override_of(e.key(), overrides);
    if (!o || o->value.empty() || o->value.front() != '[' || e.reason().rfind("expected text", 0) != 0) return "";
    return "; a value in brackets is read as a list: quote it, --set '" + o->key + "=\"" + o->value + "\"'";
  };
  struct NoteWhileReading {
    scenario_detail::ScenarioWarnings::OverrideNote before;
    explicit NoteWhileReading(scenario_detail::ScenarioWarnings::OverrideNote now)
        : before(std::exchange(scenario_detail::ScenarioWarnings::override_note(), std::move(now))) {}
    ~NoteWhileReading() { scenario_detail::ScenarioWarnings::override_note() = std::move(before); }
  };
  try {
    const NoteWhileReading note(named);
    ScenarioReader(root, path, sc).read();
  } catch (const InputError& e) {
    // A value read before the error without a unit (so as SI) may explain it.
    std::string earlier;
    for (const std::string& w : sc.warnings)
      if (w.find(" has no unit and is read as ") != std::string::npos) earlier += "\n  after the warning: " + w;
    // (A message that already names the --set, as a material's consistency check does, once.)
    if (const std::string n = named(e.key()); !n.empty() && e.reason().find(n.substr(2, n.size() - 3)) == std::string::npos)
      throw InputError("", 0, e.key(), e.reason() + n + quoting(e) + earlier);
    name_made_section(e, overrides, made);
    if (!earlier.empty()) throw InputError(e.file(), e.line(), e.key(), e.reason() + earlier);
    throw;
  }
  if (const std::string n = named("analysis.end_time"); !n.empty()) {
    sc.end_time_line = 0;
    sc.end_time_note = n;
  }
  return sc;
}

std::vector<SchemaSection> scenario_schema() {
  std::vector<SchemaSection> schema{{"(top level)", "the sections of a scenario file", top_keys()},
          {"analysis", "what is solved and how", analysis_keys()},
          {"mesh", "the geometry or mesh (Gmsh)", mesh_keys()},
          {"parts.<name>", "a part: elements of one physical group with one material", part_keys()},
          {"initial_conditions[]", "a list entry", initial_condition_keys()},
          {"boundary_conditions[]", "a list entry", boundary_condition_keys()},
          {"boundary_conditions[].velocity", "prescribed velocity components", velocity_component_keys()},
          {"boundary_conditions[].rotation", "a rigid rotation of the group", rotation_keys()},
          {"loads[]", "a list entry", load_keys()},
          {"contact", "contact between parts", contact_keys()},
          {"contact.material_friction[]", "friction of a pair of materials", material_friction_keys()},
          {"walls[]", "a rigid plane", wall_keys()},
          {"walls[].extent", "a finite wall (docs/theory/contact.md, \"Finite walls\")", wall_extent_keys()},
          {"interfaces[]", "a cohesive interface (docs/theory/cohesive_interfaces.md)", scenario_detail::interface_keys()},
          {"particle_contact", "the law particles touch each other and the walls with; the law's own parameters "
                               "(linear_spring: modulus, tangential_ratio, friction, damping_ratio or restitution, "
                               "limit_damping; hertz_mindlin: young, poisson, restitution, friction, limit_damping)",
           particle_contact_keys()},
          {"materials.<name>.erosion", "when an element fails and what becomes of it (any material model). Without "
                                        "this section a model with a failure variable of its own (johnson_cook with "
                                        "failure_d1, composite_damage with an erosion_criterion) still deletes an "
                                        "element once one of its points reaches 1; variable: none (with inverted or a "
                                        "distortion) keeps elements from eroding on it",
           erosion_keys()},
          {"parts.<name>.orientation", "material axes of the whole part", orientation_keys(false)},
          {"parts.<name>.laminate", "material axes ply by ply through the part", orientation_keys(true)},
          {"cracking", "discrete crack insertion", cracking_keys()},
          {"remeshing", "adaptive remeshing (docs/theory/adaptive_remeshing.md)", scenario_detail::remeshing_keys()},
          {"remeshing.parts[]", "a remeshed part and its size rule", scenario_detail::remeshed_part_keys()},
          {"crash", "crash outputs of a crush test", scenario_detail::crash_keys()},
          {"probes[]", "a point history (probe_<name>.csv)", scenario_detail::probe_keys()},
          {"output", "what is written to the output folder", output_keys()}};
  for (auto& section : scenario_detail::particle_schema()) schema.push_back(std::move(section));
  return schema;
}

namespace {
void key_table(std::ostringstream& out, const KeyList& keys) {
  out << "| key | type | range | default | meaning |\n|---|---|---|---|---|\n";
  for (const auto& k : keys.keys()) {
    std::string type = k.type_text();
    std::replace(type.begin(), type.end(), '|', '/');
    out << "| `" << k.name << "` | " << type << " | " << k.range_text() << " | "
        << (k.required ? "**required**" : k.default_text ? "`" + *k.default_text + "`" : "—") << " | "
        << k.doc << " |\n";
  }
  out << "\n";
}
}  // namespace

std::string scenario_reference_markdown() {
  std::ostringstream out;
  out << "# Scenario reference\n\n"
         "<!-- Generated by `shard reference` from the key declarations in src/io/scenario.cpp and "
         "the material models; do not edit by hand (a test checks it is current). -->\n\n"
         "A scenario is a YAML file. Quantities take units (`370 MPa`, `0.5 mm`, `203 m/s`, "
         "`20 us`, `7830 kg/m^3`); plain numbers are SI. Time tables are lists of `[time, value]` "
         "rows, interpolated linearly and held constant beyond their ends. `shard check` validates "
         "a scenario without running it; `shard run` writes the resolved scenario (every default "
         "filled in, SI units) to `resolved.yaml` in the output folder.\n\n";
  for (const auto& section : scenario_schema()) {
    out << "## `" << section.path << "`\n\n" << section.summary << ".\n\n";
    key_table(out, section.keys);
  }
  out << "## Material models\n\nEvery material has `model` and `density`; the model adds its "
         "own keys.\n\n";
  for (const auto& name : MaterialRegistry::names()) {
    const MaterialModelInfo* info = MaterialRegistry::find(name);
    out << "### `" << name << "`\n\n" << info->summary << ". Theory: `" << info->theory_note
        << "`.\n\n";
    key_table(out, material_keys(*info));
  }
  return out.str();
}

std::string to_yaml_text(const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter.SetDoublePrecision(17);
  emitter << node;
  return std::string(emitter.c_str()) + "\n";
}

}  // namespace shard
