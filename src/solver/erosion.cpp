#include "solver/erosion.hpp"

namespace shard {

std::vector<EnergyTerm> ErosionCompaction::conversion_energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"conversion_elastic", "elastic energy of elements converted to particles (they start stress-free)",
           r::eroded + 1, {{G::internal, -1}, {G::dissipated, +1}}, ""},
          {"conversion_kinetic", "kinetic energy of converted elements that their particles cannot carry",
           r::eroded + 2, {{G::dissipated, +1}}, ""}};
}

void ErosionCompaction::run(Model& model, EventContext& context) {
  if (context.eroded_elements == compacted_) return;  // nothing eroded since the last compaction
  compacted_ = context.eroded_elements;
  Remap remap;
  const ConversionResult converted = conversion_.prepare(model, materials_, remap);
  context.topology.apply(model, remap);
  conversion_.finish(model);
  if (converted.elements == 0) return;
  context.energy.at("conversion_kinetic") += converted.kinetic_taken - converted.kinetic_given;
  converted_elements_ += converted.elements;
  particles_made_ += converted.particles;
}

}  // namespace shard
