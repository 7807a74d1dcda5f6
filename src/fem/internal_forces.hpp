// Internal nodal forces of a part: kinematics, objective stress update, material, bulk viscosity,
// hourglass control, scatter. Theory: docs/theory/elements_and_kinematics.md.
#pragma once

#include <cstdint>
#include <limits>

#include "material/material.hpp"
#include "model/model.hpp"

namespace shard {

struct StepContext {
  Formulation formulation = Formulation::plane_strain;
  double thickness = 1.0;    ///< plane strain / plane stress
  double dt = 0.0;           ///< Δt_n-1/2: the increment the velocities in `nodes.v` act over
  double q_linear = 0.06;    ///< bulk viscosity, linear coefficient
  double q_quadratic = 1.5;  ///< bulk viscosity, quadratic coefficient
};

/// Sums over a part for one step. Work terms are for the increment just taken (J).
struct ForceSums {
  double stress_work = 0;     ///< ∫ ½(σ_n + σ_n+1) : Δε dV
  double viscous_work = 0;    ///< bulk viscosity dissipation
  double hourglass_work = 0;  ///< hourglass control dissipation
  double plastic_work = 0;    ///< from the material
  double fracture_work = 0;   ///< from the material
  double heat = 0;            ///< the part of plastic_work that became heat
  double eroded_energy = 0;   ///< elastic energy of the elements eroded in this step
  std::int64_t eroded_elements = 0;  ///< elements eroded in this step
  double stable_dt = std::numeric_limits<double>::infinity();  ///< min over elements
  std::int64_t inverted_element = -1;  ///< first element with non-positive volume, or -1

  void add(const ForceSums& o);
};

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

/// Updates stresses and state of every point of `part` with the velocities in `nodes.v` over
/// `ctx.dt`, on the current positions `nodes.x`, and subtracts the internal forces from
/// `nodes.force`. The result is the same for any number of OpenMP threads.
ForceSums add_internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                              const StepContext& ctx);

/// Element volumes/areas and characteristic lengths on the current positions (no stress update);
/// used for masses and the initial time step.
double element_measure(const Part& part, const NodeArrays& nodes, std::size_t element,
                       Formulation formulation, double thickness);

/// Orders the elements of a part by colour so that no two elements of one colour share a node
/// (greedy, in element order), and fills part.colour_begin. Keeps the order within a colour.
void colour_elements(Part& part, std::size_t node_count);

}  // namespace shard
