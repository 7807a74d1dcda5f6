// ParaView frames of a particle part: the automata as points (vertex cells) and their pairs as
// lines, so that the broken-bond network is seen directly (colour the lines by bond_state).
#pragma once

#include "io/vtu_writer.hpp"
#include "model/model.hpp"

namespace shard {

/// Points: every automaton, with displacement, velocity, rotation, the averaged stress of
/// eq. (3), pressure (eq. (4)), stress intensity (eq. (5)), plastic strain, material, size.
/// Cells: one vertex per automaton, then one line per pair with bond_state (−1 for the vertex
/// cells; 0 linked, 1 breaking, 2 unlinked), k_link and the pair's specific normal and shear
/// forces (eqs. (6), (13)).
VtuGrid make_particle_frame(const ParticlePart& part, double time);

}  // namespace shard
