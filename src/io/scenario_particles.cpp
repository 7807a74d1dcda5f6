#include "io/scenario_particles.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace shard::scenario_detail {

namespace {

KeyList bond_keys() {
  KeyList k;
  k.add("materials", ValueKind::list, "the two automaton materials the bond joins, e.g. [tic, nicr]")
      .must_be_given();
  k.choice("criterion", {"none", "drucker_prager", "von_mises", "mohr_coulomb"},
           "fracture criterion on the pair stress tensor, eqs. (16)-(17) of the MCA paper")
      .defaults_to("drucker_prager");
  k.quantity("tensile_strength", dim::pressure, "σ_t (Drucker–Prager, Mohr–Coulomb)").above(0);
  k.quantity("compressive_strength", dim::pressure, "σ_c (Drucker–Prager, Mohr–Coulomb)").above(0);
  k.quantity("von_mises_strength", dim::pressure, "threshold of the von Mises criterion").above(0);
  k.choice("breaking", {"instant", "stable", "unstable"},
           "how the linked fraction k_link falls from 1 to 0 once the criterion is met")
      .defaults_to("unstable");
  k.quantity("breaking_strain", dim::none,
             "stable breaking: pair equivalent strain from onset to k_link = 0")
      .above(0);
  k.quantity("crack_speed", dim::velocity, "unstable breaking: crack speed V_crack across the contact")
      .above(0);
  k.quantity("friction", dim::none, "Amontons coefficient of the pair once unlinked").at_least(0).defaults_to("0");
  return k;
}

KeyList region_keys() {
  KeyList k;
  KeySpec& lo = k.add("min", ValueKind::vector, "box: lower corner");
  lo.dimension = dim::length;
  KeySpec& hi = k.add("max", ValueKind::vector, "box: upper corner");
  hi.dimension = dim::length;
  KeySpec& c = k.add("centre", ValueKind::vector, "ball (disc in 2D): centre");
  c.dimension = dim::length;
  k.quantity("radius", dim::length, "ball (disc in 2D): radius").above(0);
  k.choice("side", {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"},
           "the layer of automata at this side of the sample's bounding box");
  k.quantity("depth", dim::length, "side: thickness of the layer").above(0).defaults_to(
      "half the automaton size");
  return k;
}

KeyList particle_part_keys() {
  KeyList k;
  k.add("sample", ValueKind::text,
        "a sample file (path relative to the scenario), as a run writes it (particles_<part>_sample.csv): "
        "its automata with their places, sizes and materials instead of lattice, automaton_size, min, max, "
        "angle, material, regions, inclusions, pores and interphase; bonded by bond_tolerance (docs/outputs.md)");
  k.choice("lattice", {"hexagonal", "square", "fcc", "simple_cubic"},
           "close packing (2D: hexagonal, square; 3D: fcc, simple_cubic); required without 'sample'");
  k.quantity("automaton_size", dim::length,
             "automaton size d (nearest-neighbour distance); required without 'sample'")
      .above(0);
  KeySpec& lo = k.add("min", ValueKind::vector, "lower corner of the sample box; required without 'sample'");
  lo.dimension = dim::length;
  KeySpec& hi = k.add("max", ValueKind::vector, "upper corner of the sample box; required without 'sample'");
  hi.dimension = dim::length;
  k.quantity("angle", dim::none, "lattice rotated about z by this angle (degrees)").defaults_to("0");
  k.add("material", ValueKind::text, "automaton material of the sample (matrix); required without 'sample'");
  k.add("regions", ValueKind::list, "other materials by region: [{material: m, min: .., max: ..}, ...]")
      .defaults_to("[]");
  k.add("inclusions", ValueKind::section, "random equiaxed inclusions");
  k.add("pores", ValueKind::section, "pores: automata removed at random");
  k.add("interphase", ValueKind::section, "graded interphase zones around the inclusions");
  k.quantity("bond_tolerance", dim::none, "neighbours closer than (1 + tol) d are bonded")
      .above(0)
      .below(0.5)
      .defaults_to("0.1");
  k.quantity("time_step_safety", dim::none,
             "fraction of the velocity-Verlet stability bound (the MCA paper uses a quarter; the "
             "mean-stress predictor of eq. (2) makes half unstable in long runs)")
      .above(0)
      .at_most(1)
      .defaults_to("0.25");
  k.add("contact_update_interval", ValueKind::integer,
        "steps between searches for new contacts between automata (0: never)")
      .defaults_to("0");
  k.quantity("contact_skin", dim::length, "unlinked pairs further apart than this are dropped")
      .at_least(0)
      .defaults_to("0.1 automaton sizes");
  KeySpec& v = k.add("velocity", ValueKind::vector, "initial velocity of every automaton");
  v.dimension = dim::velocity;
  k.add("grains", ValueKind::boolean,
        "true: loose grains (spheres, discs in 2D, of the automaton size and the material's density), "
        "no bonds and no automaton forces; they meet each other, the walls and the mesh through "
        "particle_contact (docs/theory/particle_contact.md)")
      .defaults_to("false");
  return k;
}

KeyList inclusion_keys() {
  KeyList k;
  k.add("material", ValueKind::text, "automaton material of the inclusions").must_be_given();
  k.quantity("volume_fraction", dim::none, "fraction of the automata").above(0).below(1).must_be_given();
  k.quantity("diameter", dim::length, "inclusion diameter").above(0).must_be_given();
  k.add("seed", ValueKind::integer, "random seed (a sample is the same on every platform)").defaults_to("1");
  return k;
}

KeyList pore_keys() {
  KeyList k;
  k.quantity("porosity", dim::none, "fraction of automata removed").above(0).below(1).must_be_given();
  k.add("with_neighbours", ValueKind::boolean,
        "remove an automaton and its nearest neighbours (larger pores)")
      .defaults_to("false");
  k.add("seed", ValueKind::integer, "random seed").defaults_to("1");
  return k;
}

KeyList interphase_keys() {
  KeyList k;
  k.quantity("width", dim::length, "matrix automata closer than this to an inclusion grade").above(0).must_be_given();
  k.add("levels", ValueKind::integer, "number of graded materials").defaults_to("3");
  return k;
}

KeyList particle_condition_keys() {
  KeyList k;
  k.add("name", ValueKind::text, "name in the history columns (reaction_<name>_x, displacement_<name>_x)")
      .must_be_given();
  k.add("part", ValueKind::text, "a particle part").must_be_given();
  k.add("region", ValueKind::section, "which automata: a box, a ball or a side layer").must_be_given();
  k.add("fix", ValueKind::list, "components held at zero velocity: x, y, z, rotation");
  k.add("velocity", ValueKind::section, "prescribed velocity per component: {y: -0.5 m/s} or time tables");
  return k;
}

[[noreturn]] void no_such(Section& s, const std::string& key, const std::string& what,
                          const std::string& name, const std::vector<std::string>& names) {
  std::string reason = "no " + what + " named '" + name + "'";
  const std::string close = closest_match(name, names);
  if (!close.empty()) reason += " (did you mean '" + close + "'?)";
  if (names.empty()) reason += "; none is defined";
  s.fail(key, reason);
}

std::vector<std::string> automaton_names(const Scenario& sc) {
  std::vector<std::string> names;
  for (const auto& m : sc.automaton_materials) names.push_back(m.name);
  return names;
}

void copy3(const std::vector<double>& v, std::array<double, 3>& a) {
  std::copy(v.begin(), v.end(), a.begin());
}

RegionInput read_region(Section& r, std::size_t dim) {
  RegionInput g;
  const bool box = r.has("min") || r.has("max"), ball = r.has("centre") || r.has("radius"),
             side = r.has("side");
  if (int(box) + int(ball) + int(side) != 1)
    throw InputError(r.file(), r.line(), r.path(),
                     "a region is one of: a box {min: [..], max: [..]}, a ball {centre: [..], "
                     "radius: ..} or a side {side: y_max, depth: ..}");
  if (box) {
    if (!r.has("min") || !r.has("max")) r.fail(r.has("min") ? "max" : "min", "a box needs both min and max");
    g.kind = RegionInput::Kind::box;
    copy3(r.vector("min", dim), g.lo);
    copy3(r.vector("max", dim), g.hi);
    for (std::size_t k = 0; k < dim; ++k)
      if (!(g.hi[k] > g.lo[k])) r.fail("max", "each component of max must exceed that of min");
  } else if (ball) {
    if (!r.has("centre") || !r.has("radius")) r.fail(r.has("centre") ? "radius" : "centre", "a ball needs centre and radius");
    g.kind = RegionInput::Kind::ball;
    copy3(r.vector("centre", dim), g.centre);
    g.radius = r.number("radius");
  } else {
    g.kind = RegionInput::Kind::side;
    const std::string s = *r.choice("side");
    g.axis = s[0] - 'x';
    if (g.axis >= static_cast<int>(dim)) r.fail("side", "a 2D model has no z sides");
    g.at_max = s.substr(2) == "max";
    g.depth = r.optional_number("depth").value_or(0.0);  // 0: half the automaton size, later
  }
  return g;
}

}  // namespace

KeyList automaton_material_keys() {
  KeyList k;
  k.add("model", ValueKind::text, "automaton");
  k.quantity("density", dim::density, "mass density").above(0).must_be_given();
  k.quantity("young", dim::pressure, "Young's modulus E of the bulk").above(0).must_be_given();
  k.quantity("poisson", dim::none, "Poisson's ratio ν of the bulk").above(-1).below(0.5).must_be_given();
  k.quantity("yield_stress", dim::pressure, "initial yield stress (0: elastic)").at_least(0).defaults_to("0");
  k.quantity("hardening_modulus", dim::pressure, "linear hardening dσ/dε_p").at_least(0).defaults_to("0");
  k.add("hardening_curve", ValueKind::list,
        "uniaxial response σ(ε) as [[strain, stress], ...] (total strain; overrides yield_stress "
        "and hardening_modulus)");
  return k;
}

AutomatonMaterialInput read_automaton_material(const YAML::Node& body, const std::string& file,
                                               const std::string& name, int line, YAML::Node resolved) {
  static const KeyList keys = automaton_material_keys();
  Section s(body, file, "materials." + name, keys, resolved, line);
  AutomatonMaterialInput m;
  m.name = name;
  m.line = line;
  s.text("model");
  m.material.name = name;
  m.material.density = s.number("density");
  m.material.young = s.number("young");
  m.material.poisson = s.number("poisson");
  m.material.yield_stress = s.number("yield_stress");
  m.material.hardening = s.number("hardening_modulus");
  if (s.has("hardening_curve")) {
    const YAML::Node c = s.value("hardening_curve");
    KeySpec strain, stress;
    strain.dimension = dim::none;
    stress.dimension = dim::pressure;
    if (!c.IsSequence() || c.size() < 2)
      s.fail("hardening_curve", "expected at least two rows [strain, stress]");
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (!c[i].IsSequence() || c[i].size() != 2)
        throw InputError(file, line_of(c[i]), s.key_path("hardening_curve"),
                         "each row is [strain, stress], got " + Section::shape(c[i]));
      CurvePoint p{s.parse_number(c[i][0], strain, "hardening_curve"),
                   s.parse_number(c[i][1], stress, "hardening_curve")};
      if (!m.material.curve.empty() && !(p.strain > m.material.curve.back().strain))
        throw InputError(file, line_of(c[i]), s.key_path("hardening_curve"),
                         "the strains of the curve must increase from row to row");
      m.material.curve.push_back(p);
      YAML::Node row(YAML::NodeType::Sequence);
      row.SetStyle(YAML::EmitterStyle::Flow);
      row.push_back(p.strain);
      row.push_back(p.stress);
      out.push_back(row);
    }
    // The first row is the elastic limit: it must lie on the elastic line.
    const CurvePoint& first = m.material.curve.front();
    if (std::abs(first.stress - m.material.young * first.strain) > 1e-3 * first.stress)
      s.fail("hardening_curve", "the first row must be the elastic limit, on σ = E ε (E ε = " +
                                    std::to_string(m.material.young * first.strain) + " Pa, given " +
                                    std::to_string(first.stress) + " Pa)");
    s.resolved()["hardening_curve"] = out;
  }
  return m;
}

namespace {

// The automaton materials of the scenario, by name, for checking references to them.
struct AutomatonMaterials {
  std::vector<std::string> names;
  bool has(const std::string& name) const {
    return std::find(names.begin(), names.end(), name) != names.end();
  }
  void require(Section& s, const char* key, const std::string& name, const std::string& what) const {
    if (!has(name)) no_such(s, key, what, name, names);
  }
};

void read_bond_criterion(Section& s, YAML::Node& out, BondLaw& law) {
  const std::string criterion = s.choice("criterion").value_or("drucker_prager");
  out["criterion"] = criterion;
  law.criterion = criterion == "none"             ? BondCriterion::none
                  : criterion == "drucker_prager" ? BondCriterion::drucker_prager
                  : criterion == "von_mises"      ? BondCriterion::von_mises
                                                  : BondCriterion::mohr_coulomb;
  if (law.criterion == BondCriterion::drucker_prager || law.criterion == BondCriterion::mohr_coulomb) {
    for (const char* key : {"tensile_strength", "compressive_strength"})
      if (!s.has(key)) s.fail(key, std::string("criterion '") + criterion + "' needs '" + key + "'");
    law.sigma_t = s.number("tensile_strength");
    law.sigma_c = s.number("compressive_strength");
    // σ_c < σ_t gives the criterion a negative pressure coefficient (eq. (17) of the MCA paper,
    // Drucker–Prager form): pressure would weaken the bond, which no brittle solid does.
    if (law.sigma_c < law.sigma_t)
      s.fail("compressive_strength", "below tensile_strength (" + s.value("tensile_strength").Scalar() +
                                         "): pressure would weaken the bond; brittle solids have a compressive "
                                         "strength several times their tensile one (swapped?)");
  } else if (law.criterion == BondCriterion::von_mises) {
    if (!s.has("von_mises_strength")) s.fail("von_mises_strength", "criterion 'von_mises' needs 'von_mises_strength'");
    law.sigma_vm = s.number("von_mises_strength");
  }
}

void read_bond_breaking(Section& s, YAML::Node& out, BondLaw& law) {
  const std::string breaking = s.choice("breaking").value_or("unstable");
  out["breaking"] = breaking;
  law.breaking = breaking == "instant" ? BondBreaking::instant
                 : breaking == "stable" ? BondBreaking::stable
                                        : BondBreaking::unstable;
  if (law.breaking == BondBreaking::stable) {
    if (!s.has("breaking_strain")) s.fail("breaking_strain", "stable breaking needs 'breaking_strain'");
    law.strain_width = s.number("breaking_strain");
  }
  if (law.breaking == BondBreaking::unstable && law.criterion != BondCriterion::none) {
    if (!s.has("crack_speed")) s.fail("crack_speed", "unstable breaking needs 'crack_speed'");
    law.crack_speed = s.number("crack_speed");
  }
  law.friction = s.number("friction");
}

BondInput read_bond(Section& s, YAML::Node& out, const Scenario& sc, const AutomatonMaterials& materials) {
  BondInput b;
  b.line = s.line();
  const YAML::Node pair = s.value("materials");
  if (!pair.IsSequence() || pair.size() != 2 || !pair[0].IsScalar() || !pair[1].IsScalar())
    s.fail("materials", "expected two automaton material names, e.g. [tic, nicr]");
  b.material_a = pair[0].Scalar();
  b.material_b = pair[1].Scalar();
  for (const auto& m : {b.material_a, b.material_b}) materials.require(s, "materials", m, "automaton material");
  for (const auto& other : sc.bonds)
    if ((other.material_a == b.material_a && other.material_b == b.material_b) ||
        (other.material_a == b.material_b && other.material_b == b.material_a))
      s.fail("materials", "a second bond for these materials (the first is at line " +
                              std::to_string(other.line) + ")");
  out["materials"] = pair;
  read_bond_criterion(s, out, b.law);
  read_bond_breaking(s, out, b.law);
  return b;
}

void read_bonds(Section& top, Scenario& sc, const AutomatonMaterials& materials) {
  static const KeyList b_keys = bond_keys();
  const YAML::Node bonds = top.value_or_null("bonds");
  if (bonds.IsDefined() && !bonds.IsNull() && !bonds.IsSequence())
    top.fail("bonds", "expected a list (entries starting with '- ')");
  YAML::Node bonds_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; bonds.IsSequence() && i < bonds.size(); ++i) {
    YAML::Node out(YAML::NodeType::Map);
    Section s(bonds[i], top.file(), "bonds[" + std::to_string(i + 1) + "]", b_keys, out, line_of(bonds[i]));
    sc.bonds.push_back(read_bond(s, out, sc, materials));
    bonds_out.push_back(out);
  }
  if (top.has("bonds")) sc.resolved["bonds"] = bonds_out;
}

PlaneMode plane_of(const Scenario& sc) {
  return sc.dim() == 3 ? PlaneMode::none
         : sc.formulation == Formulation::plane_stress ? PlaneMode::plane_stress
                                                       : PlaneMode::plane_strain;
}

/// The builder's keys a part needs when it names no sample file.
void require_builder_keys(const Section& s, int part_line) {
  for (const std::string key : {"lattice", "automaton_size", "min", "max", "material"})
    if (!s.has(key)) {
      const KeySpec& k = s.spec(key);
      throw InputError(s.file(), part_line, s.key_path(key),
                       "missing required key '" + key + "' (" + k.doc + "; " + k.type_text() +
                           "), or give 'sample': a sample file that a run wrote");
    }
}

PackingSpec read_packing(Section& s, const Scenario& sc) {
  const std::size_t dim = static_cast<std::size_t>(sc.dim());
  if (sc.formulation == Formulation::axisymmetric)
    s.fail("lattice", "particle parts are plane strain, plane stress or 3D, not axisymmetric");
  const std::string lattice = *s.choice("lattice");
  const bool lattice_3d = lattice == "fcc" || lattice == "simple_cubic";
  if (lattice_3d != (dim == 3))
    s.fail("lattice", "lattice '" + lattice + "' does not fit this " + std::to_string(dim) +
                          "D model (2D: hexagonal, square; 3D: fcc, simple_cubic)");
  PackingSpec k;
  k.lattice = lattice == "hexagonal" ? Lattice::hexagonal_2d
              : lattice == "square"  ? Lattice::square_2d
              : lattice == "fcc"     ? Lattice::fcc
                                     : Lattice::simple_cubic;
  k.size = s.number("automaton_size");
  const auto lo = s.vector("min", dim), hi = s.vector("max", dim);
  for (std::size_t a = 0; a < dim; ++a) {
    k.lo[a] = lo[a];
    k.hi[a] = hi[a];
    if (!(hi[a] > lo[a] + k.size))
      s.fail("max", "the sample box must be larger than one automaton along every axis");
  }
  k.angle = s.number("angle") * M_PI / 180.0;
  k.plane = plane_of(sc);
  k.thickness = sc.thickness;
  k.bond_tolerance = s.number("bond_tolerance");
  return k;
}

void read_material_regions(Section& s, const std::string& path, std::size_t dim,
                           const AutomatonMaterials& materials, ParticlePartInput& p) {
  const YAML::Node regions = s.value_or_null("regions");
  YAML::Node regions_out(YAML::NodeType::Sequence);
  for (std::size_t r = 0; regions.IsSequence() && r < regions.size(); ++r) {
    KeyList rk = region_keys();
    rk.add("material", ValueKind::text, "automaton material of the region").must_be_given();
    YAML::Node out(YAML::NodeType::Map);
    Section rs(regions[r], s.file(), path + ".regions[" + std::to_string(r + 1) + "]", rk, out,
               line_of(regions[r]));
    const std::string m = rs.text("material");
    materials.require(rs, "material", m, "automaton material");
    RegionInput g = read_region(rs, dim);
    if (g.kind == RegionInput::Kind::side && g.depth == 0) g.depth = 0.5 * p.packing.size;
    p.material_regions.emplace_back(m, g);
    regions_out.push_back(out);
  }
  s.resolved()["regions"] = regions_out;
}

void read_microstructure(Section& s, const std::string& path, const AutomatonMaterials& materials,
                         ParticlePartInput& p) {
  static const KeyList i_keys = inclusion_keys();
  static const KeyList o_keys = pore_keys();
  static const KeyList g_keys = interphase_keys();
  const std::string& file = s.file();
  if (s.has("inclusions")) {
    Section is(s.value("inclusions"), file, path + ".inclusions", i_keys, s.resolved()["inclusions"], s.line("inclusions"));
    InclusionSpec spec;
    p.inclusion_material = is.text("material");
    materials.require(is, "material", p.inclusion_material, "automaton material");
    spec.volume_fraction = is.number("volume_fraction");
    spec.diameter = is.number("diameter");
    if (spec.diameter < p.packing.size)
      is.warn(0, "diameter",
              "smaller than the automata (automaton_size " + s.value("automaton_size").Scalar() +
                  "): an inclusion is made of the automata whose centres fall inside it, so each is one automaton "
                  "or none; inclusions of several automata across need a diameter of a few automaton sizes");
    spec.seed = static_cast<std::uint64_t>(is.integer("seed"));
    p.inclusions = spec;
  }
  if (s.has("pores")) {
    Section ps(s.value("pores"), file, path + ".pores", o_keys, s.resolved()["pores"], s.line("pores"));
    PoreSpec spec;
    spec.porosity = ps.number("porosity");
    if (ps.has("with_neighbours")) {
      const std::string b = ps.value("with_neighbours").Scalar();
      if (b != "true" && b != "false") ps.fail("with_neighbours", "expected true or false");
      spec.with_neighbours = b == "true";
    }
    spec.seed = static_cast<std::uint64_t>(ps.integer("seed"));
    p.pores = spec;
  }
  if (s.has("interphase")) {
    Section gs(s.value("interphase"), file, path + ".interphase", g_keys, s.resolved()["interphase"], s.line("interphase"));
    if (!p.inclusions) s.fail("interphase", "an interphase grades from the inclusions to the matrix: give 'inclusions' too");
    InterphaseSpec spec;
    spec.width = gs.number("width");
    spec.levels = static_cast<int>(gs.integer("levels"));
    if (spec.levels < 1) gs.fail("levels", "at least one level");
    p.interphase = spec;
  }
}

/// `sample`: the automata from a file, in place of every key of the builder.
void read_sample(Section& s, const Scenario& sc, ParticlePartInput& p) {
  for (const std::string key :
       {"lattice", "automaton_size", "min", "max", "angle", "material", "regions", "inclusions", "pores", "interphase"})
    if (s.has(key))
      s.fail(key, "'" + key + "' and 'sample' (line " + std::to_string(s.line("sample")) +
                      ") exclude each other: the sample file gives the automata with their places, sizes and "
                      "materials, and its header the lattice and automaton size; remove '" + key + "'");
  if (sc.formulation == Formulation::axisymmetric)
    s.fail("sample", "particle parts are plane strain, plane stress or 3D, not axisymmetric");
  const std::string given = s.text("sample");
  std::filesystem::path file = given;
  if (file.is_relative()) file = sc.file.parent_path() / file;
  file = file.lexically_normal();
  s.resolved()["sample"] = file.string();
  if (const std::string why = unreadable_file_reason(file); !why.empty())
    s.fail("sample", "sample file '" + file.string() + "' " + why +
                         " (the path is relative to the scenario file; a run writes particles_<part>_sample.csv)");
  const SampleReference where{s.file(), s.line("sample"), s.key_path("sample"), given};
  p.sample = read_particle_sample(file, sc.dim(), automaton_names(sc), where);
  p.packing.lattice = p.sample->lattice;
  p.packing.size = p.sample->automaton_size;
  p.packing.plane = plane_of(sc);
  p.packing.thickness = sc.thickness;
  p.packing.bond_tolerance = s.number("bond_tolerance");
}

void read_particle_part(Section& s, const std::string& path, const Scenario& sc,
                        const AutomatonMaterials& materials, ParticlePartInput& p) {
  const std::size_t dim = static_cast<std::size_t>(sc.dim());
  if (s.has("sample")) {
    read_sample(s, sc, p);
  } else {
    require_builder_keys(s, p.line);
    p.packing = read_packing(s, sc);
    p.material = s.text("material");
    materials.require(s, "material", p.material, "automaton material (model: automaton)");
    read_material_regions(s, path, dim, materials, p);
    read_microstructure(s, path, materials, p);
  }
  p.time_step_safety = s.number("time_step_safety");
  p.contact_update_interval = static_cast<int>(s.integer("contact_update_interval"));
  if (p.contact_update_interval < 0) s.fail("contact_update_interval", "must be 0 or more");
  p.contact_skin = s.number("contact_skin", 0.1 * p.packing.size);
  if (s.has("velocity")) copy3(s.vector("velocity", dim), p.velocity);
  p.grains = s.boolean("grains");
  if (s.has("grains")) p.grains_line = s.line("grains");
}

void read_particle_parts(Section& top, Scenario& sc, const AutomatonMaterials& materials) {
  static const KeyList p_keys = particle_part_keys();
  const std::string& file = top.file();
  const YAML::Node parts = top.value_or_null("particles");
  if (parts.IsDefined() && !parts.IsNull() && !parts.IsMap())
    top.fail("particles", "expected a map of named particle parts, e.g.\n  particles:\n    sample: {lattice: hexagonal, automaton_size: 3 um, min: [0, 0], max: [130 um, 24 um], material: nicr}");
  std::vector<std::string> names;
  for (const auto& p : sc.parts) names.push_back(p.name);
  for (auto it = parts.IsMap() ? parts.begin() : YAML::const_iterator(); parts.IsMap() && it != parts.end(); ++it) {
    ParticlePartInput p;
    p.name = key_name(it->first, top.file(), "particles");
    p.line = line_of(it->first);
    const std::string path = "particles." + p.name;
    if (std::find(names.begin(), names.end(), p.name) != names.end())
      throw InputError(file, p.line, path, "a part named '" + p.name + "' exists already; part names must differ");
    names.push_back(p.name);
    Section s(it->second, file, path, p_keys, sc.resolved["particles"][p.name], p.line);
    read_particle_part(s, path, sc, materials, p);
    sc.particle_parts.push_back(std::move(p));
  }
}

void read_fixed_components(Section& s, YAML::Node& out, std::size_t dim, ParticleBoundaryInput& c) {
  const YAML::Node fix = s.value("fix");
  if (!fix.IsSequence()) s.fail("fix", "expected a list of components such as [x, y, rotation]");
  for (const auto& f : fix) {
    const std::string name = s.name_in_list("fix", f, "a component name (x, y, z, rotation)");
    if (name == "rotation") {
      c.fix_rotation = true;
      continue;
    }
    const int k = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : -1;
    if (k < 0 || k >= static_cast<int>(dim))
      s.fail("fix", "'" + name + "' is not a component here (use " + (dim == 3 ? "x, y, z" : "x, y") + ", rotation)");
    c.velocity[k] = TimeTable::constant(0.0);
  }
  out["fix"] = fix;
}

void read_velocity_components(Section& s, const std::string& path, YAML::Node& out, std::size_t dim,
                              ParticleBoundaryInput& c) {
  static const KeyList v_keys = velocity_component_keys();
  const char* axes[3] = {"x", "y", "z"};
  Section v(s.value("velocity"), s.file(), path + ".velocity", v_keys, out["velocity"], s.line("velocity"));
  for (std::size_t k = 0; k < 3; ++k)
    if (v.has(axes[k])) {
      if (k >= dim) v.fail("z", "a 2D model has no z component");
      if (c.velocity[k]) v.fail(axes[k], std::string("component ") + axes[k] + " is also in 'fix'");
      c.velocity[k] = v.table(axes[k]);
    }
}

ParticleBoundaryInput read_particle_condition(Section& s, const std::string& path, YAML::Node& out,
                                              const Scenario& sc, std::vector<std::string>& condition_names) {
  static const KeyList r_keys = region_keys();
  const std::size_t dim = static_cast<std::size_t>(sc.dim());
  std::vector<std::string> particle_names;
  for (const auto& p : sc.particle_parts) particle_names.push_back(p.name);
  ParticleBoundaryInput c;
  c.line = s.line();
  c.name = s.text("name");
  if (std::find(condition_names.begin(), condition_names.end(), c.name) != condition_names.end())
    s.fail("name", "a second condition named '" + c.name + "'; names must differ");
  condition_names.push_back(c.name);
  c.part = s.text("part");
  const auto part = std::find(particle_names.begin(), particle_names.end(), c.part);
  if (part == particle_names.end()) no_such(s, "part", "particle part", c.part, particle_names);
  Section rs(s.value("region"), s.file(), path + ".region", r_keys, out["region"], s.line("region"));
  c.region = read_region(rs, dim);
  if (c.region.kind == RegionInput::Kind::side && c.region.depth == 0)
    c.region.depth = 0.5 * sc.particle_parts[part - particle_names.begin()].packing.size;
  if (s.has("fix")) read_fixed_components(s, out, dim, c);
  if (s.has("velocity")) read_velocity_components(s, path, out, dim, c);
  return c;
}

void read_particle_conditions(Section& top, Scenario& sc) {
  static const KeyList c_keys = particle_condition_keys();
  const YAML::Node conditions = top.value_or_null("particle_boundary_conditions");
  if (conditions.IsDefined() && !conditions.IsNull() && !conditions.IsSequence())
    top.fail("particle_boundary_conditions", "expected a list (entries starting with '- ')");
  std::vector<std::string> condition_names;
  YAML::Node c_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; conditions.IsSequence() && i < conditions.size(); ++i) {
    YAML::Node out(YAML::NodeType::Map);
    const std::string path = "particle_boundary_conditions[" + std::to_string(i + 1) + "]";
    Section s(conditions[i], top.file(), path, c_keys, out, line_of(conditions[i]));
    sc.particle_conditions.push_back(read_particle_condition(s, path, out, sc, condition_names));
    c_out.push_back(out);
  }
  if (top.has("particle_boundary_conditions")) sc.resolved["particle_boundary_conditions"] = c_out;
}

}  // namespace

void read_particle_sections(Section& top, Scenario& sc) {
  const AutomatonMaterials materials{automaton_names(sc)};
  read_bonds(top, sc, materials);
  read_particle_parts(top, sc, materials);
  read_particle_conditions(top, sc);
}

std::vector<SchemaSection> particle_schema() {
  KeyList region_material = region_keys();
  region_material.add("material", ValueKind::text, "automaton material of the region");
  return {{"materials.<name> (model: automaton)", "a material of movable cellular automata (docs/theory/mca.md)",
           automaton_material_keys()},
          {"bonds[]", "the bond law between automata of two materials", bond_keys()},
          {"particles.<name>", "a particle part: a packed sample of bonded automata", particle_part_keys()},
          {"particles.<name>.regions[]", "materials by region", region_material},
          {"particles.<name>.inclusions", "random equiaxed inclusions", inclusion_keys()},
          {"particles.<name>.pores", "random pores", pore_keys()},
          {"particles.<name>.interphase", "graded interphase zones", interphase_keys()},
          {"particle_boundary_conditions[]", "fixed or prescribed motion of a region of automata, or a monitor",
           particle_condition_keys()},
          {"particle_boundary_conditions[].region", "a box, a ball or a side layer", region_keys()},
          {"particle_boundary_conditions[].velocity", "prescribed velocity components", velocity_component_keys()}};
}

}  // namespace shard::scenario_detail

namespace shard {

bool RegionInput::contains(const double* x, int dim) const {
  switch (kind) {
    case Kind::everywhere: return true;
    case Kind::box:
      for (int k = 0; k < dim; ++k)
        if (x[k] < lo[k] || x[k] > hi[k]) return false;
      return true;
    case Kind::ball: {
      double r2 = 0;
      for (int k = 0; k < dim; ++k) r2 += (x[k] - centre[k]) * (x[k] - centre[k]);
      return r2 <= radius * radius;
    }
    case Kind::side: return false;  // resolved against the sample's extent by the caller
  }
  return false;
}

}  // namespace shard
