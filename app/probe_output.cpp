#include "app/probe_output.hpp"

#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "core/voigt.hpp"
#include "io/output_file.hpp"

namespace shard {

namespace {

std::filesystem::path probe_path(const std::filesystem::path& dir, const std::string& name) {
  return dir / ("probe_" + name + ".csv");
}

}  // namespace

ProbeOutput::ProbeOutput(const std::vector<Simulation::Probe>& probes, const Loads& loads, std::filesystem::path dir,
                         int dim)
    : probes_(probes), loads_(loads), dir_(std::move(dir)), dim_(dim) {}

void ProbeOutput::open(bool restart, const std::vector<double>& bytes) {
  files_.clear();
  const char* axes[3] = {"x", "y", "z"};
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    const auto path = probe_path(dir_, probes_[p].name);
    if (restart) {
      std::error_code ec;
      if (p < bytes.size()) std::filesystem::resize_file(path, static_cast<std::uintmax_t>(bytes[p]), ec);
      files_.emplace_back(path, std::ios::app);
      continue;
    }
    files_.emplace_back(path, std::ios::trunc);
    auto& out = files_.back();
    out << "time";
    for (const char* what : {"x_", "v_", "a_"})
      for (int k = 0; k < dim_; ++k) out << ',' << what << axes[k];
    for (const char* c : {"xx", "yy", "zz", "xy", "yz", "xz"}) out << ",stress_" << c;
    out << '\n';
  }
}

double ProbeOutput::prescribed_acceleration(const Model& model, std::size_t n, std::size_t k, int index,
                                            double t) const {
  const Prescription& p = loads_.prescriptions[static_cast<std::size_t>(index)];
  const TimeTable& table = loads_.tables[static_cast<std::size_t>(p.table)];
  if (p.rotation < 0) return table.rate(t);
  // A rigid rotation about the axis a through c at ω(t): a = ω̇ a × r + ω² a × (a × r), r = x − c.
  const Rotation& rot = loads_.rotations[static_cast<std::size_t>(p.rotation)];
  const std::size_t D = static_cast<std::size_t>(dim_);
  double r[3] = {0, 0, 0};
  for (std::size_t d = 0; d < D; ++d) r[d] = model.nodes.x[D * n + d] - rot.centre[d];
  const auto& a = rot.axis;
  const double axr[3] = {a[1] * r[2] - a[2] * r[1], a[2] * r[0] - a[0] * r[2], a[0] * r[1] - a[1] * r[0]};
  const double ax_axr[3] = {a[1] * axr[2] - a[2] * axr[1], a[2] * axr[0] - a[0] * axr[2],
                            a[0] * axr[1] - a[1] * axr[0]};
  const double w = table.at(t);
  return table.rate(t) * axr[k] + w * w * ax_axr[k];
}

std::vector<double> ProbeOutput::values(const Model& model, const Simulation::Probe& probe, double t) const {
  const std::size_t D = static_cast<std::size_t>(dim_);
  std::unordered_map<std::int64_t, std::size_t> index;  // ids are indices until nodes move
  for (std::size_t i = 0; i < model.nodes.count(); ++i) index.emplace(model.nodes.id[i], i);
  std::vector<double> v(3 * D + kTensorSize, 0.0);
  std::vector<char> wanted(model.nodes.count(), 0);
  std::size_t found = 0;
  for (auto id : probe.nodes) {
    const auto it = index.find(id);
    if (it == index.end()) continue;  // removed with an eroded piece: the others still count
    const std::size_t n = it->second;
    wanted[n] = 1;
    ++found;
    const double m = model.nodes.mass[n];
    for (std::size_t k = 0; k < D; ++k) {
      v[k] += model.nodes.x[D * n + k];
      v[D + k] += model.nodes.v[D * n + k];
      const int held = model.nodes.prescribed.empty() ? -1 : model.nodes.prescribed[D * n + k];
      if (held >= 0) v[2 * D + k] += prescribed_acceleration(model, n, k, held, t);
      else v[2 * D + k] += m > 0 ? model.nodes.force[D * n + k] / m : 0.0;
    }
  }
  // The stress: the mean over the elements around the probe's nodes of their mean over points.
  std::size_t elements = 0;
  for (const auto& part : model.parts) {
    const std::size_t npe = static_cast<std::size_t>(part.type->nodes), points = static_cast<std::size_t>(part.type->points);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!part.eroded.empty() && part.eroded[e]) continue;
      bool touches = false;
      for (std::size_t a = 0; a < npe && !touches; ++a) touches = wanted[part.connectivity[npe * e + a]] != 0;
      if (!touches) continue;
      ++elements;
      for (std::size_t q = 0; q < points; ++q)
        for (int c = 0; c < kTensorSize; ++c)
          v[3 * D + c] += part.stress[kTensorSize * (points * e + q) + c] / static_cast<double>(points);
    }
  }
  for (std::size_t k = 0; k < 3 * D; ++k) v[k] = found ? v[k] / static_cast<double>(found) : NAN;
  for (int c = 0; c < kTensorSize; ++c) v[3 * D + c] = elements ? v[3 * D + c] / static_cast<double>(elements) : NAN;
  return v;
}

bool ProbeOutput::due(std::size_t p, double t, const std::vector<double>& next) const {
  const double interval = probes_[p].interval;
  return !(interval > 0 && t < next[p] * interval * (1 - 1e-9));
}

bool ProbeOutput::any_due(double t, std::vector<double>& next) const {
  next.resize(probes_.size(), 0.0);
  for (std::size_t p = 0; p < probes_.size(); ++p)
    if (due(p, t, next)) return true;
  return false;
}

void ProbeOutput::sample(const Model& model, double t, const std::vector<double>& next) {
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    if (!due(p, t, next)) continue;
    // 17 digits: every value reads back to the same double (the frames' nodal values, exactly).
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", t);
    files_[p] << buffer;
    for (double x : values(model, probes_[p], t)) {
      std::snprintf(buffer, sizeof buffer, ",%.17g", x);
      files_[p] << buffer;
    }
    files_[p] << '\n';
  }
}

void ProbeOutput::advance(double t, std::vector<double>& next) const {
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    const double interval = probes_[p].interval;
    if (interval > 0 && due(p, t, next)) next[p] = std::floor(t / interval * (1 + 1e-9)) + 1;
  }
}

std::vector<double> ProbeOutput::sizes() {
  std::vector<double> out;
  for (std::size_t p = 0; p < files_.size(); ++p) {
    files_[p].flush();
    const auto path = probe_path(dir_, probes_[p].name);
    check_written(files_[p], path);
    out.push_back(static_cast<double>(std::filesystem::file_size(path)));
  }
  return out;
}

}  // namespace shard
