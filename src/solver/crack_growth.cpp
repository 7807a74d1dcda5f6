#include "solver/crack_growth.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "fem/internal_forces.hpp"

namespace shard {

CrackGrowth::CrackGrowth(const Model& model, const std::vector<std::unique_ptr<Material>>& materials,
                         CrackGrowthSettings settings)
    : settings_(std::move(settings)) {
  parts_.resize(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Material& m = *materials[model.parts[p].material];
    CrackingPart& cp = parts_[p];
    cp.density = m.density();
    cp.moduli = m.elastic();
  }
  for (int p : settings_.parts) {
    const Part& part = model.parts[p];
    const Material& m = *materials[part.material];
    const auto slots = m.failure_map_slots();
    SHARD_ASSERT(slots && part.type->is_triangle(), "part " << part.name << " cannot crack");
    CrackingPart& cp = parts_[p];
    cp.cracks = true;
    cp.factor_index = slots->factor;
    cp.reset_indices = slots->reset;
    cp.energy_density_index = slots->energy_density;
    cp.comminutes = settings_.comminution && part.erosion.to_particles;
    fields_.push_back({static_cast<std::size_t>(p), PointFailureField{}});
    normals_.push_back(slots->normal);
  }
}

std::size_t CrackGrowth::insert(Model& model, EnergyLedger& energy, Topology& topology, double time,
                                std::int64_t* eroded, std::vector<double>* part_stored) {
  if (settings_.parts.empty()) return 0;
  // No node can reach the threshold while no point has (the nodal factor is a weighted mean).
  bool any = false;
  for (std::size_t f = 0; f < fields_.size(); ++f) {
    const Part& part = model.parts[fields_[f].part];
    const CrackingPart& cp = parts_[fields_[f].part];
    fields_[f].field = failure_field_from_state(part, cp.factor_index, normals_[f]);
    any = any || max_point_factor(part, fields_[f].field) >= settings_.failure_threshold;
  }
  if (!any) return 0;
  nodal_failure_map(model, fields_, map_);
  CrackInsertionSettings s;
  s.failure_threshold = settings_.failure_threshold;
  s.min_fragment_elements = settings_.min_fragment_elements;
  s.time = time;
  const CrackInsertion ins = insert_cracks(model, parts_, map_.factor, map_.direction, s);
  energy.at("fracture") += ins.released_energy;
  if (part_stored)
    for (std::size_t p = 0; p < ins.released_by_part.size() && p < part_stored->size(); ++p)
      (*part_stored)[p] -= ins.released_by_part[p];
  const std::int64_t comminuted = comminute(model, ins, energy, part_stored);
  if (eroded) *eroded += comminuted;
  if (ins.new_node_count() == 0 && comminuted == 0) return 0;
  topology.changed(model, ins.remap);
  inserted_ += static_cast<std::int64_t>(ins.new_node_count());
  return ins.new_node_count();
}

bool CrackGrowth::may_split(Model& model) {
  if (settings_.parts.empty()) return false;
  bool any = false;
  for (std::size_t f = 0; f < fields_.size(); ++f) {
    const Part& part = model.parts[fields_[f].part];
    fields_[f].field = failure_field_from_state(part, parts_[fields_[f].part].factor_index, normals_[f]);
    any = any || max_point_factor(part, fields_[f].field) >= settings_.failure_threshold;
  }
  if (!any) return false;
  nodal_failure_map(model, fields_, map_);
  CrackInsertionSettings s;
  s.failure_threshold = settings_.failure_threshold;
  s.min_fragment_elements = settings_.min_fragment_elements;
  return cracks_would_change(model, parts_, map_.factor, map_.direction, s);
}

std::int64_t CrackGrowth::comminute(Model& model, const CrackInsertion& ins, EnergyLedger& energy,
                                    std::vector<double>* part_stored) {
  std::int64_t count = 0;
  for (const auto& [p, e] : ins.comminuted) {
    Part& part = model.parts[p];
    if (part.eroded[e]) continue;
    const CrackingPart& cp = parts_[p];
    const int npts = part.type->points;
    const std::size_t state_size = static_cast<std::size_t>(part.state_size);
    const double volume = std::abs(element_measure(part, model.nodes, e, model.formulation, model.thickness)) / npts;
    for (int q = 0; q < npts; ++q) {
      const std::size_t point = static_cast<std::size_t>(npts) * e + q;
      const double psi = cp.energy_density_index >= 0 ? part.state[state_size * point + cp.energy_density_index]
                                                      : cp.moduli.energy_density(&part.stress[kTensorSize * point]);
      energy.at("conversion_elastic") += psi * volume;
      if (part_stored && static_cast<std::size_t>(p) < part_stored->size()) (*part_stored)[p] -= psi * volume;
      std::fill_n(&part.stress[kTensorSize * point], kTensorSize, 0.0);
    }
    part.eroded[e] = 1;
    ++count;
  }
  comminuted_ += count;
  return count;
}

}  // namespace shard
