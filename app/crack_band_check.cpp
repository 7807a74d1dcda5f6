#include "app/crack_band_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "fem/internal_forces.hpp"

namespace shard {

double crack_band_width(const Part& part, const NodeArrays& nodes, std::size_t e) {
  if (part.type->dim == 2) {
    const double area = element_measure(part, nodes, e, Formulation::plane_strain, 1.0);
    return std::sqrt(2.0 * std::abs(area));
  }
  const double volume = std::abs(element_measure(part, nodes, e, Formulation::three_d, 1.0));
  return std::cbrt(part.type->nodes == 4 ? 6.0 * volume : volume);
}

namespace {

/// A warning placed at the line of the scenario's material `material` (its key named).
std::string warning_at_material(const Scenario& scenario, int material, const std::string& text) {
  const auto& input = scenario.materials[static_cast<std::size_t>(material)];
  return InputError(shown_path(scenario.file), input.line, "materials." + input.name, text).what();
}

}  // namespace

std::vector<std::string> crack_band_warnings(const Scenario& scenario, const Simulation& sim) {
  std::vector<std::string> warnings;
  for (const Part& part : sim.model.parts) {
    const Material& material = *sim.materials[part.material];
    const double limit = material.crack_band_limit();
    if (!std::isfinite(limit)) continue;
    // Each element against the limit at its own strength (a Weibull field makes the stronger,
    // smaller elements need smaller sizes); the first point's state stands for the element's.
    const std::size_t per_element = static_cast<std::size_t>(part.type->points) * material.state_size();
    std::size_t larger = 0;
    double largest = 0.0, tightest = limit;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      const double h = crack_band_width(part, sim.model.nodes, e);
      const double own = part.state.empty() ? limit : material.crack_band_limit(&part.state[per_element * e]);
      largest = std::max(largest, h);
      tightest = std::min(tightest, own);
      if (h > own) ++larger;
    }
    if (larger == 0) continue;
    char text[1024];
    std::snprintf(text, sizeof text,
                  "part '%s': %zu of %zu elements are wider than the crack-band limit of material '%s' "
                  "(%s), %.3g mm at its tensile strength (the largest element %.3g mm across): in them "
                  "the softening would snap back, so the model acts as a strength criterion (a point "
                  "fails when its stress reaches the tensile strength, with less than the fracture "
                  "energy dissipated). Elements of %.3g mm or less across make it a regularised crack "
                  "band%s%s",
                  part.name.c_str(), larger, part.element_count(), material.name().c_str(),
                  std::string(material.model()).c_str(), 1e3 * limit, 1e3 * largest, 1e3 * tightest,
                  tightest < limit ? " (the strongest elements of its Weibull field need that)" : "",
                  material.failure_depends_on_loading_rate()
                      ? ". Under fast loading its cracks open above the tensile strength, where the limit "
                        "is smaller still (it falls as the square of the strength)"
                      : "");
    warnings.push_back(warning_at_material(scenario, part.material, text));
  }
  return warnings;
}

std::vector<CrackBandReport> crack_band_reports(const Model& model, const std::vector<std::unique_ptr<Material>>& materials) {
  std::vector<CrackBandReport> reports;
  for (const Part& part : model.parts) {
    const Material& material = *materials[static_cast<std::size_t>(part.material)];
    if (!std::isfinite(material.crack_band_limit())) continue;
    CrackBandReport r{part.name, material.name(), material.failure_depends_on_loading_rate()};
    const std::size_t stride = static_cast<std::size_t>(part.state_size);
    for (std::size_t q = 0; stride > 0 && q < part.point_count(); ++q) {
      const Material::OpenedCrack crack = material.opened_crack(&part.state[stride * q]);
      if (!crack.opened) continue;
      ++r.opened;
      r.largest_stress = std::max(r.largest_stress, crack.stress);
      if (!(crack.band_width > crack.limit)) continue;
      r.smallest_limit = r.wider == 0 ? crack.limit : std::min(r.smallest_limit, crack.limit);
      ++r.wider;
    }
    reports.push_back(r);
  }
  return reports;
}

std::string crack_band_note(const CrackBandReport& r) {
  if (!r.rate_dependent || r.wider == 0) return {};
  char text[768];
  std::snprintf(text, sizeof text,
                "part '%s': %zu of the %zu points of material '%s' with an open crack opened it in a "
                "band wider than the crack-band limit at the stress it opened at (down to %.3g mm; "
                "cracks opened at up to %.4g MPa): their softening snapped back, and there the model "
                "acted as a strength criterion at that stress (docs/theory/rotating_crack.md, section 6b)",
                r.part.c_str(), r.wider, r.opened, r.material.c_str(), 1e3 * r.smallest_limit,
                1e-6 * r.largest_stress);
  return text;
}

std::vector<std::string> loading_rate_warnings(const Scenario& scenario, const Simulation& sim) {
  std::vector<std::string> warnings;
  if (scenario.bulk_viscosity_length > 0 || !(scenario.bulk_viscosity_linear > 0)) return warnings;
  std::vector<char> seen(sim.materials.size(), 0);
  for (const Part& part : sim.model.parts) {
    const Material& material = *sim.materials[part.material];
    if (seen[part.material] || !material.failure_depends_on_loading_rate()) continue;
    seen[part.material] = 1;
    char text[768];
    std::snprintf(text, sizeof text,
                  "material '%s' (%s) fails by how fast the stress rises, and the linear bulk viscosity "
                  "(bulk_viscosity_linear %.3g) spreads a wave front over a length that shrinks with "
                  "the elements, so its results move with the mesh (the SiC edge-on impact's damage "
                  "front: 6 480 to 9 250 m/s from 0.5 to 0.18 mm). Give analysis.bulk_viscosity_length "
                  "(a length about C_l times the element size you trust, e.g. 12 um for 0.25 mm "
                  "triangles) to spread it over the same length on every mesh",
                  material.name().c_str(), std::string(material.model()).c_str(), scenario.bulk_viscosity_linear);
    warnings.push_back(warning_at_material(scenario, part.material, text));
  }
  return warnings;
}

}  // namespace shard
