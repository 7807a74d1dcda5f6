// Element types: what the model, assembly, contact, fragments and output know of an element
// formulation (its name, nodes, integration points, faces, the mesh cell it is built on). The
// physics of each type (internal forces, lumped masses, measure) is its kernel in src/fem/; one
// file there per element type registers both (src/fem/element.hpp, register_element).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "model/mesh_data.hpp"

namespace shard {

/// How an element treats the volumetric part of the deformation. Nearly incompressible flow
/// (metal plasticity) locks constant-strain triangles and tetrahedra and fully integrated
/// hexahedra; the remedies replace each element's dilatation and pressure by averages
/// (docs/theory/elements_and_kinematics.md, "Volumetric locking").
enum class VolumetricTreatment : std::uint8_t {
  standard,                ///< the element's own dilatation at each point
  average_nodal_pressure,  ///< tri3/tet4: dilatation and pressure averaged through the nodes
  mean_dilatation,         ///< hex8: B-bar, the element's mean dilatation at all 8 points
};

struct ElementType {
  std::string name;      ///< as the scenario names it ("tri3")
  std::string summary;   ///< one line for `shard info` and the docs
  int dim = 2;           ///< 2 (plane strain, plane stress, axisymmetric) or 3
  int nodes = 3;         ///< nodes per element
  int points = 1;        ///< integration points per element
  CellType cell = CellType::tri3;  ///< the mesh cell it is built on
  bool default_for_cell = true;    ///< the type a part gets when it names none, for that cell
  int vtk_cell = 5;      ///< VTK cell type of the frames (5 triangle, 10 tetra, 12 hexahedron)
  /// Local nodes of each face (2D: edge), ordered so that the right-hand normal points out of an
  /// element of positive measure.
  std::vector<std::vector<int>> faces;
  /// Values per element the kernel keeps from one step to the next (checkpointed with the part;
  /// hex8_reduced: its 12 hourglass force coefficients).
  int kernel_state = 0;
  /// The volumetric treatments the type offers besides `standard`.
  std::vector<VolumetricTreatment> volumetric;

  bool offers(VolumetricTreatment t) const;
  /// A 3-node triangle: the element discrete cracks are inserted between.
  bool is_triangle() const { return dim == 2 && nodes == 3; }
};

/// Adds a type to the registry (at static initialisation, from the file of its kernel). Returns
/// false if the name is taken.
bool register_element_type(ElementType type);
/// The registered type of that name; throws std::invalid_argument naming the types there are.
const ElementType& element_type(std::string_view name);
const ElementType* find_element_type(std::string_view name);
/// Every registered name, 2D before 3D, then by nodes, then by name.
std::vector<std::string> element_type_names();
/// The type a part built on cells of `cell` gets when it names none (nullptr: no type is built
/// on such cells).
const ElementType* default_element_type(CellType cell);

const char* name_of(VolumetricTreatment treatment);

}  // namespace shard
