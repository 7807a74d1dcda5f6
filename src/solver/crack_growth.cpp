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
    cp.heals = slots->heals;
    cp.weakest_flaw_index = slots->weakest_flaw;
    cp.energy_density_index = slots->energy_density;
    cp.comminutes = settings_.comminution && part.erosion.to_particles;
    fields_.push_back({static_cast<std::size_t>(p), PointFailureField{}});
    normals_.push_back(slots->normal);
  }
}

bool CrackGrowth::map_failure(const Model& model) {
  if (settings_.parts.empty()) return false;
  // No node can reach the threshold while no point has (the nodal factor is a weighted mean).
  bool any = false;
  for (std::size_t f = 0; f < fields_.size(); ++f) {
    const Part& part = model.parts[fields_[f].part];
    fields_[f].field = failure_field_from_state(part, parts_[fields_[f].part].factor_index, normals_[f]);
    any = any || max_point_factor(part, fields_[f].field) >= settings_.failure_threshold;
  }
  if (!any) return false;
  nodal_failure_map(model, fields_, map_);
  return true;
}

CrackInsertionSettings CrackGrowth::insertion_settings(double time) const {
  CrackInsertionSettings s;
  s.failure_threshold = settings_.failure_threshold;
  s.min_fragment_elements = settings_.min_fragment_elements;
  s.time = time;
  return s;
}

void CrackGrowth::book_released(const CrackInsertion& ins, EnergyLedger& energy, std::vector<double>* part_stored) {
  energy.at("fracture") += ins.released_energy;
  if (part_stored)
    for (std::size_t p = 0; p < ins.released_by_part.size() && p < part_stored->size(); ++p)
      (*part_stored)[p] -= ins.released_by_part[p];
}

std::size_t CrackGrowth::insert(Model& model, EnergyLedger& energy, Topology& topology, double time,
                                std::int64_t* eroded, std::vector<double>* part_stored) {
  if (!map_failure(model)) return 0;
  keep_to_crack_tips(model, parts_, settings_.failure_threshold, map_.factor);
  hold_back_cracks(model, parts_, settings_.speed_limit, time, settings_.failure_threshold, map_.direction,
                   map_.factor);
  const CrackInsertion ins = insert_cracks(model, parts_, map_.factor, map_.direction, insertion_settings(time));
  book_released(ins, energy, part_stored);
  const std::int64_t comminuted = comminute(model, ins, energy, part_stored);
  if (eroded) *eroded += comminuted;
  if (ins.new_node_count() == 0 && comminuted == 0) return 0;
  topology.changed(model, ins.remap);
  inserted_ += static_cast<std::int64_t>(ins.new_node_count());
  return ins.new_node_count();
}

bool CrackGrowth::may_split(Model& model) {
  if (!map_failure(model)) return false;
  return cracks_would_change(model, parts_, map_.factor, map_.direction, insertion_settings(0));
}

std::vector<double> CrackGrowth::owned_failed_nodes(Model& local, std::span<const std::int32_t> global_node,
                                                    std::span<const std::uint8_t> node_owned) {
  std::vector<double> out;
  if (!map_failure(local)) return out;
  const std::size_t nn = local.nodes.count();
  std::vector<std::int32_t> slot(nn, -1);
  std::vector<std::int32_t> failed;
  for (std::size_t i = 0; i < nn; ++i)
    if (node_owned[i] && map_.factor[i] >= settings_.failure_threshold) {
      slot[i] = static_cast<std::int32_t>(failed.size());
      failed.push_back(static_cast<std::int32_t>(i));
    }
  if (failed.empty()) return out;
  // The star of each: the nodes of the live triangles around it, whose positions the planner reads.
  std::vector<std::vector<std::int32_t>> star(failed.size());
  for (const Part& part : local.parts) {
    if (!part.type->is_triangle()) continue;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;
      const std::int32_t* cn = &part.connectivity[3 * e];
      for (int a = 0; a < 3; ++a)
        if (slot[cn[a]] >= 0) star[slot[cn[a]]].insert(star[slot[cn[a]]].end(), cn, cn + 3);
    }
  }
  const double* x = local.nodes.x.data();
  for (std::size_t k = 0; k < failed.size(); ++k) {
    const std::int32_t p = failed[k];
    auto& nodes = star[k];
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    out.insert(out.end(), {static_cast<double>(global_node[p]), map_.factor[p], map_.direction[2 * p],
                           map_.direction[2 * p + 1], static_cast<double>(nodes.size())});
    for (const std::int32_t n : nodes) out.insert(out.end(), {static_cast<double>(global_node[n]), x[2 * n], x[2 * n + 1]});
  }
  return out;
}

CrackInsertion CrackGrowth::split_whole(Model& whole, const std::vector<std::vector<double>>& failed, double time) {
  const std::size_t nn = whole.nodes.count();
  std::vector<double> factor(nn, 0.0), normal(2 * nn, 0.0);
  double* x = whole.nodes.x.data();
  for (const std::vector<double>& from : failed)
    for (std::size_t at = 0; at < from.size();) {
      const auto p = static_cast<std::size_t>(from[at]);
      factor[p] = from[at + 1];
      normal[2 * p] = from[at + 2];
      normal[2 * p + 1] = from[at + 3];
      const auto count = static_cast<std::size_t>(from[at + 4]);
      at += 5;
      for (std::size_t k = 0; k < count; ++k, at += 3) {
        const auto n = static_cast<std::size_t>(from[at]);
        x[2 * n] = from[at + 1];
        x[2 * n + 1] = from[at + 2];
      }
    }
  CrackInsertion ins = split_cracks(whole, parts_, factor, normal, insertion_settings(time));
  inserted_ += static_cast<std::int64_t>(ins.new_node_count());
  return ins;
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
