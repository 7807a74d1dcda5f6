// Sample builders for MCA (see packing.hpp).
#include "particle/packing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "core/error.hpp"
#include "model/remap.hpp"

namespace shard {

namespace {

struct LatticeCell {
  int dim = 3;
  double a[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  ///< primitive translation vectors (rows)
  std::vector<std::array<double, 3>> basis;
  double volume = 0;  ///< Voronoi cell volume per automaton (2D: area, before thickness)
  double face = 0;    ///< face area between nearest neighbours (2D: length, before thickness)
};

LatticeCell lattice_cell(Lattice lattice, double d) {
  LatticeCell c;
  switch (lattice) {
    case Lattice::hexagonal_2d:
      c.dim = 2;
      c.a[0][0] = d;
      c.a[1][0] = 0.5 * d, c.a[1][1] = 0.5 * std::sqrt(3.0) * d;
      c.basis = {{0, 0, 0}};
      c.volume = 0.5 * std::sqrt(3.0) * d * d;  // hexagon of inradius d/2
      c.face = d / std::sqrt(3.0);
      break;
    case Lattice::square_2d:
      c.dim = 2;
      c.a[0][0] = d, c.a[1][1] = d;
      c.basis = {{0, 0, 0}};
      c.volume = d * d;
      c.face = d;
      break;
    case Lattice::fcc: {
      const double a = d * std::sqrt(2.0);
      c.a[0][0] = a, c.a[1][1] = a, c.a[2][2] = a;
      c.basis = {{0, 0, 0}, {0.5 * a, 0.5 * a, 0}, {0.5 * a, 0, 0.5 * a}, {0, 0.5 * a, 0.5 * a}};
      c.volume = a * a * a / 4;               // rhombic dodecahedron of inradius d/2
      c.face = d * d / (2 * std::sqrt(2.0));  // its face: V = 12 · S · (d/2) / 3
      break;
    }
    case Lattice::simple_cubic:
      c.a[0][0] = d, c.a[1][1] = d, c.a[2][2] = d;
      c.basis = {{0, 0, 0}};
      c.volume = d * d * d;
      c.face = d * d;
      break;
  }
  return c;
}

}  // namespace

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

ParticlePart build_packing(const PackingSpec& spec, std::vector<MCAMaterial> materials) {
  if (spec.size <= 0) throw InputError("packing: automaton size must be positive");
  if (materials.empty()) throw InputError("packing: no material");
  const LatticeCell cell = lattice_cell(spec.lattice, spec.size);
  const double volume = cell.dim == 2 ? cell.volume * spec.thickness : cell.volume;
  const double face = cell.dim == 2 ? cell.face * spec.thickness : cell.face;
  const int D = cell.dim;
  for (int a = 0; a < D; ++a)
    if (spec.hi[a] <= spec.lo[a]) throw InputError(std::string("packing: box is empty along axis ") + "xyz"[a]);
  // Lattice origin: the box corner when not rotated (faces through lattice planes), the box
  // centre when rotated.
  double origin[3] = {spec.lo[0], spec.lo[1], D == 3 ? spec.lo[2] : 0.0};
  const bool rotated = spec.angle != 0;
  if (rotated)
    for (int a = 0; a < D; ++a) origin[a] = 0.5 * (spec.lo[a] + spec.hi[a]);
  const double ca = std::cos(spec.angle), sa = std::sin(spec.angle);
  const double tol = 1e-9 * spec.size;
  // Integer ranges of the lattice indices that cover the box: the box corners in the lattice's
  // own frame, in fractional coordinates of the translation vectors.
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (int r = 0; r < D; ++r)
    for (int c = 0; c < D; ++c) A(c, r) = cell.a[r][c];
  const Eigen::Matrix3d Ainv = A.inverse();
  long imin[3] = {0, 0, 0}, imax[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a) imin[a] = 1L << 40, imax[a] = -(1L << 40);
  for (int corner = 0; corner < (1 << D); ++corner) {
    double c[3] = {0, 0, 0};
    for (int a = 0; a < D; ++a) c[a] = ((corner >> a) & 1 ? spec.hi[a] : spec.lo[a]) - origin[a];
    const Eigen::Vector3d local(ca * c[0] + sa * c[1], -sa * c[0] + ca * c[1], c[2]);
    const Eigen::Vector3d f = Ainv * local;
    for (int a = 0; a < D; ++a) {
      imin[a] = std::min(imin[a], static_cast<long>(std::floor(f(a))) - 1);
      imax[a] = std::max(imax[a], static_cast<long>(std::ceil(f(a))) + 1);
    }
  }
  if (D == 2) imin[2] = imax[2] = 0;
  const long kz = D == 3 ? 1 : 0;
  std::vector<double> sites;
  for (long k = imin[2]; k <= imax[2]; ++k)
    for (long j = imin[1]; j <= imax[1]; ++j)
      for (long i = imin[0]; i <= imax[0]; ++i)
        for (const auto& b : cell.basis) {
          double p[3];
          for (int a = 0; a < 3; ++a) p[a] = i * cell.a[0][a] + j * cell.a[1][a] + kz * k * cell.a[2][a] + b[a];
          const double px = ca * p[0] - sa * p[1], py = sa * p[0] + ca * p[1];
          double pos[3] = {origin[0] + px, origin[1] + py, origin[2] + p[2]};
          bool inside = true;
          for (int a = 0; a < D; ++a) inside = inside && pos[a] >= spec.lo[a] - tol && pos[a] <= spec.hi[a] + tol;
          if (inside) sites.insert(sites.end(), pos, pos + D);
        }
  const std::size_t n = sites.size() / static_cast<std::size_t>(D);
  if (n == 0) throw InputError("packing: the box holds no automaton; make it larger than the size");
  ParticlePart part = make_automata(D, spec.plane, spec.thickness, std::move(materials), n);
  MCAState& s = mca_state(part);
  part.x = std::move(sites);
  for (std::size_t i = 0; i < n; ++i) {
    part.radius[i] = 0.5 * spec.size;
    part.material[i] = spec.material;
    s.volume[i] = volume;
    s.face_area[i] = face;
  }
  return part;
}

const char* lattice_name(Lattice lattice) {
  switch (lattice) {
    case Lattice::hexagonal_2d: return "hexagonal";
    case Lattice::square_2d: return "square";
    case Lattice::fcc: return "fcc";
    case Lattice::simple_cubic: return "simple_cubic";
  }
  return "?";
}

ParticlePart place_automata(const PackingSpec& spec, std::vector<MCAMaterial> materials, std::vector<double> x,
                            const std::vector<double>& radius, const std::vector<std::int64_t>& id,
                            const std::vector<int>& material) {
  const LatticeCell cell = lattice_cell(spec.lattice, spec.size);
  // The same products as build_packing, so that a sample read back has the same bits.
  const double volume = cell.dim == 2 ? cell.volume * spec.thickness : cell.volume;
  const double face = cell.dim == 2 ? cell.face * spec.thickness : cell.face;
  const std::size_t n = radius.size();
  SHARD_ASSERT(x.size() == n * static_cast<std::size_t>(cell.dim) && id.size() == n && material.size() == n,
               "sample arrays of " << n << " automata");
  ParticlePart part = make_automata(cell.dim, spec.plane, spec.thickness, std::move(materials), n);
  MCAState& s = mca_state(part);
  part.x = std::move(x);
  for (std::size_t i = 0; i < n; ++i) {
    part.id[i] = id[i];
    part.radius[i] = radius[i];
    part.material[i] = material[i];
    s.volume[i] = volume;
    s.face_area[i] = face;
  }
  return part;
}

void finish_sample(ParticlePart& ps, double bond_tolerance) {
  MCAState& s = mca_state(ps);
  if (s.pairs.count() > 0) {
    const EntityRemap none = EntityRemap::keeping(std::vector<std::uint8_t>(s.pairs.count(), 0));
    apply_particle_remap(ps, nullptr, &none, nullptr);
  }
  bond_neighbours(ps, bond_tolerance);
  compute_fabric(ps);
  finalize_automata(ps);
}

void assign_material(ParticlePart& ps, const std::function<bool(const double*)>& inside, int material) {
  SHARD_ASSERT(material >= 0 && material < static_cast<int>(mca_state(ps).materials.size()), "material " << material);
  for (std::size_t i = 0; i < ps.count(); ++i)
    if (inside(&ps.x[ps.dim * i])) ps.material[i] = material;
}

namespace {

void bounds(const ParticlePart& ps, double* lo, double* hi) {
  for (int a = 0; a < ps.dim; ++a) {
    lo[a] = 1e300;
    hi[a] = -1e300;
  }
  for (std::size_t i = 0; i < ps.count(); ++i)
    for (int a = 0; a < ps.dim; ++a) {
      lo[a] = std::min(lo[a], ps.coord(i, a));
      hi[a] = std::max(hi[a], ps.coord(i, a));
    }
}

double dist2(const ParticlePart& ps, std::size_t i, const double* c) {
  double s = 0;
  for (int a = 0; a < ps.dim; ++a) {
    const double dx = ps.coord(i, a) - c[a];
    s += dx * dx;
  }
  return s;
}

}  // namespace

int add_inclusions(ParticlePart& ps, const InclusionSpec& spec, double* fraction) {
  if (spec.volume_fraction <= 0 || spec.volume_fraction >= 1)
    throw InputError("inclusions: volume fraction must be in (0, 1)");
  std::mt19937_64 rng(spec.seed);
  double lo[3], hi[3];
  bounds(ps, lo, hi);
  const std::size_t n = ps.count();
  const std::size_t target = static_cast<std::size_t>(std::ceil(spec.volume_fraction * n));
  std::vector<std::array<double, 3>> centres;
  std::size_t marked = 0;
  for (std::size_t i = 0; i < n; ++i) marked += ps.material[i] == spec.material;
  int tries = 0;
  const double R = 0.5 * spec.diameter;
  while (marked < target && tries < spec.max_tries) {
    ++tries;
    std::array<double, 3> c{};
    for (int a = 0; a < 3; ++a) c[a] = a < ps.dim ? lo[a] + uniform01(rng) * (hi[a] - lo[a]) : 0.0;
    bool clear = true;
    for (const auto& o : centres) {
      double s = 0;
      for (int a = 0; a < ps.dim; ++a) s += (o[a] - c[a]) * (o[a] - c[a]);
      if (s < spec.diameter * spec.diameter) {
        clear = false;
        break;
      }
    }
    if (!clear) continue;
    centres.push_back(c);
    for (std::size_t i = 0; i < n; ++i) {
      double s = 0;
      for (int a = 0; a < ps.dim; ++a) s += (ps.coord(i, a) - c[a]) * (ps.coord(i, a) - c[a]);
      if (ps.material[i] != spec.material && s <= R * R) {
        ps.material[i] = spec.material;
        ++marked;
      }
    }
  }
  if (fraction) *fraction = n > 0 ? static_cast<double>(marked) / static_cast<double>(n) : 0.0;
  return static_cast<int>(centres.size());
}

int add_pores(ParticlePart& ps, const PoreSpec& spec) {
  if (spec.porosity <= 0 || spec.porosity >= 1) throw InputError("pores: porosity must be in (0, 1)");
  std::mt19937_64 rng(spec.seed);
  const std::size_t n = ps.count();
  std::vector<std::uint8_t> remove(n, 0);
  const std::size_t target = static_cast<std::size_t>(std::ceil(spec.porosity * n));
  std::size_t removed = 0;
  int pores = 0;
  for (int tries = 0; removed < target && tries < 100 * static_cast<int>(n); ++tries) {
    const std::size_t c = std::min(n - 1, static_cast<std::size_t>(uniform01(rng) * n));
    if (remove[c]) continue;
    ++pores;
    remove[c] = 1;
    ++removed;
    if (spec.with_neighbours) {
      const double reach = 1.1 * (2 * ps.radius[c]);
      for (std::size_t i = 0; i < n; ++i)
        if (!remove[i] && dist2(ps, i, &ps.x[ps.dim * c]) <= reach * reach) {
          remove[i] = 1;
          ++removed;
        }
    }
  }
  std::vector<std::uint8_t> keep(n);
  for (std::size_t i = 0; i < n; ++i) keep[i] = !remove[i];
  const EntityRemap removal = EntityRemap::keeping(keep);
  apply_particle_remap(ps, &removal, nullptr, nullptr);
  return pores;
}

int add_interphase(ParticlePart& ps, const InterphaseSpec& spec) {
  const int nm0 = static_cast<int>(mca_state(ps).materials.size());
  SHARD_ASSERT(spec.inclusion_material < nm0 && spec.matrix_material < nm0, "material index");
  if (spec.levels < 1 || spec.width <= 0) throw InputError("interphase: width and levels must be positive");
  // Inclusion automata sorted by x for a windowed nearest search.
  std::vector<std::pair<double, int>> incl;
  for (std::size_t i = 0; i < ps.count(); ++i)
    if (ps.material[i] == spec.inclusion_material) incl.emplace_back(ps.coord(i, 0), static_cast<int>(i));
  std::sort(incl.begin(), incl.end());
  std::vector<int> level(ps.count(), -1);
  int changed = 0;
  for (std::size_t i = 0; i < ps.count(); ++i) {
    if (ps.material[i] != spec.matrix_material) continue;
    const double reach = spec.width + (2 * ps.radius[i]);
    auto it = std::lower_bound(incl.begin(), incl.end(), std::make_pair(ps.coord(i, 0) - reach, -1));
    double best = 1e300;
    for (; it != incl.end() && it->first <= ps.coord(i, 0) + reach; ++it)
      best = std::min(best, std::sqrt(dist2(ps, i, &ps.x[ps.dim * it->second])));
    const double gap = best - (2 * ps.radius[i]);  // 0 for a direct neighbour of the inclusion
    if (gap < spec.width) {
      level[i] = std::min(spec.levels - 1, static_cast<int>(std::max(0.0, gap) / spec.width * spec.levels));
      ++changed;
    }
  }
  const int first = add_interphase_materials(ps, spec);
  for (std::size_t i = 0; i < ps.count(); ++i)
    if (level[i] >= 0) ps.material[i] = first + level[i];
  return changed;
}

int add_interphase_materials(ParticlePart& ps, const InterphaseSpec& spec) {
  const int nm0 = static_cast<int>(mca_state(ps).materials.size());
  SHARD_ASSERT(spec.inclusion_material < nm0 && spec.matrix_material < nm0, "material index");
  if (spec.levels < 1) throw InputError("interphase: levels must be positive");
  const MCAMaterial inc = mca_state(ps).materials[spec.inclusion_material];  // copies: materials grows below
  const MCAMaterial mat = mca_state(ps).materials[spec.matrix_material];
  const std::vector<int> old_laws = mca_state(ps).bond_law_of;
  for (int l = 0; l < spec.levels; ++l) {
    const double t = (l + 0.5) / spec.levels;  // 0: inclusion, 1: matrix
    MCAMaterial g = mat;
    g.name = mat.name + "_interphase_" + std::to_string(l);
    g.density = inc.density + t * (mat.density - inc.density);
    g.young = inc.young + t * (mat.young - inc.young);
    g.poisson = inc.poisson + t * (mat.poisson - inc.poisson);
    g.yield_stress = inc.yield_stress + t * (mat.yield_stress - inc.yield_stress);
    g.hardening = inc.hardening + t * (mat.hardening - inc.hardening);
    g.curve.clear();
    mca_state(ps).materials.push_back(g);
  }
  const int nm = static_cast<int>(mca_state(ps).materials.size());
  mca_state(ps).bond_law_of.assign(nm * nm, -1);
  auto old = [&](int a, int b) { return old_laws.empty() ? -1 : old_laws[a * nm0 + b]; };
  for (int a = 0; a < nm0; ++a)
    for (int b = 0; b < nm0; ++b) mca_state(ps).bond_law_of[a * nm + b] = old(a, b);
  const int interface_law = old(spec.matrix_material, spec.inclusion_material) >= 0
                                ? old(spec.matrix_material, spec.inclusion_material)
                                : old(spec.matrix_material, spec.matrix_material);
  for (int g = nm0; g < nm; ++g)
    for (int b = 0; b < nm; ++b) {
      mca_state(ps).bond_law_of[g * nm + b] = interface_law;
      mca_state(ps).bond_law_of[b * nm + g] = interface_law;
    }
  return nm0;
}

std::vector<int> boundary_layer(const ParticlePart& ps, int axis, bool at_max, double tol) {
  double lo[3], hi[3];
  bounds(ps, lo, hi);
  std::vector<int> out;
  for (std::size_t i = 0; i < ps.count(); ++i) {
    const double c = ps.coord(i, axis);
    if (at_max ? c >= hi[axis] - tol : c <= lo[axis] + tol) out.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace shard
