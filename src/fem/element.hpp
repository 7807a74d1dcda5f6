// The element kernel interface and its registry: one file per element type (tri3.cpp, tet4.cpp,
// hex8.cpp, hex8_reduced.cpp) implements ElementKernel and registers it with its ElementType
// (src/model/element_type.hpp) in one line. A kernel is called once per part and step; inside, it
// loops over batches of the part's elements in tight, inlined code (src/fem/element_loops.hpp).
// Theory: docs/theory/elements_and_kinematics.md.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>

#include "material/material.hpp"
#include "model/element_type.hpp"
#include "model/model.hpp"

namespace shard {

struct StepContext {
  Formulation formulation = Formulation::plane_strain;
  double thickness = 1.0;    ///< plane strain / plane stress
  double dt = 0.0;           ///< Δt_n-1/2: the increment the velocities in `nodes.v` act over
  double q_linear = 0.06;    ///< bulk viscosity, linear coefficient
  /// Bulk viscosity, linear term as a length ℓ_v (0: C_l times the element's length): the
  /// linear pressure ρ c ℓ_v |ε̇_v| is then the same on every mesh.
  double q_length = 0.0;
  double q_quadratic = 1.5;  ///< bulk viscosity, quadratic coefficient
};

/// Sums over a part for one step. Work terms are for the increment just taken (J), summed
/// exactly (src/core/exact_sum.hpp): the same bits whatever the batches, threads or ranks.
struct ForceSums {
  ExactSum stress_work;     ///< ∫ ½(σ_n + σ_n+1) : Δε dV
  ExactSum viscous_work;    ///< bulk viscosity dissipation
  ExactSum hourglass_work;  ///< hourglass control dissipation
  ExactSum plastic_work;    ///< from the material
  ExactSum fracture_work;   ///< from the material
  ExactSum heat;            ///< the part of plastic_work that became heat
  ExactSum eroded_energy;   ///< elastic energy of the elements eroded in this step
  std::int64_t eroded_elements = 0;  ///< elements eroded in this step
  double stable_dt = std::numeric_limits<double>::infinity();  ///< min over elements
  std::int64_t inverted_element = -1;  ///< first element with non-positive volume, or -1

  void add(const ForceSums& o);
};

/// The physics of one element type.
class ElementKernel {
 public:
  virtual ~ElementKernel() = default;
  /// Updates stresses and state of every point of `part` with the velocities in `nodes.v` over
  /// `ctx.dt`, on the current positions `nodes.x`, and subtracts the internal forces from
  /// `nodes.force`. The result is the same for any number of OpenMP threads.
  virtual ForceSums internal_forces(Part& part, const Material& material, NodeArrays& nodes,
                                    const StepContext& ctx) const = 0;
  /// Adds each element's lumped (row-sum) masses to mass[node], on the positions nodes.x.
  virtual void lump_masses(const Part& part, const NodeArrays& nodes, double density,
                           Formulation formulation, double thickness, double* mass) const = 0;
  /// The volume element e stands for (2D: area × thickness; axisymmetric: of the ring), on nodes.x.
  virtual double measure(const Part& part, const NodeArrays& nodes, std::size_t e,
                         Formulation formulation, double thickness) const = 0;
};

/// Registers an element type with its kernel (at static initialisation, one line in the type's
/// own file). Returns false if the name is taken.
bool register_element(ElementType type, std::unique_ptr<ElementKernel> kernel);
const ElementKernel& kernel_of(const ElementType& type);

}  // namespace shard
