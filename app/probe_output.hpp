// Point histories (`probes`): each probe's position, velocity, acceleration and stress at its own
// interval, in OUTDIR/probe_<name>.csv.
#pragma once

#include <filesystem>
#include <fstream>
#include <vector>

#include "app/simulation.hpp"

namespace shard {

class ProbeOutput {
 public:
  ProbeOutput(const std::vector<Simulation::Probe>& probes, const Loads& loads, std::filesystem::path dir, int dim);

  /// Opens the files: new with their header, or (restart) cut back to `bytes` and appended to.
  void open(bool restart, const std::vector<double>& bytes);
  /// Whether any probe is due at t (`next`: each probe's index of its next row, sized here).
  bool any_due(double t, std::vector<double>& next) const;
  /// Writes a row for every probe due at t, from the state the frames show: positions,
  /// velocities of the last half step, accelerations at t (force/mass, or for a component whose
  /// velocity is prescribed the rate of its prescription: 0 where fixed), and the mean stress of
  /// the elements around each node. A decomposed run samples its whole model, on the rank that writes.
  void sample(const Model& model, double t, const std::vector<double>& next);
  /// Moves each probe due at t on to its next row (on every rank of a decomposed run: they must
  /// agree when to gather).
  void advance(double t, std::vector<double>& next) const;
  /// Flushes the files and returns their sizes (for a checkpoint); throws OutputError when one
  /// could not be written.
  std::vector<double> sizes();

 private:
  std::vector<double> values(const Model& model, const Simulation::Probe& probe, double t) const;
  /// The acceleration of component k of node n, whose velocity follows prescription `index`.
  double prescribed_acceleration(const Model& model, std::size_t n, std::size_t k, int index, double t) const;
  bool due(std::size_t p, double t, const std::vector<double>& next) const;

  const std::vector<Simulation::Probe>& probes_;
  const Loads& loads_;
  std::filesystem::path dir_;
  int dim_;
  std::vector<std::ofstream> files_;
};

}  // namespace shard
