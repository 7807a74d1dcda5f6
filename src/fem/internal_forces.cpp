#include "fem/internal_forces.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <vector>

#include "fem/nonlocal_average.hpp"
#include "model/remap.hpp"

namespace shard {

void ForceSums::add(const ForceSums& o) {
  stress_work += o.stress_work;
  viscous_work += o.viscous_work;
  hourglass_work += o.hourglass_work;
  plastic_work += o.plastic_work;
  fracture_work += o.fracture_work;
  heat += o.heat;
  eroded_energy += o.eroded_energy;
  eroded_elements += o.eroded_elements;
  stable_dt = std::min(stable_dt, o.stable_dt);
  if (o.inverted_element >= 0 && (inverted_element < 0 || o.inverted_element < inverted_element))
    inverted_element = o.inverted_element;
}

std::vector<EnergyTerm> element_energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"stress_work", "work of the stresses, ∫∫ σ:D dV dt (stored plus dissipated by the materials)", r::stress_work,
           {{G::internal, +1}}, "-"},
          {"viscosity", "dissipated by the bulk (artificial) viscosity", r::viscosity, {{G::dissipated, +1}}, ""},
          {"hourglass", "dissipated by the hourglass control", r::hourglass, {{G::dissipated, +1}}, ""},
          {"plastic", "plastic work", r::plastic, {{G::internal, -1}, {G::dissipated, +1}}, ""},
          {"heat", "the part of the plastic work that became heat (β W_p), not a separate sink", r::heat, {}, ""},
          {"fracture", "fracture energy (softening, crack insertion, broken bonds)", r::fracture,
           {{G::internal, -1}, {G::dissipated, +1}}, ""},
          // What an eroded element stored leaves the stored energy (internal) for good.
          {"eroded", "elastic energy carried away by eroded elements", r::eroded,
           {{G::internal, -1}, {G::dissipated, +1}}, ""}};
}

namespace {
std::map<const ElementType*, std::unique_ptr<ElementKernel>>& kernels() {
  static std::map<const ElementType*, std::unique_ptr<ElementKernel>> registry;
  return registry;
}
}  // namespace

bool register_element(ElementType type, std::unique_ptr<ElementKernel> kernel) {
  const std::string name = type.name;
  if (!register_element_type(std::move(type))) return false;
  kernels()[find_element_type(name)] = std::move(kernel);
  return true;
}

const ElementKernel& kernel_of(const ElementType& type) {
  const auto it = kernels().find(&type);
  if (it == kernels().end()) throw std::logic_error("element type '" + type.name + "' has no kernel");
  return *it->second;
}

ForceSums add_internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                              const StepContext& ctx, PartCache& cache) {
  const ForceSums sums = kernel_of(*part.type).internal_forces(part, material, nodes, ctx);
  // Part-level pass of materials with a non-local history variable (src/fem/nonlocal_average.hpp),
  // on the state just updated.
  if (const auto* nonlocal = dynamic_cast<const NonlocalAveraging*>(&material)) {
    const NonlocalSpec spec = nonlocal->nonlocal_spec();
    if (spec.length > 0) average_nonlocal(part, nodes, spec, material.state_size(), cache.nonlocal);
  }
  return sums;
}

double element_measure(const Part& part, const NodeArrays& nodes, std::size_t e,
                       Formulation formulation, double thickness) {
  return kernel_of(*part.type).measure(part, nodes, e, formulation, thickness);
}

void add_lumped_masses(const Part& part, const NodeArrays& nodes, double density, Formulation formulation,
                       double thickness, std::vector<double>& mass) {
  kernel_of(*part.type).lump_masses(part, nodes, density, formulation, thickness, mass.data());
}

void colour_elements(Model& model, std::size_t p) {
  Part& part = model.parts[p];
  const int npe = part.type->nodes;
  const std::size_t ne = part.element_count();
  std::vector<std::uint64_t> used(model.nodes.count(), 0);  // colours used at each node (≤ 64)
  part.colour.assign(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    std::uint64_t taken = 0;
    for (int a = 0; a < npe; ++a) taken |= used[part.connectivity[npe * e + a]];
    int c = 0;
    while (c < 64 && (taken >> c & 1u)) ++c;
    if (c == 64) throw std::runtime_error("part '" + part.name + "': more than 64 element colours");
    part.colour[e] = static_cast<std::uint8_t>(c);
    for (int a = 0; a < npe; ++a) used[part.connectivity[npe * e + a]] |= std::uint64_t{1} << c;
  }
  // A stable reorder by colour: a topology change that moves every declared element field (and
  // the facets that bound the elements), then colour_begin.
  Remap order;
  order.elements.emplace(static_cast<int>(p), colour_order(part).value_or(EntityRemap::identity(ne)));
  apply_remap(model, order);
}

}  // namespace shard
