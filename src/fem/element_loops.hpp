// The loops every element kernel shares, over batches of a part's elements: kinematics, the
// material update with the stress work and erosion, bulk viscosity, the stable step and the
// scatter of nodal forces; and the averaged-nodal-pressure variant of the constant-strain
// elements. Internal to src/fem/: each element file (tri3.cpp, ...) instantiates them with its
// kernel struct, which provides
//   nodes, points, geometry (doubles per element in the workspace), has_hourglass_control,
//   kinematics(ctx, part, nodes, e, ws, slot, hourglass_scale) → false if inverted,
//   forces(part, nodes, e, ws, slot, pressure shift), band_width(ctx, ws, slot).
// Theory: docs/theory/elements_and_kinematics.md.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "fem/internal_forces.hpp"
#include "fem/nonlocal_average.hpp"
#include "core/tensor_ops.hpp"

namespace shard {

namespace {

/// Elements per material batch: large enough that the virtual call and loop set-up vanish, small
/// enough that a batch's scratch stays in the L1/L2 cache.
constexpr std::size_t kBatch = 64;

/// Per-thread scratch for one batch (thread_local: no allocation in the step loop after the
/// first steps, and no sharing between threads).
struct Workspace {
  std::vector<double> strain_increment;  // per point, kTensorSize
  std::vector<double> stress_old;        // per point, rotated σ_n
  std::vector<double> spin;              // per point, 3: W_xy, W_yz, W_zx on the mid-step geometry
  std::vector<double> point_volume;      // per point
  std::vector<double> band_width;        // per point: MaterialPointBatch::characteristic_length
  std::vector<double> geometry;          // per element, kernel-specific
  std::vector<double> volume_rate;       // per element: tr D
  std::vector<double> length;            // per element: characteristic length
  std::vector<double> volume;            // per element
  std::vector<double> hourglass_work;    // per element
  std::vector<double> hourglass_new_half;  // per element: the share of the force at t_n in it
  std::vector<double> saved_stress, saved_state, saved_temperature;  // plane-stress iteration

  void size_for(std::size_t elements, std::size_t points, std::size_t geometry_per_element) {
    auto grow = [](std::vector<double>& v, std::size_t n) {
      if (v.size() < n) v.resize(n);
    };
    grow(strain_increment, points * kTensorSize);
    grow(stress_old, points * kTensorSize);
    grow(spin, points * 3);
    grow(point_volume, points);
    grow(band_width, points);
    grow(geometry, elements * geometry_per_element);
    grow(volume_rate, elements);
    grow(length, elements);
    grow(volume, elements);
    grow(hourglass_work, elements);
    grow(hourglass_new_half, elements);
  }
};
thread_local Workspace workspace;

struct Batch {
  std::size_t begin, end;  // element range
  bool ghost = false;      // ghost elements of a subdomain: their energies are their owners'
};

/// An element that turned inside out in this step: no strain, no volume, no force, and its
/// stress σ_n kept; the caller reports it.
inline void degenerate_point(Workspace& ws, std::size_t point, const double* sig) {
  std::fill_n(&ws.strain_increment[kTensorSize * point], kTensorSize, 0.0);
  std::fill_n(&ws.spin[3 * point], 3, 0.0);
  ws.point_volume[point] = 0;
  std::copy_n(sig, kTensorSize, &ws.stress_old[kTensorSize * point]);
}
inline void degenerate_element(Workspace& ws, std::size_t i) {
  ws.volume_rate[i] = 0;
  ws.length[i] = 1;
  ws.volume[i] = 0;
  ws.hourglass_work[i] = ws.hourglass_new_half[i] = 0;  // not left from the slot's last element
}

/// The values the kernel keeps for element e between steps, cleared (an eroded element).
inline void clear_kernel_state(Part& part, std::size_t e) {
  const int n = part.type->kernel_state;
  if (n > 0) std::fill_n(&part.kernel_state[static_cast<std::size_t>(n) * e], n, 0.0);
}

/// σ_zz = 0 for plane stress: Newton iteration on Δε_zz with the elastic constrained modulus as
/// the tangent (exact in one pass for an elastic point; a few passes for inelastic ones).
void plane_stress_update(const Material& material, MaterialPointBatch& batch, Workspace& ws,
                         std::size_t state_size) {
  const ElasticModuli m = material.elastic();
  const double ratio = m.lame() / m.constrained();
  double* de = const_cast<double*>(batch.strain_increment);
  for (std::size_t p = 0; p < batch.count; ++p)
    de[kTensorSize * p + zz] = -ratio * (de[kTensorSize * p + xx] + de[kTensorSize * p + yy]) -
                               batch.stress[kTensorSize * p + zz] / m.constrained();
  ws.saved_stress.assign(batch.stress, batch.stress + kTensorSize * batch.count);
  ws.saved_state.assign(batch.state, batch.state + state_size * batch.count);
  ws.saved_temperature.assign(batch.temperature, batch.temperature + batch.count);
  for (int iteration = 0; iteration < 25; ++iteration) {
    MaterialPointBatch trial = batch;
    material.update(trial);
    double worst = 0.0, scale = 0.0;
    for (std::size_t p = 0; p < batch.count; ++p) {
      const double* s = batch.stress + kTensorSize * p;
      worst = std::max(worst, std::abs(s[zz]));
      scale = std::max({scale, std::abs(s[xx]), std::abs(s[yy]), std::abs(s[xy])});
    }
    if (worst <= 1e-12 * scale || iteration == 24) {
      batch.plastic_work += trial.plastic_work;
      batch.fracture_work += trial.fracture_work;
      return;
    }
    for (std::size_t p = 0; p < batch.count; ++p)
      de[kTensorSize * p + zz] -= batch.stress[kTensorSize * p + zz] / m.constrained();
    std::copy(ws.saved_stress.begin(), ws.saved_stress.end(), batch.stress);
    std::copy(ws.saved_state.begin(), ws.saved_state.end(), batch.state);
    std::copy(ws.saved_temperature.begin(), ws.saved_temperature.end(), batch.temperature);
  }
}

/// An eroded element: no strain, no volume, no force, no limit on the step.
template <class Kernel>
void skip_element(Part& part, std::size_t e, Workspace& ws, std::size_t i) {
  constexpr int npts = Kernel::points;
  std::fill_n(&ws.geometry[Kernel::geometry * i], Kernel::geometry, 0.0);
  for (int p = 0; p < npts; ++p) {
    const std::size_t point = npts * i + p;
    std::fill_n(&ws.strain_increment[kTensorSize * point], kTensorSize, 0.0);
    std::fill_n(&ws.spin[3 * point], 3, 0.0);
    std::copy_n(&part.stress[kTensorSize * (npts * e + p)], kTensorSize, &ws.stress_old[kTensorSize * point]);
    ws.point_volume[point] = 0.0;
  }
  ws.volume_rate[i] = 0.0;
  ws.length[i] = std::numeric_limits<double>::infinity();
  ws.volume[i] = 0.0;
  ws.hourglass_work[i] = 0.0;
  clear_kernel_state(part, e);
}

/// part.eroded value of an element eroded by its shape in this step's kinematics, whose stored
/// energy the material pass has still to book.
constexpr std::uint8_t kShapeEroded = 2;

/// The erosion rule's shape criteria: turned inside out (when the rule allows it), or a
/// characteristic length below min_length_ratio of the element's first one.
inline bool fails_by_shape(Part& part, std::size_t e, bool positive_volume, double length) {
  const ErosionRule& rule = part.erosion;
  if (!positive_volume) return rule.on_inversion;
  if (!(rule.min_length_ratio > 0)) return false;
  double& first = part.reference_length[e];
  if (first == 0) first = length;
  return length < rule.min_length_ratio * first;
}

/// An element leaving in this step's kinematics applies no force at t_n, but its stress and bulk
/// viscosity of t_n−1 acted over the increment: their half of the trapezoid is work (stress work
/// ½ σ_n−1 : Δε V, viscous −½ q_n−1 tr D V Δt), as for every element.
template <class Kernel>
void book_work_from_last_forces(const StepContext& ctx, Part& part, std::size_t e, const Workspace& ws,
                                std::size_t i, ForceSums& out) {
  for (int q = 0; q < Kernel::points; ++q) {
    const std::size_t point = Kernel::points * i + q;
    out.stress_work += 0.5 * double_contraction(&ws.stress_old[kTensorSize * point],
                                                &ws.strain_increment[kTensorSize * point]) *
                       ws.point_volume[point];
  }
  out.viscous_work += -0.5 * part.bulk_viscosity[e] * ws.volume_rate[i] * ws.volume[i] * ctx.dt;
}

/// Kinematics of the elements [begin, end) into workspace slots first_slot + (e − begin).
template <class Kernel>
void element_kinematics(const StepContext& ctx, Part& part, const NodeArrays& nodes, std::size_t begin,
                        std::size_t end, Workspace& ws, std::size_t first_slot, double hourglass_scale,
                        ForceSums& out) {
  for (std::size_t e = begin; e < end; ++e) {
    const std::size_t i = first_slot + (e - begin);
    if (part.eroded[e]) {
      skip_element<Kernel>(part, e, ws, i);
      continue;
    }
    const bool ok = Kernel::kinematics(ctx, part, nodes, e, ws, i, hourglass_scale);
    if constexpr (Kernel::has_hourglass_control) out.hourglass_work += ws.hourglass_work[i];
    if (part.erosion.by_shape() && fails_by_shape(part, e, ok, ws.length[i])) {
      // Eroded by its shape: it leaves the force computation now; update_points books the
      // energy it held (kShapeEroded marks it for that). Its hourglass force at t_n is never
      // applied: only the half of the trapezoid from t_n−1 was work.
      if constexpr (Kernel::has_hourglass_control) out.hourglass_work -= ws.hourglass_new_half[i];
      if (ok) book_work_from_last_forces<Kernel>(ctx, part, e, ws, i, out);
      part.eroded[e] = kShapeEroded;
      ++out.eroded_elements;
      skip_element<Kernel>(part, e, ws, i);
      continue;
    }
    if (!ok && out.inverted_element < 0) out.inverted_element = static_cast<std::int64_t>(e);
  }
}

/// Material update of the points of elements [begin, end) (workspace slots from first_slot), the
/// stress work ∫ σ_mid : Δε dV, the accumulated strain, and erosion of elements whose material
/// marks a point failed.
/// What the point update needs of a material beyond update(), looked up once per part and step
/// (state_names() builds strings: not something to call per batch).
struct MaterialLayout {
  std::size_t state_size;
  int failure_index;        ///< the state variable a point fails on (−1: never)
  double failure_threshold;  ///< the value at which it has failed
  /// The state variable holding the recoverable energy per unit volume Ψ (−1: none; the stress's
  /// elastic energy p²/2K + s:s/4G is taken instead).
  int energy_density_index;
  ElasticModuli moduli;
  MaterialLayout(const Material& m, const ErosionRule& rule)
      : state_size(m.state_size()),
        failure_index(rule.state_index >= 0                           ? rule.state_index
                      : rule.state_index == ErosionRule::kNoVariable ? -1
                                                                      : m.failure_state_index()),
        failure_threshold(rule.threshold),
        energy_density_index(m.stored_energy_index()),
        moduli(m.elastic()) {}

  /// The elastic energy per unit volume a point holds: Ψ where the material keeps it (for a
  /// softening material the balance counts Ψ as stored), else p²/2K + s:s/4G of its stress.
  double stored_energy_density(const double* s, const double* point_state) const {
    return energy_density_index >= 0 ? point_state[energy_density_index] : moduli.energy_density(s);
  }
};

template <class Kernel>
void update_points(const StepContext& ctx, Part& part, const Material& material,
                   const MaterialLayout& layout, std::size_t begin, std::size_t end, Workspace& ws,
                   std::size_t first_slot, ForceSums& out) {
  constexpr int npts = Kernel::points;
  const std::size_t state_size = layout.state_size;
  const std::size_t p0 = begin * npts, s0 = first_slot * npts;
  for (std::size_t i = first_slot; i < first_slot + (end - begin); ++i)
    std::fill_n(&ws.band_width[npts * i], npts, Kernel::band_width(ctx, ws, i));
  MaterialPointBatch mp;
  mp.count = (end - begin) * npts;
  mp.dt = ctx.dt;
  mp.strain_increment = ws.strain_increment.data() + kTensorSize * s0;
  mp.spin = ws.spin.data() + 3 * s0;
  mp.stress = part.stress.data() + kTensorSize * p0;
  mp.state = part.state.data() + state_size * p0;
  mp.temperature = part.temperature.data() + p0;
  mp.volume = ws.point_volume.data() + s0;
  mp.characteristic_length = ws.band_width.data() + s0;
  if (ctx.formulation == Formulation::plane_stress)
    plane_stress_update(material, mp, workspace, state_size);  // this thread's scratch
  else
    material.update(mp);
  out.plastic_work += mp.plastic_work;
  out.fracture_work += mp.fracture_work;
  out.heat += mp.heat;

  // The stress work of an element's points is summed first (in point order, the same in any
  // batch), then added to the exact sum once per element.
  for (std::size_t first = 0; first < mp.count; first += npts) {
    double element_work = 0;
    for (std::size_t p = first; p < first + npts; ++p) {
      const double* de = &mp.strain_increment[kTensorSize * p];
      const double* old = &ws.stress_old[kTensorSize * (s0 + p)];
      double s_mid[kTensorSize];
      for (int k = 0; k < kTensorSize; ++k) s_mid[k] = 0.5 * (old[k] + mp.stress[kTensorSize * p + k]);
      element_work += double_contraction(s_mid, de) * mp.volume[p];
      double* eps = &part.strain[kTensorSize * (p0 + p)];
      for (int k = 0; k < kTensorSize; ++k) eps[k] += de[k];
    }
    out.stress_work += element_work;
  }

  // Eroded elements stay stress-free (a total-form equation of state would otherwise restore a
  // pressure from their frozen volumetric strain). One eroded by its shape in this step's
  // kinematics leaves with the energy it held at the start of the step, on its last volume.
  for (std::size_t e = begin; e < end; ++e) {
    if (!part.eroded[e]) continue;
    if (part.eroded[e] == kShapeEroded) {
      for (int q = 0; q < npts; ++q) {
        const std::size_t slot = npts * (first_slot + e - begin) + q;
        out.eroded_energy += layout.stored_energy_density(&ws.stress_old[kTensorSize * slot],
                                                          part.state.data() + state_size * (npts * e + q)) *
                             part.volume[e] / npts;
      }
      part.eroded[e] = 1;
    }
    std::fill_n(&part.stress[kTensorSize * npts * e], kTensorSize * npts, 0.0);
  }

  const int failure = layout.failure_index;
  if (failure < 0) return;
  const int required = part.erosion.points_required(npts);
  for (std::size_t e = begin; e < end; ++e) {
    if (part.eroded[e]) continue;
    int failed = 0;
    for (int q = 0; q < npts; ++q)
      failed += part.state[state_size * (npts * e + q) + static_cast<std::size_t>(failure)] >= layout.failure_threshold;
    if (failed < required) continue;
    // Erosion: the element leaves the force computation; the elastic energy it stored,
    // p²/2K + s:s/4G per unit volume, leaves the body with it and is booked as eroded.
    part.eroded[e] = 1;
    ++out.eroded_elements;
    // Its forces at t_n are never applied (element_forces skips it): the hourglass force's half
    // of the trapezoid is not work.
    if constexpr (Kernel::has_hourglass_control) out.hourglass_work -= ws.hourglass_new_half[first_slot + e - begin];
    for (int q = 0; q < npts; ++q) {
      double* s = &part.stress[kTensorSize * (npts * e + q)];
      out.eroded_energy += layout.stored_energy_density(s, part.state.data() + state_size * (npts * e + q)) *
                           ws.point_volume[npts * (first_slot + e - begin) + q];
      std::fill_n(s, kTensorSize, 0.0);
    }
    clear_kernel_state(part, e);
  }
}

/// Bulk viscosity, stable step and nodal forces of elements [begin, end); `pressure_shift`
/// (may be null) adds a per-slot pressure to the element's stress in the force (used by the
/// averaged nodal pressure).
template <class Kernel>
void element_forces(const StepContext& ctx, Part& part, NodeArrays& nodes, double rho, double c,
                    std::size_t begin, std::size_t end, const Workspace& ws, std::size_t first_slot,
                    const double* pressure_shift, ForceSums& out) {
  double stable = out.stable_dt;
  for (std::size_t e = begin; e < end; ++e) {
    const std::size_t i = first_slot + (e - begin);
    const double rate = ws.volume_rate[i];
    const double l = ws.length[i];
    // Bulk viscosity (von Neumann–Richtmyer quadratic + Landshoff linear), in compression only.
    // With a viscous length ℓ_v the linear term is ρ c ℓ_v |ε̇_v| (C_l = ℓ_v / l): a front spread
    // over the same length on every mesh (docs/theory/time_integration_and_energy.md).
    const double linear = ctx.q_length > 0.0 ? ctx.q_length / l : ctx.q_linear;
    double q = 0.0, qs = 0.0;
    if (rate < 0.0) {
      q = rho * l * (ctx.q_quadratic * l * rate * rate - linear * c * rate);
      qs = linear * c - ctx.q_quadratic * l * rate;
    }
    // Work of the viscous forces over [t_n−1, t_n], where the velocities were v_n−1/2: the
    // trapezoid of the forces at both ends (the same split as every nodal force).
    double& q_prev = part.bulk_viscosity[e];
    if (part.eroded[e]) q = 0.0;  // an eroded element applies no force at t_n
    out.viscous_work += -0.5 * (q_prev + q) * rate * ws.volume[i] * ctx.dt;
    part.volume[e] = ws.volume[i];
    if (part.eroded[e]) {
      q_prev = 0.0;
      continue;
    }
    q_prev = q;
    // Stable step with bulk viscosity (Q + sqrt(Q² + c²) replaces c).
    stable = std::min(stable, l / (qs + std::sqrt(qs * qs + c * c)));
    Kernel::forces(part, nodes, e, ws, i, q + (pressure_shift ? pressure_shift[i] : 0.0));
  }
  out.stable_dt = stable;
}

/// Batches of at most kBatch elements within each colour, the owned elements of a subdomain
/// apart from its ghosts (Part::ghost_begin); first batch of each colour.
void make_batches(const Part& part, std::vector<Batch>& batches, std::vector<std::size_t>& colour_first_batch) {
  batches.clear();
  colour_first_batch.clear();
  auto add_range = [&](std::size_t begin, std::size_t end, bool ghost) {
    for (std::size_t b = begin; b < end; b += kBatch) batches.push_back({b, std::min(b + kBatch, end), ghost});
  };
  for (std::size_t col = 0; col < part.colour_count(); ++col) {
    colour_first_batch.push_back(batches.size());
    const auto begin = static_cast<std::size_t>(part.colour_begin[col]);
    const auto end = static_cast<std::size_t>(part.colour_begin[col + 1]);
    const std::size_t ghosts = part.ghost_begin.empty() ? end : static_cast<std::size_t>(part.ghost_begin[col]);
    add_range(begin, ghosts, false);
    add_range(ghosts, end, true);
  }
  colour_first_batch.push_back(batches.size());
}

/// The sums of a part's batches: per thread, one for the batches it owns and one for its ghost
/// batches. The energies are exact sums, so which thread took which batch changes no bit.
class BatchSums {
 public:
  BatchSums() {
#ifdef _OPENMP
    sums_.resize(2 * static_cast<std::size_t>(omp_get_max_threads()));
#else
    sums_.resize(2);
#endif
  }
  ForceSums& of(const Batch& b) {
#ifdef _OPENMP
    return sums_[2 * static_cast<std::size_t>(omp_get_thread_num()) + b.ghost];
#else
    return sums_[b.ghost];
#endif
  }
  /// The part's sums: the smallest stable step and first inverted element of every batch, the
  /// energies and erosion counts of the owned ones.
  ForceSums total() const {
    ForceSums total;
    for (std::size_t i = 0; i < sums_.size(); ++i) {
      if (i % 2 == 0) {
        total.add(sums_[i]);
        continue;
      }
      ForceSums limits;
      limits.stable_dt = sums_[i].stable_dt;
      limits.inverted_element = sums_[i].inverted_element;
      total.add(limits);
    }
    return total;
  }

 private:
  std::vector<ForceSums> sums_;
};

template <class Kernel>
ForceSums run_part(Part& part, const Material& material, NodeArrays& nodes,
                   const StepContext& ctx) {
  constexpr int npts = Kernel::points;
  const MaterialLayout layout(material, part.erosion);
  const double rho = material.density();
  const double c = material.wave_speed();
  const double hourglass_scale = 0.25 * part.hourglass_coefficient * rho * c;

  std::vector<Batch> batches;
  std::vector<std::size_t> colour_first_batch;
  make_batches(part, batches, colour_first_batch);
  BatchSums sums;

  // One pass per colour: kinematics, material and forces of a batch together, while its
  // scratch is in cache. Elements of one colour share no node, so batches scatter in parallel.
  for (std::size_t col = 0; col + 1 < colour_first_batch.size(); ++col) {
    const auto first = static_cast<std::ptrdiff_t>(colour_first_batch[col]);
    const auto last = static_cast<std::ptrdiff_t>(colour_first_batch[col + 1]);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t bi = first; bi < last; ++bi) {
      const Batch batch = batches[bi];
      ForceSums& out = sums.of(batch);
      Workspace& ws = workspace;
      const std::size_t n = batch.end - batch.begin;
      ws.size_for(n, n * npts, Kernel::geometry);
      element_kinematics<Kernel>(ctx, part, nodes, batch.begin, batch.end, ws, 0, hourglass_scale, out);
      update_points<Kernel>(ctx, part, material, layout, batch.begin, batch.end, ws, 0, out);
      element_forces<Kernel>(ctx, part, nodes, rho, c, batch.begin, batch.end, ws, 0, nullptr, out);
    }
  }
  return sums.total();
}

/// Scratch of the averaged-nodal-pressure pass, for a whole part (the passes need every
/// element's kinematics before any element's force). Used by one part at a time.
struct NodalAveragingScratch {
  Workspace elements;
  std::vector<double> node_rate, node_volume, node_pressure, pressure_shift;
};
thread_local NodalAveragingScratch nodal_scratch;  // one per thread: ranks run as threads in tests

/// tri3 and tet4 with averaged nodal pressure (after Bonet & Burton 1998). With V_a = Σ_e V_e/n
/// and V̇_a = Σ_e V_e tr D_e / n the nodal volume and its rate, each element takes the dilatation
///   d̄_e = (1/n) Σ_a∈e V̇_a / V_a
/// in place of its own tr D_e, and in the force the pressure
///   p̄_e = (1/n) Σ_a∈e p̃_a,   p̃_a = Σ_e∋a V_e p_e / (n V_a),
/// in place of its own p_e. The two averages are adjoint: Σ_e V_e p̄_e tr D_e = Σ_e V_e p_e d̄_e,
/// so the forces do exactly the work the material's stress does on the averaged strain (the
/// energy balance closes as for the standard element). One constraint per node instead of one per
/// element removes the volumetric locking of constant-strain elements in plastic flow.

template <class Kernel>
ForceSums run_part_nodal_pressure(Part& part, const Material& material, NodeArrays& nodes,
                                  const StepContext& ctx) {
  constexpr int npe = Kernel::nodes;
  const MaterialLayout layout(material, part.erosion);
  const double rho = material.density();
  const double c = material.wave_speed();
  const std::size_t ne = part.element_count(), nn = nodes.count();
  NodalAveragingScratch& sc = nodal_scratch;
  Workspace& ws = sc.elements;
  ws.size_for(ne, ne, Kernel::geometry);
  sc.node_rate.assign(nn, 0.0);
  sc.node_volume.assign(nn, 0.0);
  sc.node_pressure.assign(nn, 0.0);
  sc.pressure_shift.assign(ne, 0.0);

  std::vector<Batch> batches;
  std::vector<std::size_t> colour_first_batch;
  make_batches(part, batches, colour_first_batch);
  BatchSums sums;
  const auto nb = static_cast<std::ptrdiff_t>(batches.size());

  // Per colour, batches in parallel: no two elements of a colour share a node, so the nodal sums
  // are formed in colour order whatever the thread count.
  auto per_colour = [&](auto&& body) {
    for (std::size_t col = 0; col + 1 < colour_first_batch.size(); ++col) {
      const auto first = static_cast<std::ptrdiff_t>(colour_first_batch[col]);
      const auto last = static_cast<std::ptrdiff_t>(colour_first_batch[col + 1]);
#pragma omp parallel for schedule(static)
      for (std::ptrdiff_t bi = first; bi < last; ++bi) body(batches[bi], sums.of(batches[bi]));
    }
  };

  // 1. Kinematics of every element; nodal volume and volume rate.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t bi = 0; bi < nb; ++bi)
    element_kinematics<Kernel>(ctx, part, nodes, batches[bi].begin, batches[bi].end, ws,
                               batches[bi].begin, 0.0, sums.of(batches[bi]));
  per_colour([&](const Batch& b, ForceSums&) {
    for (std::size_t e = b.begin; e < b.end; ++e) {
      const double v = ws.volume[e] / npe, r = ws.volume[e] * ws.volume_rate[e] / npe;
      for (int a = 0; a < npe; ++a) {
        const std::int32_t n = part.connectivity[npe * e + a];
        sc.node_volume[n] += v;
        sc.node_rate[n] += r;
      }
    }
  });

  // Mean over an element's nodes of a nodal sum per nodal volume (V̇_a/V_a, p̃_a).
  auto element_mean = [&](std::size_t e, const std::vector<double>& nodal_sum) {
    double mean = 0.0;
    for (int a = 0; a < npe; ++a) {
      const std::int32_t n = part.connectivity[npe * e + a];
      mean += nodal_sum[n] / sc.node_volume[n];
    }
    return mean / npe;
  };

  // 2. Averaged dilatation, material update; element pressures to the nodes.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t bi = 0; bi < nb; ++bi) {
    const Batch b = batches[bi];
    for (std::size_t e = b.begin; e < b.end; ++e) {
      if (!(ws.volume[e] > 0.0)) continue;
      const double mean = element_mean(e, sc.node_rate);
      double* de = &ws.strain_increment[kTensorSize * e];
      const double shift = (1.0 - kNodalPressureElementShare) * (mean - ws.volume_rate[e]) * ctx.dt / 3.0;
      de[xx] += shift;
      de[yy] += shift;
      de[zz] += shift;
    }
    update_points<Kernel>(ctx, part, material, layout, b.begin, b.end, ws, b.begin, sums.of(b));
  }
  per_colour([&](const Batch& b, ForceSums&) {
    for (std::size_t e = b.begin; e < b.end; ++e) {
      const double* s = &part.stress[kTensorSize * e];
      const double weighted = -ws.volume[e] * (s[xx] + s[yy] + s[zz]) / (3.0 * npe);
      for (int a = 0; a < npe; ++a) sc.node_pressure[part.connectivity[npe * e + a]] += weighted;
    }
  });

  // 3. Forces with the averaged pressure: σ + (p_e − p̄_e) I, i.e. a pressure shift p̄_e − p_e.
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t bi = 0; bi < nb; ++bi) {
    const Batch b = batches[bi];
    for (std::size_t e = b.begin; e < b.end; ++e) {
      if (!(ws.volume[e] > 0.0)) continue;
      const double mean = element_mean(e, sc.node_pressure);
      const double* s = &part.stress[kTensorSize * e];
      sc.pressure_shift[e] = (1.0 - kNodalPressureElementShare) * (mean + (s[xx] + s[yy] + s[zz]) / 3.0);
    }
  }
  per_colour([&](const Batch& b, ForceSums& out) {
    element_forces<Kernel>(ctx, part, nodes, rho, c, b.begin, b.end, ws, b.begin,
                           sc.pressure_shift.data(), out);
  });

  return sums.total();
}

}  // namespace

}  // namespace shard
