// Internal nodal forces of a part: kinematics, objective stress update, material, bulk viscosity,
// hourglass control, scatter, done by the part's element kernel (src/fem/element.hpp); lumped
// masses, measures and the element colouring. Theory: docs/theory/elements_and_kinematics.md.
#pragma once

#include <vector>

#include "core/energy_ledger.hpp"
#include "fem/element.hpp"
#include "fem/nonlocal_average.hpp"

namespace shard {

/// Share of the element's own dilatation and pressure kept in the averaged-nodal-pressure
/// elements (the rest is the nodal average). Pure averaging (0) leaves the element-wise
/// "checkerboard" of dilatations that averages to zero at every node without volumetric
/// stiffness; in severe plastic flow (a 287 m/s steel Taylor bar) elements then collapse near the
/// axis. A share α restores a stiffness α²K against that mode only (α of the dilatation, α of the
/// pressure; cf. the stabilised nodal integration of Puso & Solberg 2006): 0.01 K, which locks
/// like a standard element with K' = α²K (measured, tests/verification/test_volumetric_locking.cpp).
/// 0.1 survives that case and changes the Taylor-bar length by less than 0.5 % at 190–208 m/s
/// (docs/theory/elements_and_kinematics.md, section 11).
inline constexpr double kNodalPressureElementShare = 0.1;

/// The energy terms the element kernels book (ForceSums): stress work, bulk viscosity, hourglass
/// control, plastic work (and the heat it became), fracture and the energy eroded elements took.
std::vector<EnergyTerm> element_energy_terms();

/// What the element pass of a part keeps from one step to the next besides the Model (derived
/// from it; the caller keeps one per part and clears it when the topology changes).
struct PartCache {
  NonlocalNeighbours nonlocal;  ///< the neighbourhoods of a non-local material's points
};

/// Updates stresses and state of every point of `part` with the velocities in `nodes.v` over
/// `ctx.dt`, on the current positions `nodes.x`, and subtracts the internal forces from
/// `nodes.force` (the part's kernel), then runs the part-level pass of a non-local material. The
/// result is the same for any number of OpenMP threads.
ForceSums add_internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                              const StepContext& ctx, PartCache& cache);

/// Element volumes/areas on the current positions (no stress update); used for masses and the
/// initial time step.
double element_measure(const Part& part, const NodeArrays& nodes, std::size_t element,
                       Formulation formulation, double thickness);

/// Adds the lumped (row-sum) masses of the part's elements to `mass` (one per node).
void add_lumped_masses(const Part& part, const NodeArrays& nodes, double density, Formulation formulation,
                       double thickness, std::vector<double>& mass);

/// Colours the elements of part `part` so that no two elements of one colour share a node
/// (greedy, in element order), and orders them by colour, keeping their order within a colour (a
/// remap of the part's elements: every declared field follows, and so do the facets that bound
/// them); fills part.colour_begin.
void colour_elements(Model& model, std::size_t part);

}  // namespace shard
