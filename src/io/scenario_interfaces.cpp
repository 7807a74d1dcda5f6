#include "io/scenario_interfaces.hpp"

#include <algorithm>
#include <cmath>

namespace shard::scenario_detail {

KeyList interface_keys() {
  KeyList k;
  k.add("between", ValueKind::list, "two parts that share a surface (a conforming mesh): [a, b]");
  k.add("plies_of", ValueKind::text, "a part with a `laminate`: every surface between two of its plies");
  k.quantity("normal_strength", dim::pressure, "σ_f: the normal traction at which damage starts in mode I")
      .above(0)
      .must_be_given();
  k.quantity("shear_strength", dim::pressure, "τ_f: the shear traction at which damage starts in mode II")
      .above(0)
      .must_be_given();
  k.quantity("mode_one_energy", dim::energy_per_area, "G_Ic: fracture energy in opening (e.g. 750 J/m^2)")
      .above(0)
      .must_be_given();
  k.quantity("mode_two_energy", dim::energy_per_area, "G_IIc: fracture energy in shear").above(0).must_be_given();
  k.quantity("stiffness", dim::stiffness_per_area,
             "K: the penalty per unit area, normal and shear (e.g. 50 E3/t for plies of thickness t: "
             "Turon et al. 2007); stiffer shortens the stable step, and the run says so")
      .above(0)
      .must_be_given();
  k.quantity("reference_size", dim::length,
             "Δ_ref of the size factor ζ = max(1, √(δ/Δ_ref)) on the tractions of eq. (14) of the CFRP-crushing "
             "paper (δ: the element's size); 0: ζ = 1")
      .at_least(0)
      .defaults_to("0");
  k.choice("mixed_mode", {"quadratic_ratio", "benzeggagh_kenane"},
           "the fracture energy in mixed mode: √((σ0/σ_f G_I)² + (τ0/τ_f G_II)²) of the onset tractions "
           "(eq. 16 of the CFRP-crushing paper), or G_I + (G_II − G_I)(G_II/G)^η (Benzeggagh & Kenane 1996)")
      .defaults_to("quadratic_ratio");
  k.quantity("bk_exponent", dim::none, "η of Benzeggagh–Kenane").above(0).defaults_to("2");
  k.quantity("friction", dim::none,
             "Coulomb coefficient of the contact between the two sides once failed (unless `contact` "
             "gives one for their materials)")
      .at_least(0)
      .defaults_to("0");
  return k;
}

namespace {

InterfaceInput read_interface(Section& s, const Scenario& sc, YAML::Node out) {
  InterfaceInput in;
  in.line = s.line();
  auto check = [&](const std::string& key, const std::string& name) {
    for (const auto& p : sc.parts)
      if (p.name == name) return p;
    std::vector<std::string> names;
    for (const auto& p : sc.parts) names.push_back(p.name);
    std::string reason = "no part named '" + name + "'";
    const std::string close = closest_match(name, names);
    if (!close.empty()) reason += " (did you mean '" + close + "'?)";
    s.fail(key, reason);
  };
  if (s.has("between") == s.has("plies_of"))
    s.fail(s.has("between") ? "plies_of" : "between",
           "give either 'between: [part_a, part_b]' or 'plies_of: <laminate part>'");
  if (s.has("between")) {
    const YAML::Node list = s.value("between");
    if (!list.IsSequence() || list.size() != 2)
      s.fail("between", "expected two part names, e.g. [upper, lower], got " + Section::shape(list));
    for (const auto& n : list) {
      check("between", n.Scalar());
      in.between.push_back(n.Scalar());
    }
    if (in.between[0] == in.between[1]) s.fail("between", "an interface joins two different parts");
    out["between"] = list;
  } else {
    in.plies_of = s.text("plies_of");
    const PartInput& part = check("plies_of", in.plies_of);
    if (!part.orientation || part.orientation->ply_thickness == 0)
      s.fail("plies_of", "part '" + in.plies_of + "' has no `laminate` (its plies come from a stacking sequence)");
  }
  CohesiveLaw& law = in.law;
  law.name = "interfaces[" + std::to_string(in.line) + "]";
  law.normal_strength = s.number("normal_strength");
  law.shear_strength = s.number("shear_strength");
  law.mode_one_energy = s.number("mode_one_energy");
  law.mode_two_energy = s.number("mode_two_energy");
  law.stiffness = s.number("stiffness");
  law.reference_size = s.number("reference_size");
  law.mixed_mode = *s.choice("mixed_mode") == "benzeggagh_kenane" ? MixedModeEnergy::benzeggagh_kenane
                                                                  : MixedModeEnergy::quadratic_ratio;
  law.bk_exponent = s.number("bk_exponent");
  in.friction = s.number("friction");
  // Linear softening needs the failure opening 2G/σ beyond the onset σ/K: K > σ²/(2G).
  const double need = std::max(law.normal_strength * law.normal_strength / (2 * law.mode_one_energy),
                               law.shear_strength * law.shear_strength / (2 * law.mode_two_energy));
  if (!(law.stiffness > need))
    s.fail("stiffness", "the penalty must exceed σ_f²/(2 G_Ic) and τ_f²/(2 G_IIc) = " + format_si(need, dim::stiffness_per_area) +
                            " for the softening to start after the onset; the interface would be more "
                            "compliant than the plies anyway: take about 50 E3/t");
  return in;
}

}  // namespace

void read_interfaces(Section& top, Scenario& sc) {
  static const KeyList keys = interface_keys();
  const YAML::Node list = top.value_or_null("interfaces");
  if (list.IsDefined() && !list.IsNull() && !list.IsSequence())
    top.fail("interfaces", "expected a list (entries starting with '- ')");
  YAML::Node list_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; list.IsSequence() && i < list.size(); ++i) {
    YAML::Node out(YAML::NodeType::Map);
    Section s(list[i], top.file(), "interfaces[" + std::to_string(i + 1) + "]", keys, out, line_of(list[i]));
    sc.interfaces.push_back(read_interface(s, sc, out));
    list_out.push_back(out);
  }
  if (top.has("interfaces")) sc.resolved["interfaces"] = list_out;
}

KeyList crash_keys() {
  KeyList k;
  k.add("wall", ValueKind::text, "the rigid wall (of `walls`) that measures the crushing force").must_be_given();
  k.add("stroke_part", ValueKind::text, "the part whose mean displacement towards the wall is the stroke (the carriage)")
      .must_be_given();
  k.add("crushed_part", ValueKind::text,
        "the part being crushed: SEA is the absorbed energy over its mass per unit length × the stroke")
      .must_be_given();
  k.quantity("cfc", dim::none, "SAE J211 channel frequency class of the force filter (60, 180, 600, 1000)")
      .above(0)
      .defaults_to("600");
  k.quantity("sample_interval", dim::time, "the force is resampled at this period before filtering").above(0).defaults_to("1 us");
  k.quantity("scale", dim::none, "multiplies forces and energies: the width of the specimen over the slice modelled")
      .above(0)
      .defaults_to("1");
  k.quantity("peak_window", dim::time,
             "also report the largest mean force over a window this long (a multiple of sample_interval); 0: not")
      .at_least(0)
      .defaults_to("0");
  return k;
}

/// Crash settings that read, but whose figures would mean nothing: the stroke part starting
/// across or away from the wall's normal (its stroke, the mean displacement along −normal, stays
/// near zero or negative, and SEA and efficiency with it), or the stroke read on the crushed part
/// itself (its mean displacement is about half the crush of a specimen shortening on the wall).
void warn_crash_geometry(const Section& s, const Scenario& sc, const CrashInput& in) {
  if (in.stroke_part == in.crushed_part)
    s.warn(0, "stroke_part",
           "the same part as crushed_part ('" + in.crushed_part + "'): the stroke is its mean displacement towards the "
           "wall, about half the crush of a specimen that shortens on it, and SEA and the mean force are read "
           "over that; with a carriage, give the carriage");
  const auto wall = std::find_if(sc.walls.begin(), sc.walls.end(), [&](const WallInput& w) { return w.name == in.wall; });
  if (std::any_of(wall->velocity.begin(), wall->velocity.end(), [](const auto& v) { return v.has_value(); })) return;
  // A later entry for the part replaces an earlier one: only the last acts.
  const auto last = std::find_if(sc.initial_velocities.rbegin(), sc.initial_velocities.rend(),
                                 [&](const InitialVelocityInput& ic) { return ic.part == in.stroke_part; });
  if (last == sc.initial_velocities.rend()) return;
  double speed = 0, towards = 0;
  for (int k = 0; k < 3; ++k) speed += last->velocity[k] * last->velocity[k], towards -= last->velocity[k] * wall->normal[k];
  speed = std::sqrt(speed);
  // Within about 84° of −normal: a carriage driven at an angle still crushes.
  if (speed == 0 || towards >= 0.1 * speed) return;
  s.warn(0, "wall",
         "part '" + in.stroke_part + "' (stroke_part) starts " +
             (towards <= -0.1 * speed ? std::string("away from") : std::string("across the normal of")) + " wall '" +
             in.wall + "' (" + format_si(towards, dim::velocity) + " of " + format_si(speed, dim::velocity) +
             " towards it, initial_conditions line " + std::to_string(last->line) +
             "): the stroke, its mean displacement along the wall's −normal, stays near zero or negative, and the "
             "SEA and crush-force efficiency with it; check the wall's normal (it points to the side where the bodies are)");
}

void read_crash(Section& top, Scenario& sc) {
  if (!top.has("crash")) return;
  static const KeyList keys = crash_keys();
  Section s(top.value("crash"), top.file(), "crash", keys, sc.resolved["crash"], top.line("crash"));
  CrashInput in;
  in.line = s.line();
  in.wall = s.text("wall");
  if (std::none_of(sc.walls.begin(), sc.walls.end(), [&](const WallInput& w) { return w.name == in.wall; })) {
    std::vector<std::string> names;
    for (const auto& w : sc.walls) names.push_back(w.name);
    std::string reason = "no wall named '" + in.wall + "'";
    const std::string close = closest_match(in.wall, names);
    if (!close.empty()) reason += " (did you mean '" + close + "'?)";
    s.fail("wall", reason + "; the crushing force is read on a rigid wall of `walls`");
  }
  for (const char* key : {"stroke_part", "crushed_part"}) {
    const std::string name = s.text(key);
    if (std::none_of(sc.parts.begin(), sc.parts.end(), [&](const PartInput& p) { return p.name == name; }))
      s.fail(key, "no part named '" + name + "'");
    (std::string(key) == "stroke_part" ? in.stroke_part : in.crushed_part) = name;
  }
  warn_crash_geometry(s, sc, in);
  in.cfc = s.number("cfc");
  if (in.cfc != 60 && in.cfc != 180 && in.cfc != 600 && in.cfc != 1000)
    s.fail("cfc", "SAE J211 defines the channel classes 60, 180, 600 and 1000");
  in.sample_interval = s.number("sample_interval");
  // The filter's design (ω_a = tan(ω_d T/2), ω_d = 2π·2.0775·CFC) needs T well below 1/(4.155 CFC).
  if (in.sample_interval > 0.1 / in.cfc)
    s.fail("sample_interval", "CFC " + std::to_string(static_cast<int>(in.cfc)) + " needs a sample interval of at most " +
                                  format_si(0.1 / in.cfc, dim::time) + " (1/(10 CFC))");
  in.scale = s.number("scale");
  in.peak_window = s.number("peak_window");
  if (in.peak_window > 0 && in.peak_window < in.sample_interval * (1 - 1e-9))
    s.fail("peak_window", "shorter than sample_interval (" + format_si(in.sample_interval, dim::time) +
                              "): the window holds at least one sample");
  const double samples = in.peak_window / in.sample_interval;
  if (std::abs(samples - std::round(samples)) > 1e-6 * std::max(1.0, samples))
    s.fail("peak_window", "not a whole number of sample intervals (" + format_si(in.sample_interval, dim::time) +
                              "): the window is a run of whole samples");
  sc.crash = in;
}

}  // namespace shard::scenario_detail

namespace shard::scenario_detail {

KeyList probe_keys() {
  KeyList k;
  k.add("name", ValueKind::text, "the probe's name: its file is probe_<name>.csv").must_be_given();
  KeySpec& p = k.add("point", ValueKind::vector, "a point: the probe follows the node nearest to it at the start");
  p.dimension = dim::length;
  k.add("group", ValueKind::text, "a Gmsh physical group: the probe gives the mean over its nodes (instead of `point`)");
  k.quantity("interval", dim::time, "time between rows (0: every step)").at_least(0).defaults_to("output.history_interval");
  return k;
}

void read_probes(Section& top, Scenario& sc) {
  if (!top.has("probes")) return;
  static const KeyList keys = probe_keys();
  const YAML::Node list = top.value("probes");
  if (!list.IsSequence()) top.fail("probes", "expected a list of probes, e.g. [{name: back_face, point: [0, -8.6 mm]}]");
  YAML::Node list_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < list.size(); ++i) {
    YAML::Node out(YAML::NodeType::Map);
    Section s(list[i], top.file(), "probes[" + std::to_string(i + 1) + "]", keys, out, line_of(list[i]));
    ProbeInput p;
    p.line = s.line();
    p.name = s.text("name");
    if (p.name.empty() || p.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
                              std::string::npos)
      s.fail("name", "a probe's name names its file: letters, digits, '_' and '-' only");
    for (const auto& other : sc.probes)
      if (other.name == p.name) s.fail("name", "a second probe named '" + p.name + "'");
    if (s.has("point") == s.has("group")) s.fail("name", "a probe needs either 'point' or 'group' (one of them)");
    if (s.has("point")) {
      const auto x = s.vector("point", static_cast<std::size_t>(sc.dim()));
      p.point = std::array<double, 3>{0, 0, 0};
      std::copy(x.begin(), x.end(), p.point->begin());
    }
    p.group = s.text("group");
    p.interval = s.number("interval", sc.output.history_interval);
    sc.probes.push_back(p);
    list_out.push_back(out);
  }
  sc.resolved["probes"] = list_out;
}

}  // namespace shard::scenario_detail
