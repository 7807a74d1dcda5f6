#include "fracture/fragments.hpp"

#include <algorithm>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "core/disjoint_sets.hpp"

namespace shard {

namespace {

bool live(const Part& part, std::size_t e) { return part.eroded.empty() || part.eroded[e] == 0; }

/// Joins the two sides of every cohesive interface element that still holds: not open (some
/// point not yet failed, so it still carries traction) and bounding two live elements. Its node
/// pairs are stable ids; a pair whose node has left the model joins nothing.
void join_across_intact_interfaces(const Model& model, DisjointSets& sets) {
  const CohesiveElements& c = model.cohesive;
  if (c.element_count() == 0) return;
  std::vector<char> live_id(static_cast<std::size_t>(std::max<std::int64_t>(model.next_element_id, 0)), 0);
  for (const Part& part : model.parts)
    for (std::size_t e = 0; e < part.element_count(); ++e)
      if (live(part, e) && part.id[e] >= 0 && part.id[e] < model.next_element_id) live_id[part.id[e]] = 1;
  auto is_live = [&](std::int64_t id) { return id >= 0 && id < model.next_element_id && live_id[id]; };
  const std::vector<std::int32_t> index = index_of_ids(model.nodes.id, model.next_node_id);
  auto node = [&](std::int64_t id) { return id >= 0 && id < model.next_node_id ? index[id] : -1; };
  const std::size_t k = static_cast<std::size_t>(c.nodes_per_face);
  for (std::size_t e = 0; e < c.element_count(); ++e) {
    if (c.open[e] || !is_live(c.owner_a[e]) || !is_live(c.owner_b[e])) continue;
    for (std::size_t q = 0; q < k; ++q) {
      const std::int32_t a = node(c.node_a[k * e + q]), b = node(c.node_b[k * e + q]);
      if (a >= 0 && b >= 0) sets.join(a, b);
    }
  }
}

}  // namespace

Fragments find_fragments(const Model& model) {
  const std::size_t nn = model.nodes.count();
  const int dim = model.dim();
  DisjointSets sets(nn);
  for (const Part& part : model.parts) {
    const int npe = part.type->nodes;
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!live(part, e)) continue;
      const std::int32_t* cn = &part.connectivity[npe * e];
      for (int a = 1; a < npe; ++a) sets.join(cn[0], cn[a]);
    }
  }
  join_across_intact_interfaces(model, sets);

  Fragments out;
  std::vector<std::int32_t> id_of_root(nn, -1);
  std::vector<std::size_t> last_part;  // per fragment: the last part whose name it got
  out.element_fragment.resize(model.parts.size());
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    const Part& part = model.parts[p];
    const int npe = part.type->nodes;
    auto& fragment_of = out.element_fragment[p];
    fragment_of.assign(part.element_count(), -1);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      if (!live(part, e)) continue;
      std::int32_t& id = id_of_root[sets.find(part.connectivity[npe * e])];
      if (id < 0) {
        id = static_cast<std::int32_t>(out.list.size());
        out.list.push_back(Fragment{});
        out.list.back().id = id;
        out.list.back().part = part.name;
        last_part.push_back(p);
      } else if (last_part[id] != p) {  // parts in order: each name once, in the scenario's order
        out.list[id].part += "+" + part.name;
        last_part[id] = p;
      }
      fragment_of[e] = id;
      ++out.list[id].elements;
    }
  }

  out.node_fragment.assign(nn, -1);
  const double* X = model.nodes.x.data();
  const double* V = model.nodes.v.data();
  std::vector<std::array<double, 3>> moment(out.list.size(), {0, 0, 0});
  std::vector<std::array<double, 3>> momentum(out.list.size(), {0, 0, 0});
  for (std::size_t i = 0; i < nn; ++i) {
    const std::int32_t id = id_of_root[sets.find(static_cast<std::int32_t>(i))];
    out.node_fragment[i] = id;
    if (id < 0) continue;
    Fragment& f = out.list[id];
    const double m = model.nodes.mass[i];
    f.mass += m;
    for (int k = 0; k < dim; ++k) {
      moment[id][k] += m * X[dim * i + k];
      momentum[id][k] += m * V[dim * i + k];
      f.kinetic_energy += 0.5 * m * V[dim * i + k] * V[dim * i + k];
    }
  }
  for (Fragment& f : out.list)
    for (int k = 0; k < dim; ++k) {
      f.centroid[k] = f.mass > 0 ? moment[f.id][k] / f.mass : 0.0;
      f.velocity[k] = f.mass > 0 ? momentum[f.id][k] / f.mass : 0.0;
    }
  return out;
}

std::vector<Fragment> debris_fragments(const Model& model, std::int32_t first_id) {
  std::vector<Fragment> out;
  for (const ParticlePart& p : model.particle_parts) {
    const int D = p.dim, R = p.rot_dim();
    std::string origin = p.name;  // the debris part of part X is X_particles
    for (const Part& part : model.parts)
      if (part.name + "_particles" == p.name) origin = part.name;
    for (std::size_t i = 0; i < p.count(); ++i) {
      if (p.origin_element[i] < 0) continue;
      Fragment f;
      f.id = first_id + static_cast<std::int32_t>(out.size());
      f.part = origin;
      f.particles = 1;
      f.mass = p.mass[i];
      for (int k = 0; k < D; ++k) {
        f.centroid[k] = p.x[D * i + k];
        f.velocity[k] = p.v[D * i + k];
        f.kinetic_energy += 0.5 * p.mass[i] * p.v[D * i + k] * p.v[D * i + k];
      }
      for (int k = 0; k < R; ++k) f.kinetic_energy += 0.5 * p.inertia[i] * p.omega[R * i + k] * p.omega[R * i + k];
      out.push_back(f);
    }
  }
  return out;
}

void write_fragments_csv(const std::filesystem::path& path, const std::vector<Fragment>& fragments, int dim) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  const char* axis[3] = {"x", "y", "z"};
  out << "id,part,elements,mass";
  for (int k = 0; k < dim; ++k) out << ",centroid_" << axis[k];
  for (int k = 0; k < dim; ++k) out << ",velocity_" << axis[k];
  out << ",kinetic_energy,particles\n";
  out.precision(std::numeric_limits<double>::max_digits10);
  for (const Fragment& f : fragments) {
    out << f.id << ',' << f.part << ',' << f.elements << ',' << f.mass;
    for (int k = 0; k < dim; ++k) out << ',' << f.centroid[k];
    for (int k = 0; k < dim; ++k) out << ',' << f.velocity[k];
    out << ',' << f.kinetic_energy << ',' << f.particles << '\n';
  }
  if (!out) throw std::runtime_error("error writing " + path.string());
}

}  // namespace shard
