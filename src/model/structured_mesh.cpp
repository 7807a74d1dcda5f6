#include "model/structured_mesh.hpp"

#include <random>

#include "model/assembly.hpp"

namespace shard {

Model make_box_model(Formulation formulation, const BoxMesh& box) {
  Model model;
  model.formulation = formulation;
  const ElementType& type = element_type(box.element);
  const bool planar = type.dim == 2;
  const int dim = planar ? 2 : 3;
  model.nodes.dim = dim;
  const int nx = box.cells[0], ny = box.cells[1], nz = planar ? 0 : box.cells[2];
  const std::size_t count = static_cast<std::size_t>(nx + 1) * (ny + 1) * (nz + 1);
  model.nodes.resize(count);
  auto id = [&](int i, int j, int k) { return static_cast<std::int32_t>((k * (ny + 1) + j) * (nx + 1) + i); };
  const double h[3] = {box.size[0] / nx, box.size[1] / ny, planar ? 0.0 : box.size[2] / nz};
  std::mt19937 random(box.seed);
  // Uniform in [-1, 1] from the raw generator output: std::uniform_real_distribution is not the
  // same across standard libraries, the raw mt19937 sequence is.
  auto unit = [&]() { return 2.0 * (static_cast<double>(random()) / 4294967295.0) - 1.0; };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const std::int32_t n = id(i, j, k);
        const int idx[3] = {i, j, k};
        const int top[3] = {nx, ny, nz};
        bool interior = i > 0 && i < nx && j > 0 && j < ny && (planar || (k > 0 && k < nz));
        for (int c = 0; c < dim; ++c) {
          double x = idx[c] * h[c];
          if (interior && box.distortion > 0) x += box.distortion * h[c] * unit();
          (void)top;
          model.nodes.x0[dim * n + c] = x;
        }
      }
  model.nodes.x = model.nodes.x0;

  Part part;
  part.name = "body";
  part.type = &type;
  auto& cn = part.connectivity;
  if (planar) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::int32_t a = id(i, j, 0), b = id(i + 1, j, 0), c = id(i + 1, j + 1, 0), d = id(i, j + 1, 0);
        cn.insert(cn.end(), {a, b, c, a, c, d});
      }
  } else {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::int32_t v[8] = {id(i, j, k),         id(i + 1, j, k),     id(i + 1, j + 1, k),
                                     id(i, j + 1, k),     id(i, j, k + 1),     id(i + 1, j, k + 1),
                                     id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
          if (type.cell == CellType::tet4) {
            const int tets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                    {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
            for (const auto& t : tets) {
              std::int32_t q[4] = {v[t[0]], v[t[1]], v[t[2]], v[t[3]]};
              // orient to positive volume
              const double* X = model.nodes.x0.data();
              double e1[3], e2[3], e3[3];
              for (int c = 0; c < 3; ++c) {
                e1[c] = X[3 * q[1] + c] - X[3 * q[0] + c];
                e2[c] = X[3 * q[2] + c] - X[3 * q[0] + c];
                e3[c] = X[3 * q[3] + c] - X[3 * q[0] + c];
              }
              const double det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) -
                                 e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                                 e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
              if (det < 0) std::swap(q[1], q[2]);
              cn.insert(cn.end(), q, q + 4);
            }
          } else {
            cn.insert(cn.end(), v, v + 8);
          }
        }
  }
  model.parts.push_back(std::move(part));

  // Faces: node sets and facet sets (facets oriented later where loads need it).
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int face = 0; face < 2 * dim; ++face) {
    const int axis = face / 2;
    const int at = face % 2 == 0 ? 0 : box.cells[axis];
    NodeSet ns;
    ns.name = names[face];
    FacetSet fs;
    fs.name = names[face];
    fs.nodes_per_facet = planar ? 2 : 4;
    for (int k = 0; k <= nz; ++k)
      for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
          const int idx[3] = {i, j, k};
          if (idx[axis] == at) ns.nodes.push_back(id(i, j, k));
        }
    // facets
    const int u = (axis + 1) % dim, w = (axis + 2) % dim;
    if (planar) {
      const int other = 1 - axis;
      for (int s = 0; s < box.cells[other]; ++s) {
        int a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
        a[axis] = b[axis] = at;
        a[other] = s;
        b[other] = s + 1;
        fs.nodes.push_back(id(a[0], a[1], 0));
        fs.nodes.push_back(id(b[0], b[1], 0));
      }
    } else {
      for (int s = 0; s < box.cells[u]; ++s)
        for (int t = 0; t < box.cells[w]; ++t) {
          int c[4][3];
          const int du[4] = {0, 1, 1, 0}, dw[4] = {0, 0, 1, 1};
          for (int q = 0; q < 4; ++q) {
            c[q][axis] = at;
            c[q][u] = s + du[q];
            c[q][w] = t + dw[q];
            fs.nodes.push_back(id(c[q][0], c[q][1], c[q][2]));
          }
        }
    }
    find_facet_owners(model, fs);  // none for the quadrilaterals of a tet4 box
    model.node_sets.push_back(std::move(ns));
    model.facet_sets.push_back(std::move(fs));
  }
  model.next_node_id = static_cast<std::int64_t>(model.nodes.count());
  return model;
}

}  // namespace shard
