#include "contact/particle_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>


namespace shard {

namespace {

inline void cross(const double* a, const double* b, double* out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// The relative velocity of body 2's contact point to body 1's (arms from the centres), split
/// into its normal and tangential parts.
[[gnu::always_inline]] inline void relative_motion(const double* va, const double* wa, const double* arm_a, const double* vb, const double* wb,
                     const double* arm_b, ContactKinematics& c, double* rel) {
  double spin_a[3], spin_b[3];
  cross(wa, arm_a, spin_a);
  cross(wb, arm_b, spin_b);
  for (int k = 0; k < 3; ++k) rel[k] = vb[k] + spin_b[k] - va[k] - spin_a[k];
  c.normal_velocity = dot3(rel, c.normal);
  for (int k = 0; k < 3; ++k) c.tangential_velocity[k] = rel[k] - c.normal_velocity * c.normal[k];
}

/// Barycentric weights of the point of triangle (a, b, c) closest to p (Ericson 2005, §5.1.5).
void closest_on_triangle(const double* a, const double* b, const double* c, const double* p, double* w) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  auto set = [w](double u, double v, double t) { w[0] = u, w[1] = v, w[2] = t; };
  if (d1 <= 0 && d2 <= 0) return set(1, 0, 0);
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return set(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return set(1 - t, t, 0);
  }
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return set(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return set(1 - t, 0, t);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return set(0, 1 - t, t);
  }
  const double denom = 1 / (va + vb + vc), v = vb * denom, u = vc * denom;
  set(1 - v - u, v, u);
}

/// A ring (axisymmetric) touches as a row of spheres of its cross-section along its
/// circumference: L / 2ρ of them; 0 for a particle that is not a ring.
double ring_scale(const ParticlePart& part, std::size_t i) {
  return part.ring_length[i] > 0 ? part.ring_length[i] / (2 * part.radius[i]) : 0.0;
}

/// The axis of an axisymmetric model as a plane: r = 0, facing the material.
constexpr double kAxisNormal[3] = {1, 0, 0};

/// Values the contact keeps after the law's own history: the force on b, the stored energy, and
/// the overlap it was born with (carried without force, given up as the bodies part).
constexpr int kHistoryTail = 5;

}  // namespace

std::vector<EnergyTerm> ParticleContact::energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"particle_contact_elastic", "elastic energy in the contacts of particles now (a state)",
           r::particle_contact, {{G::contact, +1}}, "-"},
          {"particle_contact_dissipation", "dissipated by damping and sliding in particle contacts",
           r::particle_contact + 1, {{G::dissipated, +1}}, ""},
          {"particle_wall_work", "work of moving rigid walls on particles (part of external_work)",
           r::particle_contact + 2, {{G::external, +1}}, "external_work"}};
}

ParticleContact::ParticleContact(ParticleContactSettings settings) : settings_(std::move(settings)) {
  if (!settings_.law) throw std::invalid_argument("particle contact needs a pair law");
  if (settings_.params.size() != settings_.law->parameters.size())
    throw std::invalid_argument("particle contact: the law's parameters are not complete");
  if (settings_.wall_params.empty()) settings_.wall_params = settings_.params;
  // The axis is a plane of symmetry: a ring's other side moves as its mirror image, so nothing
  // slides there.
  axis_params_ = settings_.wall_params;
  for (std::size_t i = 0; i < settings_.law->parameters.size(); ++i)
    if (settings_.law->parameters[i].name == "friction") axis_params_[i] = 0;
}

void ParticleContact::gather(Model& model) {
  const std::size_t n = part_of_.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const ParticlePart& p = model.particle_parts[part_of_[i]];
    const std::size_t j = index_in_part_[i];
    const int D = p.dim, R = p.rot_dim();
    for (int k = 0; k < 3; ++k) {
      x_[3 * i + k] = k < D ? p.x[D * j + k] : 0.0;
      v_[3 * i + k] = k < D ? p.v[D * j + k] : 0.0;
      w_[3 * i + k] = R == 3 ? p.omega[3 * j + k] : (k == 2 ? p.omega[j] : 0.0);
    }
  }
}

bool ParticleContact::list_is_stale(const Model& model) const {
  if (stale_ || x_at_build_.size() != x_.size()) return true;
  if (part_of_.empty()) return false;  // particles come only with a topology change
  return moved_half_the_skin(model);
}

bool ParticleContact::moved_half_the_skin(const Model& model) const {
  if (stale_ || x_at_build_.size() != x_.size()) return true;
  double moved2 = 0;
  for (std::size_t k = 0; k < x_.size(); k += 3) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (x_[k + a] - x_at_build_[k + a]) * (x_[k + a] - x_at_build_[k + a]);
    moved2 = std::max(moved2, d2);
  }
  double wall_moved2 = 0;
  const int dim = model.dim();
  for (std::size_t w = 0; w < settings_.walls.size(); ++w) {
    double d2 = 0;
    for (int a = 0; a < dim; ++a) {
      const double d = model.contact.wall_offset[dim * w + a] - wall_offset_at_build_[dim * w + a];
      d2 += d * d;
    }
    wall_moved2 = std::max(wall_moved2, d2);
  }
  // Two particles close by at most twice the largest move, a particle and a wall by the sum of
  // theirs: either within the skin keeps every contact in the list.
  const double moved = std::sqrt(moved2);
  return 2 * moved > skin_ || moved + std::sqrt(wall_moved2) > skin_ || facets_moved(model);
}

bool ParticleContact::facets_moved(const Model& model) const {
  // A particle and a facet close by at most the particle's move plus the facet's: half the skin
  // each (the particles' half is checked by the caller).
  const int dim = model.dim();
  double moved2 = 0;
  const std::size_t n = surface_.nodes.size();
  if (facet_x_at_build_.size() != n * dim) return false;
  for (std::size_t s = 0; s < n; ++s) {
    double d2 = 0;
    for (int a = 0; a < dim; ++a) {
      const double d = model.nodes.x[dim * surface_.nodes[s] + a] - facet_x_at_build_[dim * s + a];
      d2 += d * d;
    }
    moved2 = std::max(moved2, d2);
  }
  return 2 * std::sqrt(moved2) > skin_;
}

void ParticleContact::closest_on_facet(const Model& model, std::size_t f, const double* x, double* q,
                                       double* weights) const {
  const int dim = model.dim();
  const std::int32_t* nodes = &surface_.facets[dim * f];
  double p[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int i = 0; i < dim; ++i)
    for (int a = 0; a < dim; ++a) p[i][a] = model.nodes.x[dim * nodes[i] + a];
  if (dim == 2) {
    const double e[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], 0};
    const double len2 = e[0] * e[0] + e[1] * e[1];
    double t = len2 > 0 ? ((x[0] - p[0][0]) * e[0] + (x[1] - p[0][1]) * e[1]) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    weights[0] = 1 - t, weights[1] = t, weights[2] = 0;
  } else {
    closest_on_triangle(p[0], p[1], p[2], x, weights);
  }
  for (int a = 0; a < 3; ++a) q[a] = weights[0] * p[0][a] + weights[1] * p[1][a] + weights[2] * p[2][a];
}

void ParticleContact::facet_candidates(const Model& model, const std::vector<std::int64_t>& ids, double r_max,
                                       std::vector<InteractionKey>& out) {
  if (!settings_.mesh || model.parts.empty()) return;
  if (surface_stale_) {
    surface_ = extract_contact_surface(model);
    surface_stale_ = false;
  }
  const int dim = model.dim();
  const std::size_t nf = surface_.facet_count(), n = ids.size();
  facet_x_at_build_.resize(surface_.nodes.size() * dim);
  for (std::size_t s = 0; s < surface_.nodes.size(); ++s)
    for (int a = 0; a < dim; ++a) facet_x_at_build_[dim * s + a] = model.nodes.x[dim * surface_.nodes[s] + a];
  if (nf == 0 || n == 0) return;
  // Facet boxes grown by the reach of the largest particle, in cells of that size at least.
  const double reach = r_max + skin_;
  std::vector<double> boxes(6 * nf, 0.0);
  double largest = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    double* lo = &boxes[6 * f];
    double* hi = lo + 3;
    for (int a = 0; a < dim; ++a) lo[a] = std::numeric_limits<double>::infinity(), hi[a] = -lo[a];
    for (int i = 0; i < dim; ++i)
      for (int a = 0; a < dim; ++a) {
        const double c = model.nodes.x[dim * surface_.facets[dim * f + i] + a];
        lo[a] = std::min(lo[a], c - reach), hi[a] = std::max(hi[a], c + reach);
      }
    for (int a = 0; a < dim; ++a) largest = std::max(largest, hi[a] - lo[a]);
  }
  facet_grid_.build_boxes(boxes, dim, std::max(largest, 2 * reach));
  for (std::size_t i = 0; i < n; ++i)
    facet_grid_.for_cell(&x_[3 * i], [&](std::int32_t f) {
      double q[3], w[3];
      closest_on_facet(model, static_cast<std::size_t>(f), &x_[3 * i], q, w);
      double d2 = 0;
      for (int a = 0; a < dim; ++a) d2 += (x_[3 * i + a] - q[a]) * (x_[3 * i + a] - q[a]);
      const double r = radius_[i] + skin_;
      if (d2 < r * r) out.push_back({InteractionKind::particle_facet, ids[i], surface_.facet_id[f]});
    });
}

bool ParticleContact::walls_only(std::int32_t part) const {
  const auto p = static_cast<std::size_t>(part);
  return p < settings_.walls_only.size() && settings_.walls_only[p];
}

double ParticleContact::skin(const Model& model) const { return fixed_skin_ > 0 ? fixed_skin_ : own_skin(model); }

double ParticleContact::own_skin(const Model& model) const {
  if (settings_.skin > 0) return settings_.skin;
  double r_min = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p)
    if (takes_part(p))
      for (const double r : model.particle_parts[p].radius) r_min = std::min(r_min, r);
  return std::isfinite(r_min) ? 0.1 * r_min : 0.0;
}

double ParticleContact::largest_radius(const Model& model) const {
  double r_max = 0;
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p)
    if (takes_part(p))
      for (const double r : model.particle_parts[p].radius) r_max = std::max(r_max, r);
  return r_max;
}

double ParticleContact::reach(const Model& model) const { return 2 * largest_radius(model) + skin(model); }

bool ParticleContact::list_due(Model& model) {
  if (stale_ && resumable_) resume_list(model);
  if (stale_) return false;
  gather(model);
  // A rank that holds no particle still holds facets that may have moved: the rule of one
  // process, whose model has particles, once the ranks agree (and whether any has particles).
  return moved_half_the_skin(model);
}

double ParticleContact::index_particles(const Model& model, std::vector<std::int64_t>& ids) {
  part_of_.clear();
  index_in_part_.clear();
  std::int64_t id_end = model.next_particle_id;
  for (const ParticlePart& part : model.particle_parts)
    for (const std::int64_t id : part.id) id_end = std::max(id_end, id + 1);
  flat_of_id_.assign(static_cast<std::size_t>(id_end), -1);
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p) {
    if (!takes_part(p)) continue;
    const ParticlePart& part = model.particle_parts[p];
    for (std::size_t j = 0; j < part.count(); ++j) {
      flat_of_id_.at(static_cast<std::size_t>(part.id[j])) = static_cast<std::int32_t>(part_of_.size());
      part_of_.push_back(static_cast<std::int32_t>(p));
      index_in_part_.push_back(static_cast<std::int32_t>(j));
    }
  }
  const std::size_t n = part_of_.size();
  x_.resize(3 * n);
  v_.resize(3 * n);
  w_.resize(3 * n);
  radius_.resize(n);
  mass_.resize(n);
  ring_scale_.resize(n);
  newborn_.resize(n);
  owned_.resize(n);
  ids.resize(n);
  double r_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const ParticlePart& part = model.particle_parts[part_of_[i]];
    radius_[i] = part.radius[index_in_part_[i]];
    mass_[i] = part.mass[index_in_part_[i]];
    ring_scale_[i] = ring_scale(part, index_in_part_[i]);
    newborn_[i] = part.newborn[index_in_part_[i]];
    owned_[i] = part.owns(static_cast<std::size_t>(index_in_part_[i]));
    ids[i] = part.id[index_in_part_[i]];
    r_max = std::max(r_max, radius_[i]);
  }
  return r_max;
}

void ParticleContact::rebuild_list(Model& model) {
  std::vector<std::int64_t> ids;
  const double r_max = index_particles(model, ids);
  const std::size_t n = part_of_.size();
  gather(model);
  skin_ = skin(model);

  std::vector<InteractionKey> candidates;
  if (n > 0) {
    grid_.build_points(x_, 3, 2 * r_max + skin_);
    for (std::size_t i = 0; i < n; ++i)
      grid_.for_near(&x_[3 * i], [&](std::int32_t j) {
        if (ids[j] <= ids[i]) return;
        if (part_of_[i] == part_of_[j] && walls_only(part_of_[i])) return;
        double d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += (x_[3 * j + a] - x_[3 * i + a]) * (x_[3 * j + a] - x_[3 * i + a]);
        const double reach = radius_[i] + radius_[j] + skin_;
        if (d2 < reach * reach) candidates.push_back({InteractionKind::particle_particle, ids[i], ids[j]});
      });
  }
  const int dim = model.dim();
  if (model.contact.wall_offset.size() != settings_.walls.size() * dim)
    model.contact.wall_offset.assign(settings_.walls.size() * dim, 0.0);
  const std::vector<double> origin = wall_origins(model), normal = wall_normals();
  for (std::size_t w = 0; w < wall_count(); ++w)
    for (std::size_t i = 0; i < n; ++i) {
      double d = 0;
      for (int a = 0; a < dim; ++a) d += (x_[3 * i + a] - origin[3 * w + a]) * normal[3 * w + a];
      if (d - radius_[i] < skin_)
        candidates.push_back({InteractionKind::particle_wall, ids[i], static_cast<std::int64_t>(w)});
    }
  facet_candidates(model, ids, r_max, candidates);
  // A contact still carrying force whose partner is gone (a facet of an element that eroded or
  // converted, a particle removed) leaves with its stored energy: booked as dissipated. (Not
  // across ranks: no particle and no facet leaves a decomposed run's model.)
  InteractionList& list = model.particle_contacts;
  const std::size_t tail = settings_.law->history_size;
  std::vector<std::pair<InteractionKey, double>> loaded;
  for (std::size_t k = 0; k < list.size(); ++k) {
    // Booked by the owner of its first particle (by every process if that particle is gone).
    const auto id = static_cast<std::size_t>(list.key(k).first);
    const std::int32_t first = id < flat_of_id_.size() ? flat_of_id_[id] : -1;
    if (list.history(k)[tail + 3] != 0 && (first < 0 || owned_[first]))
      loaded.emplace_back(list.key(k), list.history(k)[tail + 3]);
  }
  list.update(std::move(candidates));
  for (const auto& [key, stored] : loaded)
    if (list.find(key) < 0) released_ += stored;
  resolve_list(model);
  stable_dt_ = 0;  // the step is bounded over the listed contacts
  x_at_build_ = x_;
  wall_offset_at_build_ = model.contact.wall_offset;
  stale_ = false;
  resumable_ = false;
  record_build(model);
}

void ParticleContact::record_build(Model& model) const {
  for (std::size_t i = 0; i < part_of_.size(); ++i) {
    ParticlePart& part = model.particle_parts[part_of_[i]];
    const std::size_t j = index_in_part_[i];
    for (int k = 0; k < part.dim; ++k) part.x_listed[part.dim * j + k] = x_at_build_[3 * i + k];
  }
  ContactState& c = model.contact;
  c.particle_list_built.assign(1, 1.0);
  c.particle_list_walls = wall_offset_at_build_;
  // Every node written (0 off the boundary), whatever the surface holds: the field is then the
  // same whatever it held before, and on every rank of a decomposed run.
  const int dim = model.dim();
  const bool facets = settings_.mesh && !model.parts.empty();
  c.particle_list_x.assign(facets ? model.nodes.count() * dim : 0, 0.0);
  if (facets && facet_x_at_build_.size() == surface_.nodes.size() * dim)
    for (std::size_t s = 0; s < surface_.nodes.size(); ++s)
      for (int a = 0; a < dim; ++a) c.particle_list_x[dim * surface_.nodes[s] + a] = facet_x_at_build_[dim * s + a];
}

void ParticleContact::resume_list(Model& model) {
  resumable_ = false;
  std::vector<std::int64_t> ids;
  index_particles(model, ids);
  gather(model);
  skin_ = skin(model);
  const ContactState& c = model.contact;
  const int dim = model.dim();
  if (settings_.mesh && !model.parts.empty()) {
    if (surface_stale_) surface_ = extract_contact_surface(model), surface_stale_ = false;
    facet_x_at_build_.clear();
    if (c.particle_list_x.size() == model.nodes.count() * dim)
      for (const std::int32_t node : surface_.nodes)
        facet_x_at_build_.insert(facet_x_at_build_.end(), &c.particle_list_x[dim * node], &c.particle_list_x[dim * (node + 1)]);
  }
  x_at_build_.assign(x_.size(), 0.0);
  for (std::size_t i = 0; i < part_of_.size(); ++i) {
    const ParticlePart& part = model.particle_parts[part_of_[i]];
    for (int k = 0; k < part.dim; ++k) x_at_build_[3 * i + k] = part.x_listed[part.dim * index_in_part_[i] + k];
  }
  wall_offset_at_build_ = c.particle_list_walls;
  std::unordered_map<std::int64_t, std::int32_t> facets;
  for (std::size_t f = 0; f < surface_.facet_id.size(); ++f) facets.emplace(surface_.facet_id[f], static_cast<std::int32_t>(f));
  auto held = [&](std::int64_t id) {
    return id >= 0 && static_cast<std::size_t>(id) < flat_of_id_.size() && flat_of_id_[static_cast<std::size_t>(id)] >= 0;
  };
  model.particle_contacts.keep_if([&](const InteractionKey& key) {
    if (!held(key.first)) return false;
    if (key.kind == InteractionKind::particle_particle) return held(key.second);
    return key.kind != InteractionKind::particle_facet || facets.count(key.second) > 0;
  });
  resolve_list(model);
  stable_dt_ = 0;  // bounded over the same list as when it was built
  stale_ = false;
}

void ParticleContact::resolve_list(const Model& model) {
  // The listed interactions by flat index (a wall w as −1 − w, a facet f as −1 − walls − f), and
  // each particle's in list order.
  std::unordered_map<std::int64_t, std::int32_t> facet_of_id;
  for (std::size_t f = 0; f < surface_.facet_id.size(); ++f) facet_of_id.emplace(surface_.facet_id[f], static_cast<std::int32_t>(f));
  const auto walls = static_cast<std::int32_t>(wall_count());
  const std::size_t n = part_of_.size();
  const InteractionList& list = model.particle_contacts;
  const std::size_t m = list.size();
  first_.resize(m);
  second_.resize(m);
  std::vector<std::int32_t> count(n + 1, 0);
  for (std::size_t k = 0; k < m; ++k) {
    const InteractionKey& key = list.key(k);
    first_[k] = flat_of_id_.at(static_cast<std::size_t>(key.first));
    switch (key.kind) {
      case InteractionKind::particle_particle: second_[k] = flat_of_id_.at(static_cast<std::size_t>(key.second)); break;
      case InteractionKind::particle_wall: second_[k] = -1 - static_cast<std::int32_t>(key.second); break;
      case InteractionKind::particle_facet: second_[k] = -1 - walls - facet_of_id.at(key.second); break;
    }
    ++count[first_[k] + 1];
    if (second_[k] >= 0) ++count[second_[k] + 1];
  }
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  incident_begin_ = count;
  incident_.resize(static_cast<std::size_t>(count[n]));
  for (std::size_t k = 0; k < m; ++k) {
    incident_[count[first_[k]]++] = static_cast<std::int32_t>(2 * k);
    if (second_[k] >= 0) incident_[count[second_[k]]++] = static_cast<std::int32_t>(2 * k + 1);
  }
  force_.resize(3 * m);
  torque_a_.resize(3 * m);
  torque_b_.resize(3 * m);
  stored_.resize(m);
  dissipated_.resize(m);
  acting_.resize(m);
  facet_weights_.assign(3 * m, 0.0);
  (void)model;
}

namespace {

/// One listed interaction at one step: the law where the bodies overlap, and the energy account
/// of the contact over the increment. The history holds the law's slots, then the force on the
/// second body and the stored energy of the last step (kHistoryTail values).
struct ContactEvaluation {
  const PairLaw* law;
  const std::vector<double>* params;
  /// The law acts this many times (rings: ParticleContact::contact_scale).
  double scale;
  ContactKinematics c;
  double arm_a[3] = {0, 0, 0}, arm_b[3] = {0, 0, 0};
  double rel[3] = {0, 0, 0};  ///< velocity of b's contact point relative to a's (m/s)

  /// f: the force on body b. Returns the energy dissipated over the increment: what the contact
  /// forces took from the bodies, ½ (f_n−1 + f_n)·v_rel Δt (the trapezoid the integrator's work
  /// uses), less the growth of the stored energy.
  double run(std::span<double> history, double* f, double* torque_b, double& stored) {
    const std::size_t h = law->history_size;
    double* previous = history.data() + h;
    ContactResponse r;
    if (c.overlap > 0) {
      r = law->evaluate(*params, c, history.first(h));
      if (scale != 1) {
        r.normal_force *= scale;
        r.stored_energy *= scale;
        for (int q = 0; q < 3; ++q) r.tangential_force[q] *= scale, r.rolling_torque[q] *= scale;
      }
    } else {
      std::fill_n(history.data(), h, 0.0);
    }
    for (int q = 0; q < 3; ++q) f[q] = r.normal_force * c.normal[q] + r.tangential_force[q];
    cross(arm_b, f, torque_b);
    for (int q = 0; q < 3; ++q) torque_b[q] += r.rolling_torque[q];
    stored = r.stored_energy;
    double work = 0;
    for (int q = 0; q < 3; ++q) work += 0.5 * (previous[q] + f[q]) * rel[q];
    const double dissipated = -work * c.dt - (stored - previous[3]);
    std::copy_n(f, 3, previous);
    previous[3] = stored;
    return dissipated;
  }
};

}  // namespace

int ParticleContact::history_size(const PairLaw& law) { return law.history_size + kHistoryTail; }

void ParticleContact::evaluate_contacts(Model& model, double time, double dt) {
  InteractionList& list = model.particle_contacts;
  const std::size_t m = first_.size();
  const int dim = model.dim();
  const auto walls = static_cast<std::int32_t>(wall_count());
  const auto listed_walls = static_cast<std::int32_t>(settings_.walls.size());
  const std::size_t law_slots = settings_.law->history_size;
  // The walls where they are at t_n, moving at their velocity of the increment (the axis stays).
  const std::vector<double> wall_origin = wall_origins(model);
  std::vector<double> wall_velocity(3 * wall_count(), 0.0);
  for (std::size_t w = 0; w < settings_.walls.size(); ++w)
    for (int a = 0; a < dim; ++a) wall_velocity[3 * w + a] = settings_.walls[w].velocity[a].at(time - 0.5 * dt);
  facet_features(model);
  std::size_t active = 0;
#pragma omp parallel for schedule(static) reduction(+ : active)
  for (std::size_t k = 0; k < m; ++k) {
    const std::int32_t a = first_[k], b = second_[k];
    double* fa = &force_[3 * k];
    double* ta = &torque_a_[3 * k];
    double* tb = &torque_b_[3 * k];
    std::span<double> history = list.history(k);
    const bool wall = b < 0 && b >= -walls;
    const std::vector<double>* params = !wall ? &settings_.params : b < -listed_walls ? &axis_params_ : &settings_.wall_params;
    ContactEvaluation ev{settings_.law, params, contact_scale(a, b), {}};
    ev.c.dim = dim;
    ev.c.dt = dt;
    geometry(model, k, wall_origin, ev.c);
    double* tail = history.data() + law_slots;
    const bool fresh = tail[0] == 0 && tail[1] == 0 && tail[2] == 0 && tail[3] == 0 && tail[4] == 0;
    if (ev.c.overlap > 0 && owned_[a]) ++active;
    if (fresh && ev.c.overlap > 0 && (newborn_[a] || (b >= 0 && newborn_[b]))) tail[4] = ev.c.overlap;
    if (tail[4] > 0) {
      // A particle made overlapping its neighbours (a converted element's points) starts
      // force-free: the overlap it was born with is carried, and given up as they part.
      tail[4] = std::min(tail[4], std::max(ev.c.overlap, 0.0));
      ev.c.overlap -= tail[4];
    }
    if (!(ev.c.overlap > 0) && fresh) {
      // Apart now and at the last step: nothing acts, nothing to book.
      acting_[k] = 0;
      stored_[k] = dissipated_[k] = 0;
      continue;
    }
    acting_[k] = 1;
    double f[3];
    if (b >= 0) {
      for (int q = 0; q < 3; ++q) ev.arm_a[q] = radius_[a] * ev.c.normal[q], ev.arm_b[q] = -radius_[b] * ev.c.normal[q];
      relative_motion(&v_[3 * a], &w_[3 * a], ev.arm_a, &v_[3 * b], &w_[3 * b], ev.arm_b, ev.c, ev.rel);
      ev.c.effective_radius = radius_[a] * radius_[b] / (radius_[a] + radius_[b]);
      ev.c.effective_mass = mass_[a] * mass_[b] / (mass_[a] + mass_[b]) / ev.scale;  // per sphere of a ring's row
      dissipated_[k] = ev.run(history, f, tb, stored_[k]);
      // On a: −f at arm_a, and the opposite of the law's own torque (tb less the moment of f).
      double ma[3], mb[3];
      cross(ev.arm_a, f, ma);
      cross(ev.arm_b, f, mb);
      for (int q = 0; q < 3; ++q) fa[q] = -f[q], ta[q] = -ma[q] - (tb[q] - mb[q]);
    } else {
      // A wall, or a facet point moving with its nodes, is body 1; the particle body 2 (stored in
      // the a slots); a facet's nodes take −f through its weights. Behind a facet the body is
      // taken as far heavier than the particle (m* = m, as for a wall): a node's own mass would
      // understate it and halve the dashpot of a particle as heavy as a node.
      double partner_velocity[3] = {0, 0, 0};
      if (wall) {
        std::copy_n(&wall_velocity[3 * static_cast<std::size_t>(-1 - b)], 3, partner_velocity);
      } else {
        const double* w = &facet_weights_[3 * k];
        const std::int32_t* nodes = &surface_.facets[dim * static_cast<std::size_t>(-1 - walls - b)];
        for (int i = 0; i < dim; ++i)
          for (int q = 0; q < dim; ++q) partner_velocity[q] += w[i] * model.nodes.v[dim * nodes[i] + q];
      }
      const double still[3] = {0, 0, 0};
      for (int q = 0; q < 3; ++q) ev.arm_b[q] = -radius_[a] * ev.c.normal[q];
      relative_motion(partner_velocity, still, ev.arm_a, &v_[3 * a], &w_[3 * a], ev.arm_b, ev.c, ev.rel);
      if (fresh && tail[4] == 0 && !wall) {
        // A facet contact found deeper than this step's approach (and half as much again for
        // the facet's turn): the particle was behind the surface, or under a face an eroded
        // element exposed. The excess is carried without force, as at birth: the law on the
        // whole depth would return energy the contact never stored. (A particle resting on the
        // mesh that passes on to the next facet is caught by this too: docs/theory/
        // particle_contact.md says what that costs.)
        const double excess = ev.c.overlap - 1.5 * std::max(0.0, -ev.c.normal_velocity) * dt;
        if (excess > 0) tail[4] = excess, ev.c.overlap -= excess;
      }
      ev.c.effective_radius = radius_[a];
      ev.c.effective_mass = mass_[a] / ev.scale;
      ev.c.rigid_partner = wall;
      dissipated_[k] = ev.run(history, f, ta, stored_[k]);
      for (int q = 0; q < 3; ++q) fa[q] = f[q], tb[q] = 0;
    }
  }
  active_ = active;
}

inline void ParticleContact::geometry(const Model& model, std::size_t k, const std::vector<double>& wall_origin,
                                      ContactKinematics& c) {
  const std::int32_t a = first_[k], b = second_[k];
  const auto walls = static_cast<std::int32_t>(wall_count());
  if (b < -walls) {
    // A facet is body 1, the particle body 2: the normal from the facet's closest point (found,
    // and duplicates set aside, by facet_features).
    const auto f = static_cast<std::size_t>(-1 - walls - b);
    if (facet_suppressed_[k]) {
      c.overlap = -1;
      return;
    }
    const double* q = &facet_q_[3 * k];
    double d[3], dist2 = 0;
    for (int i = 0; i < 3; ++i) d[i] = x_[3 * a + i] - q[i], dist2 += d[i] * d[i];
    const double dist = std::sqrt(dist2);
    c.overlap = radius_[a] - dist;
    if (dist > 0)
      for (int i = 0; i < 3; ++i) c.normal[i] = d[i] / dist;
    // A centre behind the facet (inside the body) is not pushed out through it.
    if (dot3(d, facet_outward(model, f).data()) < 0) c.overlap = -1;
    return;
  }
  if (b >= 0) {
    double d[3], dist2 = 0;
    for (int q = 0; q < 3; ++q) d[q] = x_[3 * b + q] - x_[3 * a + q], dist2 += d[q] * d[q];
    const double dist = std::sqrt(dist2);
    c.overlap = radius_[a] + radius_[b] - dist;
    if (dist > 0)
      for (int q = 0; q < 3; ++q) c.normal[q] = d[q] / dist;
    return;
  }
  const std::size_t w = static_cast<std::size_t>(-1 - b);
  if (w >= settings_.walls.size()) {  // the axis of an axisymmetric model: a plane through 0
    c.overlap = radius_[a] - x_[3 * a];
    std::copy_n(kAxisNormal, 3, c.normal);
    return;
  }
  // A finite wall's plate pushes through the face the particle is nearest; off it, or past its
  // depth, the contact is apart (one that held lets go).
  WallTouch touch;
  const bool touching = settings_.walls[w].touch(&x_[3 * a], &wall_origin[3 * w], radius_[a], c.dim, touch);
  c.overlap = touching ? touch.penetration : std::min(touch.penetration, -radius_[a]);
  for (int q = 0; q < 3; ++q) c.normal[q] = touch.normal[q];
}

std::vector<double> ParticleContact::wall_origins(const Model& model) const {
  const int dim = model.dim();
  std::vector<double> origin(3 * wall_count(), 0.0);  // the axis passes through 0
  for (std::size_t w = 0; w < settings_.walls.size(); ++w)
    for (int a = 0; a < dim; ++a) origin[3 * w + a] = settings_.walls[w].point[a] + model.contact.wall_offset[dim * w + a];
  return origin;
}

std::vector<double> ParticleContact::wall_normals() const {
  std::vector<double> normal(3 * wall_count(), 0.0);
  for (std::size_t w = 0; w < wall_count(); ++w)
    std::copy_n(w < settings_.walls.size() ? settings_.walls[w].normal.data() : kAxisNormal, 3, &normal[3 * w]);
  return normal;
}

void ParticleContact::facet_features(const Model& model) {
  // Every facet contact's closest point; then, per particle (its facet contacts are contiguous
  // in the list, which is sorted by kind, particle, facet), one contact per touching feature. On
  // a smooth stretch of surface a particle's closest point lies inside one facet, or on an edge
  // or vertex that several facets share; the facets around it also find points within reach, on
  // their edges, and would each push. A hit on a facet's edge or vertex is set aside when another
  // contact of the particle nearby (its point within a radius) is closer, or as close and inside
  // its facet or earlier in the list: what is left is the closest feature, once, and the
  // separate faces of a concave corner.
  const auto walls = static_cast<std::int32_t>(wall_count());
  const std::size_t m = first_.size();
  constexpr double kEdge = 1e-9;  // a weight this small puts the point on the facet's edge
  facet_q_.resize(3 * m);
  facet_suppressed_.assign(m, 0);
  std::vector<double> distance;
  std::size_t k = 0;
  while (k < m && second_[k] >= -walls) ++k;
  while (k < m && second_[k] < -walls) {
    const std::int32_t a = first_[k];
    std::size_t end = k;
    distance.clear();
    for (; end < m && second_[end] < -walls && first_[end] == a; ++end) {
      const auto f = static_cast<std::size_t>(-1 - walls - second_[end]);
      closest_on_facet(model, f, &x_[3 * a], &facet_q_[3 * end], &facet_weights_[3 * end]);
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += (x_[3 * a + i] - facet_q_[3 * end + i]) * (x_[3 * a + i] - facet_q_[3 * end + i]);
      distance.push_back(std::sqrt(d2));
    }
    auto on_edge = [&](std::size_t e) {
      const double* w = &facet_weights_[3 * e];
      return !(w[0] > kEdge && w[1] > kEdge && (model.dim() == 2 || w[2] > kEdge));
    };
    // Nearly equal distances (the same vertex or edge seen from several facets, up to round-off
    // and the particle's drift) count as equal; among equals the first in the list stays.
    const double r = radius_[a], tolerance = 1e-6 * r;
    // Points closer together than 1e-3 R are one feature whatever the facets' weights say (a node
    // pressed down by the particle dents the surface: each facet around it then finds its own
    // point inside, a fraction of a nanometre from the others).
    const double same_point = 1e-3 * r;
    for (std::size_t j = k; j < end; ++j) {
      for (std::size_t i = k; i < end && !facet_suppressed_[j]; ++i) {
        if (i == j) continue;
        double d2 = 0;
        for (int c = 0; c < 3; ++c) d2 += (facet_q_[3 * i + c] - facet_q_[3 * j + c]) * (facet_q_[3 * i + c] - facet_q_[3 * j + c]);
        const bool one_feature = d2 < same_point * same_point;
        if (!one_feature && (!on_edge(j) || d2 >= r * r)) continue;
        const double di = distance[i - k], dj = distance[j - k];
        const bool closer = di < dj - tolerance;
        const bool as_close = di <= dj + tolerance && (i < j || (!one_feature && !on_edge(i)));
        if (closer || as_close) facet_suppressed_[j] = 1;
      }
    }
    k = end;
  }
}

std::array<double, 3> ParticleContact::facet_outward(const Model& model, std::size_t f) const {
  const int dim = model.dim();
  const std::int32_t* n = &surface_.facets[dim * f];
  const double* X = model.nodes.x.data();
  if (dim == 2) return {X[2 * n[1] + 1] - X[2 * n[0] + 1], -(X[2 * n[1]] - X[2 * n[0]]), 0.0};
  const double u[3] = {X[3 * n[1]] - X[3 * n[0]], X[3 * n[1] + 1] - X[3 * n[0] + 1], X[3 * n[1] + 2] - X[3 * n[0] + 2]};
  const double v[3] = {X[3 * n[2]] - X[3 * n[0]], X[3 * n[2] + 1] - X[3 * n[0] + 1], X[3 * n[2] + 2] - X[3 * n[0] + 2]};
  std::array<double, 3> out;
  cross(u, v, out.data());
  return out;
}

void ParticleContact::add_facet_reactions(Model& model) const {
  // In list order, one contact after another: the nodal sums are the same for any thread count.
  const int dim = model.dim();
  const auto walls = static_cast<std::int32_t>(wall_count());
  for (std::size_t k = 0; k < first_.size(); ++k) {
    if (second_[k] >= -walls || !acting_[k]) continue;
    const std::int32_t* nodes = &surface_.facets[dim * static_cast<std::size_t>(-1 - walls - second_[k])];
    for (int i = 0; i < dim; ++i)
      for (int q = 0; q < dim; ++q) model.nodes.force[dim * nodes[i] + q] -= facet_weights_[3 * k + i] * force_[3 * k + q];
  }
}

void ParticleContact::scatter(Model& model, std::vector<ExactSum>& wall_force) {
  const std::size_t n = part_of_.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double f[3] = {0, 0, 0}, t[3] = {0, 0, 0};
    for (std::int32_t e = incident_begin_[i]; e < incident_begin_[i + 1]; ++e) {
      const std::size_t k = static_cast<std::size_t>(incident_[e]) / 2;
      if (!acting_[k]) continue;
      const bool side_b = incident_[e] & 1;
      const double* tk = side_b ? &torque_b_[3 * k] : &torque_a_[3 * k];
      for (int q = 0; q < 3; ++q) {
        f[q] += side_b ? -force_[3 * k + q] : force_[3 * k + q];
        t[q] += tk[q];
      }
    }
    ParticlePart& p = model.particle_parts[part_of_[i]];
    const std::size_t j = index_in_part_[i];
    const int D = p.dim;
    for (int q = 0; q < D; ++q) p.force[D * j + q] += f[q];
    if (p.rot_dim() == 3) {
      for (int q = 0; q < 3; ++q) p.torque[3 * j + q] += t[q];
    } else {
      p.torque[j] += t[2];
    }
  }
  // The listed walls' share of the contacts this process books (the axis reports none).
  const int dim = model.dim();
  wall_force.assign(settings_.walls.size() * dim, ExactSum());
  const auto walls = static_cast<std::int32_t>(settings_.walls.size());
  for (std::size_t k = 0; k < first_.size(); ++k)
    if (second_[k] < 0 && second_[k] >= -walls && acting_[k] && owned_[first_[k]])
      for (int q = 0; q < dim; ++q) wall_force[dim * static_cast<std::size_t>(-1 - second_[k]) + q] += -force_[3 * k + q];
}

ParticleContactWork ParticleContact::add_forces(Model& model, double time, double dt) {
  if (stale_ && resumable_) resume_list(model);
  if (!stale_) gather(model);
  if (list_is_stale(model)) rebuild_list(model);
  evaluate_contacts(model, time, dt);
  ParticleContactWork work;
  scatter(model, work.wall_force);
  add_facet_reactions(model);
  // Particles are newborn for their first evaluation only.
  if (std::find(newborn_.begin(), newborn_.end(), 1) != newborn_.end()) {
    std::fill(newborn_.begin(), newborn_.end(), 0);
    for (std::size_t p = 0; p < model.particle_parts.size(); ++p)
      if (takes_part(p)) std::fill(model.particle_parts[p].newborn.begin(), model.particle_parts[p].newborn.end(), 0);
  }
  for (std::size_t k = 0; k < first_.size(); ++k)
    if (acting_[k] && owned_[first_[k]]) work.stored += stored_[k], work.dissipated += dissipated_[k];
  work.dissipated += released_;
  released_ = 0;
  wall_force_.resize(work.wall_force.size());
  for (std::size_t i = 0; i < wall_force_.size(); ++i) wall_force_[i] = work.wall_force[i].value();
  return work;
}

double ParticleContact::stable_time_step(const Model& model) {
  if (stable_dt_ > 0) return stable_dt_;
  // Over the listed interactions: every pair that can touch before the list is built again (a
  // new list, after a move of half the skin or a topology change, computes it again). Per
  // contact ω² = s k / m* with the law's largest stiffness k there, s the ring count, and m*
  // of the two bodies: a wall is rigid; behind a facet stands its lightest node, which takes the
  // reaction (a light node split off by a crack, or near the axis, sets the step, not the
  // lightest node of the mesh).
  const PairLaw& law = *settings_.law;
  const auto walls = static_cast<std::int32_t>(wall_count());
  const int dim = model.dim();
  double omega2 = 0;
  for (std::size_t k = 0; k < first_.size(); ++k) {
    const std::int32_t a = first_[k], b = second_[k];
    // The contacts this process books: in a subdomain the owner of a particle holds every
    // element around its facets' corners, so their lumped masses are whole (a ghost node further
    // out may miss some); the ranks then take the largest.
    if (!owned_[a]) continue;
    ContactKinematics c;
    double inverse_mass = 1 / mass_[a];
    c.effective_radius = radius_[a];
    const std::vector<double>* params = &settings_.params;
    if (b >= 0) {
      c.effective_radius = radius_[a] * radius_[b] / (radius_[a] + radius_[b]);
      inverse_mass += 1 / mass_[b];
    } else if (b >= -walls) {
      c.rigid_partner = true;
      params = &settings_.wall_params;
    } else {
      const std::int32_t* nodes = &surface_.facets[dim * static_cast<std::size_t>(-1 - walls - b)];
      double lightest = 0;
      for (int i = 0; i < dim; ++i) {
        const double mn = model.nodes.mass[nodes[i]];
        if (mn > 0) lightest = lightest > 0 ? std::min(lightest, mn) : mn;
      }
      if (lightest > 0) inverse_mass += 1 / lightest;
    }
    c.effective_mass = 1 / inverse_mass;
    omega2 = std::max(omega2, std::max(contact_scale(a, b), 1.0) * law.stiffness(*params, c) * inverse_mass);
  }
  // And whatever the list holds now, each particle against its like and a wall: the step of
  // free flight, so that no particle crosses a neighbour in one step before the list sees it.
  for (std::size_t i = 0; i < part_of_.size(); ++i) {
    ContactKinematics c;
    const double scale = std::max(ring_scale_[i], 1.0);
    if (!walls_only(part_of_[i])) {
      c.effective_radius = 0.5 * radius_[i];
      c.effective_mass = 0.5 * mass_[i];
      omega2 = std::max(omega2, scale * law.stiffness(settings_.params, c) / c.effective_mass);
    }
    if (walls > 0) {
      c.effective_radius = radius_[i];
      c.effective_mass = mass_[i];
      c.rigid_partner = true;
      omega2 = std::max(omega2, scale * law.stiffness(settings_.wall_params, c) / c.effective_mass);
    }
  }
  stable_dt_ = omega2 > 0 ? settings_.time_step_safety * 2 / std::sqrt(omega2) : std::numeric_limits<double>::infinity();
  return stable_dt_;
}

}  // namespace shard
