#include "solver/element_conversion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fem/element.hpp"
#include "fem/hex8_shape.hpp"

namespace shard {

std::vector<double> conversion_point_weights(const ElementType& type) {
  const int n = type.nodes;
  if (type.points == 1) return std::vector<double>(n, 1.0 / n);  // the centroid
  if (type.name == "hex8") {
    std::vector<double> w(64);
    for (int q = 0; q < 8; ++q)
      for (int a = 0; a < 8; ++a) w[8 * q + a] = kHex8Gauss.N[q][a];
    return w;
  }
  throw std::invalid_argument("elements of type " + type.name + " cannot be converted to particles");
}

namespace {

/// The element's row-sum lumped masses on the reference positions: what it gave its nodes.
std::vector<double> element_mass_shares(const Model& model, const Part& part, std::size_t e, double density) {
  const int n = part.type->nodes, dim = model.dim();
  NodeArrays nodes;
  nodes.dim = dim;
  nodes.resize(static_cast<std::size_t>(n));
  Part one;
  one.type = part.type;
  one.connectivity.resize(static_cast<std::size_t>(n));
  for (int a = 0; a < n; ++a) {
    const std::int32_t node = part.connectivity[static_cast<std::size_t>(n) * e + a];
    for (int k = 0; k < dim; ++k) nodes.x[dim * a + k] = model.nodes.x0[dim * node + k];
    one.connectivity[a] = a;
  }
  std::vector<double> mass(static_cast<std::size_t>(n), 0.0);
  kernel_of(*part.type).lump_masses(one, nodes, density, model.formulation, model.thickness, mass.data());
  return mass;
}

int debris_part(Model& model, const Part& part) {
  const std::string name = part.name + "_particles";
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p)
    if (model.particle_parts[p].name == name) return static_cast<int>(p);
  ParticlePart debris;
  debris.name = name;
  debris.dim = model.dim();
  model.particle_parts.push_back(std::move(debris));
  return static_cast<int>(model.particle_parts.size()) - 1;
}

/// The radius of eq. (13) of the CFRP paper: a sphere (3D), a disc of the model's thickness (2D),
/// or in axisymmetry the circular cross-section of a ring about the axis through x_r, of mass m
/// at density ρ: ρ_c = √(m / (2π² ρ x_r)). A ring's circumference goes to `ring_length`.
double point_radius(const Model& model, double m, double density, double x_r, double& ring_length) {
  if (model.dim() == 3) return std::cbrt(3 * m / (4 * std::numbers::pi * density));
  if (model.formulation != Formulation::axisymmetric)
    return std::sqrt(m / (std::numbers::pi * density * model.thickness));
  // (A point on the axis, of an element flattened onto it, is a ring of its own sphere's radius.)
  ring_length = 2 * std::numbers::pi * (x_r > 0 ? x_r : std::cbrt(3 * m / (4 * std::numbers::pi * density)));
  return std::sqrt(m / (std::numbers::pi * density * ring_length));
}

struct Converting {
  int part;
  std::size_t element;
  std::vector<double> shares;  ///< reference lumped mass per local node
};

}  // namespace

ConversionResult ElementConversion::prepare(Model& model, const std::vector<std::unique_ptr<Material>>& materials,
                                            Remap& remap) {
  ConversionResult out;
  born_.clear();
  const int dim = model.dim();
  const std::size_t nn = model.nodes.count();
  // Which elements leave, which of them convert, and what each gave its nodes.
  std::vector<Converting> converting;
  std::vector<std::int32_t> live_refs(nn, 0);
  std::vector<double> shares_at_node(nn, 0.0);
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int n = part.type->nodes;
    std::vector<std::uint8_t> keep(part.element_count(), 1);
    bool any = false;
    for (std::size_t e = 0; e < keep.size(); ++e) {
      if (!part.eroded[e]) {
        for (int a = 0; a < n; ++a) ++live_refs[part.connectivity[static_cast<std::size_t>(n) * e + a]];
        continue;
      }
      keep[e] = 0, any = true;
      if (!part.erosion.to_particles) continue;
      Converting c{static_cast<int>(p), e, element_mass_shares(model, part, e, materials[part.material]->density())};
      for (int a = 0; a < n; ++a) shares_at_node[part.connectivity[static_cast<std::size_t>(n) * e + a]] += c.shares[a];
      converting.push_back(std::move(c));
    }
    if (any) remap.elements.emplace(static_cast<int>(p), EntityRemap::keeping(keep));
  }
  if (converting.empty()) return out;

  // What each node gives: its converted elements' shares, or all it has if no element is left
  // to hold it (the node then leaves too); never more than it has.
  std::vector<double> taken(nn, 0.0);
  std::vector<std::uint8_t> keep_node(nn, 1);
  bool orphans = false;
  for (std::size_t a = 0; a < nn; ++a) {
    if (shares_at_node[a] == 0) continue;
    if (live_refs[a] == 0) {
      taken[a] = model.nodes.mass[a];
      keep_node[a] = 0, orphans = true;
    } else {
      taken[a] = std::min(shares_at_node[a], model.nodes.mass[a]);
    }
  }
  if (orphans) remap.nodes = EntityRemap::keeping(keep_node);

  for (const Converting& c : converting) {
    const Part& part = model.parts[c.part];
    const int n = part.type->nodes, npts = part.type->points;
    const std::vector<double> weights = conversion_point_weights(*part.type);
    const int target = debris_part(model, part);
    // The element's mass and momentum: its share of what each node gives.
    double mass = 0, momentum[3] = {0, 0, 0};
    std::vector<double> m_a(static_cast<std::size_t>(n));
    for (int a = 0; a < n; ++a) {
      const std::int32_t node = part.connectivity[static_cast<std::size_t>(n) * c.element + a];
      m_a[a] = taken[node] * (c.shares[a] / shares_at_node[node]);
      mass += m_a[a];
      for (int k = 0; k < dim; ++k) momentum[k] += m_a[a] * model.nodes.v[dim * node + k];
      double v2 = 0;
      for (int k = 0; k < dim; ++k) v2 += model.nodes.v[dim * node + k] * model.nodes.v[dim * node + k];
      out.kinetic_taken += 0.5 * m_a[a] * v2;
    }
    if (!(mass > 0)) {
      // Its nodes have nothing left to give (every share already taken by split siblings): the
      // element leaves without particles, as a deleted one would.
      ++out.elements;
      continue;
    }
    // Current density (the radius of eq. (13) of the CFRP paper: a sphere, or a disc of the
    // model's thickness, of the point's mass at that density).
    const double volume = kernel_of(*part.type).measure(part, model.nodes, c.element, model.formulation, model.thickness);
    const double density = volume > 0 ? mass / volume : materials[part.material]->density();
    const double mq = mass / npts;
    std::vector<Born> points(static_cast<std::size_t>(npts));
    double interpolated[3] = {0, 0, 0};
    for (int q = 0; q < npts; ++q) {
      Born& b = points[q];
      b = Born{target, {0, 0, 0}, {0, 0, 0}, mq, 0, 0, 0, part.id[c.element], part.material};
      for (int a = 0; a < n; ++a) {
        const std::int32_t node = part.connectivity[static_cast<std::size_t>(n) * c.element + a];
        for (int k = 0; k < dim; ++k) {
          b.x[k] += weights[n * q + a] * model.nodes.x[dim * node + k];
          b.v[k] += weights[n * q + a] * model.nodes.v[dim * node + k];
        }
      }
      for (int k = 0; k < dim; ++k) interpolated[k] += mq * b.v[k];
      b.radius = point_radius(model, mq, density, b.x[0], b.ring_length);
      b.inertia = (dim == 3 ? 0.4 : 0.5) * mq * b.radius * b.radius;
    }
    // The interpolated velocities carry the element's momentum only where the lumped shares
    // match the points' (an undistorted element): a uniform correction makes it exact.
    for (Born& b : points) {
      for (int k = 0; k < dim; ++k) b.v[k] += (momentum[k] - interpolated[k]) / mass;
      double v2 = 0;
      for (int k = 0; k < dim; ++k) v2 += b.v[k] * b.v[k];
      out.kinetic_given += 0.5 * b.mass * v2;
      born_.push_back(b);
    }
    out.mass += mass;
    ++out.elements;
    out.particles += npts;
  }
  for (std::size_t a = 0; a < nn; ++a) model.nodes.mass[a] -= taken[a];
  first_new_.assign(model.particle_parts.size(), 0);
  std::vector<std::size_t> count(model.particle_parts.size(), 0);
  for (std::size_t p = 0; p < model.particle_parts.size(); ++p) first_new_[p] = model.particle_parts[p].count();
  for (const Born& b : born_) ++count[b.particle_part];
  for (std::size_t p = 0; p < count.size(); ++p) {
    if (count[p] == 0) continue;
    EntityRemap grow = EntityRemap::identity(first_new_[p]);
    for (std::size_t k = 0; k < count[p]; ++k) grow.add_born(-1);
    remap.particles.emplace(static_cast<int>(p), std::move(grow));
  }
  return out;
}

void ElementConversion::finish(Model& model) {
  std::vector<std::size_t> next = first_new_;
  for (const Born& b : born_) {
    ParticlePart& pp = model.particle_parts[b.particle_part];
    const std::size_t i = next[b.particle_part]++;
    const int D = pp.dim;
    for (int k = 0; k < D; ++k) {
      pp.x[D * i + k] = pp.x0[D * i + k] = pp.x_old[D * i + k] = b.x[k];
      pp.v[D * i + k] = b.v[k];
    }
    pp.mass[i] = b.mass;
    pp.radius[i] = b.radius;
    pp.ring_length[i] = b.ring_length;
    pp.inertia[i] = b.inertia;
    pp.material[i] = b.material;
    pp.origin_element[i] = b.element_id;
    pp.newborn[i] = 1;
  }
  born_.clear();
}

}  // namespace shard
