// Laminates: the stacking sequence of a laminate in the usual code ("[(0/45/90/-45/0)2]s",
// "[0/±45/90]s", "[0_2/90]") and the material axes of a ply of a given angle. Theory note:
// docs/theory/composite_damage.md ("Plies and laminates").
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace shard {

/// A stacking sequence that does not read; what() says where and why.
class LayupError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The ply angles (degrees) of a stacking sequence, first ply first. The code: plies separated
/// by '/'; a group in parentheses or brackets; a repeat count as "_n" after a ply or group, or
/// as a plain number right after a closing bracket; "±θ" (or "+-θ") for θ/−θ; a final "s" for
/// the sequence followed by its mirror (optionally repeated: "[0/90]s2"). Examples:
/// "[(0/45/90/-45/0)2]s" is 20 plies, "[0/±45/90]s" 8, "[0_2/90_2]" 4.
std::vector<double> parse_layup(const std::string& code);

/// Material axes a1 (fibre) and a2 of a ply at `angle_degrees` about the unit ply normal n,
/// measured from the reference (0°) direction r (projected into the ply's plane): a1 = cos θ r̂ +
/// sin θ (n × r̂), a2 = n × a1. Throws std::invalid_argument if r is parallel to n.
std::array<double, 6> ply_axes(const std::array<double, 3>& reference, const std::array<double, 3>& normal,
                               double angle_degrees);

}  // namespace shard
