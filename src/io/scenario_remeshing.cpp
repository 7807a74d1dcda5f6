#include "io/scenario_remeshing.hpp"

#include <algorithm>
#include <numbers>

#include "core/units.hpp"

namespace shard::scenario_detail {

KeyList remeshing_keys() {
  KeyList k;
  k.add("parts", ValueKind::list, "the parts remeshed and their size rules (a list of remeshing.parts[] entries)")
      .must_be_given();
  k.add("check_interval", ValueKind::integer, "steps between two assessments of the mesh (the paper's f)")
      .at_least(1)
      .defaults_to("50");
  k.quantity("distortion", dim::none,
             "remesh when an element's area or a corner angle has changed by more than this fraction since it was "
             "made (eqs. 1-2 of the ceramics paper, which uses 0.025; elastic compression alone reaches that in "
             "hard materials); 0: not used")
      .at_least(0)
      .defaults_to("0");
  k.quantity("min_angle", dim::none, "remesh when a corner angle falls below this (e.g. 15 deg; a plain number is in radians); 0: not used")
      .at_least(0)
      .below(std::numbers::pi / 3)
      .defaults_to("15 deg");
  k.quantity("max_angle", dim::none, "remesh when a corner angle rises above this (e.g. 160 deg); 0: not used")
      .at_least(0)
      .below(std::numbers::pi)
      .defaults_to("160 deg");
  k.quantity("size_mismatch", dim::none,
             "remesh when an element is this many times larger than the size rule asks for, or smaller than its "
             "reciprocal; 0: not used")
      .at_least(0)
      .defaults_to("0");
  k.add("max_interval", ValueKind::integer, "remesh the whole part at least every this many steps (0: not used)")
      .at_least(0)
      .defaults_to("0");
  k.add("patch_rings", ValueKind::integer,
        "local remeshing: when only the elements' shape is due (distortion, min_angle, max_angle), remesh a patch "
        "of the poor elements and this many rings of elements around them, its boundary kept node for node; "
        "0: always the whole part")
      .at_least(0)
      .defaults_to("0");
  k.quantity("patch_max_fraction", dim::none,
             "the whole part is remeshed instead when the patch would hold more than this fraction of its elements")
      .above(0)
      .at_most(1)
      .defaults_to("0.3");
  return k;
}

KeyList remeshed_part_keys() {
  KeyList k;
  k.add("part", ValueKind::text, "the part (of triangles)").must_be_given();
  k.choice("size_by", {"uniform", "strain_rate", "inelastic_strain", "error"},
           "what sets the element size: one size; a table of the effective total strain rate (1/s) or of the "
           "equivalent inelastic strain (tables V and IX of the ceramics paper); or the Zienkiewicz-Zhu energy-norm "
           "error with recovered stresses (eqs. 3-8)")
      .defaults_to("uniform");
  k.add("table", ValueKind::list, "[[measure, size], ...] with increasing measures, e.g. [[0, 5 mm], [1e6, 0.75 mm]]");
  k.quantity("size", dim::length, "the size of `size_by: uniform` (default: the part's sizes as they are)")
      .above(0);
  k.quantity("error_target", dim::none, "η̄: the relative energy-norm error aimed at (size_by: error)")
      .above(0)
      .below(1)
      .defaults_to("0.05");
  k.quantity("min_size", dim::length, "h_min: no element smaller (0: none)").at_least(0).defaults_to("0");
  k.quantity("max_size", dim::length, "h_max: no element larger (0: none)").at_least(0).defaults_to("0");
  k.quantity("max_refinement", dim::none, "one remesh makes an element at most this many times smaller")
      .at_least(1)
      .defaults_to("4");
  k.quantity("max_coarsening", dim::none, "one remesh makes an element at most this many times larger")
      .at_least(1)
      .defaults_to("2");
  k.add("max_elements", ValueKind::integer, "the part's element budget: sizes grow to keep within it (0: none)")
      .at_least(0)
      .defaults_to("0");
  k.quantity("gradation", dim::none, "the size grows by at most this much per unit distance").above(0).defaults_to("0.3");
  k.quantity("refine_ahead", dim::length,
             "each element takes the smallest size asked for within this distance of it, so that a wave finds the "
             "mesh fine where it arrives before the next assessment: at least the distance the fastest wave travels "
             "in check_interval steps (0: each element its own)")
      .at_least(0)
      .defaults_to("0");
  k.add("keep_cracked", ValueKind::boolean,
        "keep the elements with a node on a crack face as they are and remesh only the material around them: Gmsh "
        "never meshes between crack lips (kept node for node, they would give it thin triangles and a short step), "
        "and a cracked zone keeps the elements it cracked in")
      .defaults_to("false");
  k.choice("transfer", {"least_squares", "projection"},
           "how the integration-point state is carried: linear moving least squares, or the ceramics paper's "
           "projection through nodal averages (smears sharp fields; kept as a reference)")
      .defaults_to("least_squares");
  k.choice("algorithm", {"delaunay", "frontal_delaunay"},
           "Gmsh's 2D algorithm tried first (the other is tried next): delaunay is faster, frontal_delaunay makes "
           "more regular triangles")
      .defaults_to("delaunay");
  k.add("smoothing", ValueKind::integer,
        "Laplacian smoothing passes of the new mesh: fewer small triangles (a longer stable step), slower remeshes "
        "and a transfer over a mesh further from the old one")
      .at_least(0)
      .at_most(10)
      .defaults_to("0");
  return k;
}

namespace {

std::vector<std::array<double, 2>> read_table(Section& s, SizeMeasure measure) {
  const YAML::Node rows = s.value("table");
  if (!rows.IsSequence() || rows.size() == 0)
    s.fail("table", "expected rows [measure, size], e.g. [[0, 5 mm], [1e6, 0.75 mm]], got " + Section::shape(rows));
  const Dimension first = measure == SizeMeasure::strain_rate ? dim::rate : dim::none;
  std::vector<std::array<double, 2>> table;
  YAML::Node out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const YAML::Node row = rows[i];
    if (!row.IsSequence() || row.size() != 2 || !row[0].IsScalar() || !row[1].IsScalar())
      throw InputError(s.file(), line_of(row), s.key_path("table"), "each row is [measure, size], got " + Section::shape(row));
    std::array<double, 2> r{};
    try {
      r[0] = parse_quantity_as(row[0].Scalar(), first);
      r[1] = parse_quantity_as(row[1].Scalar(), dim::length);
    } catch (const std::invalid_argument& e) {
      throw InputError(s.file(), line_of(row), s.key_path("table"), e.what());
    }
    if (!(r[1] > 0)) throw InputError(s.file(), line_of(row), s.key_path("table"), "a size must be above 0");
    if (!table.empty() && !(r[0] > table.back()[0]))
      throw InputError(s.file(), line_of(row), s.key_path("table"),
                       "the measures must increase from row to row (row " + std::to_string(i + 1) + ")");
    table.push_back(r);
    YAML::Node o(YAML::NodeType::Sequence);
    o.SetStyle(YAML::EmitterStyle::Flow);
    o.push_back(r[0]);
    o.push_back(r[1]);
    out.push_back(o);
  }
  s.resolved()["table"] = out;
  return table;
}

RemeshedPartInput read_part(Section& s, const Scenario& sc) {
  RemeshedPartInput in;
  in.line = s.line();
  in.part = s.text("part");
  std::vector<std::string> names;
  for (const auto& p : sc.parts) names.push_back(p.name);
  if (std::find(names.begin(), names.end(), in.part) == names.end()) {
    std::string reason = "no part named '" + in.part + "'";
    const std::string close = closest_match(in.part, names);
    if (!close.empty()) reason += " (did you mean '" + close + "'?)";
    s.fail("part", reason);
  }
  SizeRule& rule = in.settings.size;
  const std::string by = s.choice("size_by").value_or("uniform");
  rule.measure = by == "strain_rate"        ? SizeMeasure::strain_rate
                 : by == "inelastic_strain" ? SizeMeasure::inelastic_strain
                 : by == "error"            ? SizeMeasure::error
                                            : SizeMeasure::uniform;
  const bool tabled = rule.measure == SizeMeasure::strain_rate || rule.measure == SizeMeasure::inelastic_strain;
  if (tabled && !s.has("table")) s.fail("size_by", "size_by: " + by + " reads its sizes from a `table` of [measure, size] rows");
  if (!tabled && s.has("table")) s.fail("table", "a table is read only with size_by: strain_rate or inelastic_strain");
  if (tabled) rule.table = read_table(s, rule.measure);
  if (s.has("size") && rule.measure != SizeMeasure::uniform) s.fail("size", "`size` is the size of size_by: uniform");
  if (s.has("size")) rule.uniform_size = s.number("size");
  rule.error_target = s.number("error_target");
  rule.h_min = s.number("min_size");
  rule.h_max = s.number("max_size");
  if (rule.h_max > 0 && rule.h_min > rule.h_max) s.fail("min_size", "min_size is above max_size");
  rule.max_refinement = s.number("max_refinement");
  rule.max_coarsening = s.number("max_coarsening");
  rule.max_elements = s.integer("max_elements");
  rule.gradation = s.number("gradation");
  rule.refine_ahead = s.number("refine_ahead");
  in.settings.transfer =
      s.choice("transfer").value_or("least_squares") == "projection" ? PointTransfer::projection : PointTransfer::least_squares;
  in.settings.algorithm =
      s.choice("algorithm").value_or("delaunay") == "frontal_delaunay" ? MeshAlgorithm::frontal_delaunay : MeshAlgorithm::delaunay;
  in.settings.smoothing = static_cast<int>(s.integer("smoothing"));
  in.settings.keep_cracked = s.boolean("keep_cracked");
  return in;
}

}  // namespace

void read_remeshing(Section& top, Scenario& sc) {
  if (!top.has("remeshing")) return;
  static const KeyList keys = remeshing_keys();
  static const KeyList part_keys = remeshed_part_keys();
  YAML::Node resolved(YAML::NodeType::Map);
  Section r(top.value("remeshing"), top.file(), "remeshing", keys, resolved, top.line("remeshing"));
  RemeshingInput in;
  in.line = top.line("remeshing");
  in.triggers.check_interval = r.integer("check_interval");
  in.triggers.distortion = r.number("distortion");
  in.triggers.min_angle = r.number("min_angle");
  in.triggers.max_angle = r.number("max_angle");
  in.triggers.size_mismatch = r.number("size_mismatch");
  if (in.triggers.size_mismatch > 0 && in.triggers.size_mismatch <= 1)
    r.fail("size_mismatch", "a mismatch factor is above 1 (e.g. 1.5), or 0 for none");
  in.triggers.max_interval = r.integer("max_interval");
  in.triggers.patch_rings = static_cast<int>(r.integer("patch_rings"));
  in.triggers.patch_max_fraction = r.number("patch_max_fraction");
  const YAML::Node list = r.value("parts");
  if (!list.IsSequence() || list.size() == 0)
    r.fail("parts", "expected a list of parts, e.g. [{part: beam, size_by: strain_rate, table: [[0, 5 mm], [1e6, 0.75 mm]]}]");
  YAML::Node list_out(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < list.size(); ++i) {
    YAML::Node out(YAML::NodeType::Map);
    Section s(list[i], top.file(), "remeshing.parts[" + std::to_string(i + 1) + "]", part_keys, out, line_of(list[i]));
    RemeshedPartInput part = read_part(s, sc);
    for (const auto& other : in.parts)
      if (other.part == part.part) s.fail("part", "part '" + part.part + "' is listed twice");
    in.parts.push_back(std::move(part));
    list_out.push_back(out);
  }
  resolved["parts"] = list_out;
  sc.resolved["remeshing"] = resolved;
  sc.remeshing = std::move(in);
}

}  // namespace shard::scenario_detail
