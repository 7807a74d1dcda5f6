#include "io/frame_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shard {

namespace {
bool wants(const std::vector<std::string>& fields, const char* name) {
  return std::find(fields.begin(), fields.end(), name) != fields.end();
}
}  // namespace

VtuGrid make_frame(const Model& model, const std::vector<std::unique_ptr<Material>>& materials,
                   const std::vector<std::string>& fields, double time, bool cracking) {
  VtuGrid grid;
  const int dim = model.dim();
  const std::size_t nn = model.nodes.count();
  grid.points.assign(3 * nn, 0.0);
  for (std::size_t i = 0; i < nn; ++i)
    for (int k = 0; k < dim; ++k) grid.points[3 * i + k] = model.nodes.x[dim * i + k];

  std::size_t ne = 0;
  for (const auto& p : model.parts) ne += p.element_count();
  grid.offsets.reserve(ne);
  grid.types.reserve(ne);
  for (const auto& part : model.parts) {
    const int npe = part.type->nodes;
    const auto type = static_cast<VtkCellType>(part.type->vtk_cell);
    for (std::size_t e = 0; e < part.element_count(); ++e) {
      for (int a = 0; a < npe; ++a) grid.connectivity.push_back(part.connectivity[npe * e + a]);
      grid.offsets.push_back(static_cast<std::int64_t>(grid.connectivity.size()));
      grid.types.push_back(type);
    }
  }

  auto point_vector = [&](const char* name, auto value) {
    VtuField f{name, 3, std::vector<double>(3 * nn, 0.0)};
    for (std::size_t i = 0; i < nn; ++i)
      for (int k = 0; k < dim; ++k) f.values[3 * i + k] = value(dim * i + k);
    grid.point_fields.push_back(std::move(f));
  };
  if (wants(fields, "displacement"))
    point_vector("displacement", [&](std::size_t d) { return model.nodes.x[d] - model.nodes.x0[d]; });
  if (wants(fields, "velocity"))
    point_vector("velocity", [&](std::size_t d) { return model.nodes.v[d]; });
  if (cracking) {
    // 1 on the nodes of crack faces (the copies and their origins), so that a threshold on it in
    // ParaView shows the crack paths; written from the first frame on (all 0 then), so that
    // ParaView offers it for the whole series.
    const std::vector<char> on_face = model.crack_face_nodes();
    grid.point_fields.push_back({"crack_face", 1, std::vector<double>(on_face.begin(), on_face.end())});
    // The time a crack reached each node: along a crack path, edge length over the difference of
    // its ends' times is the speed of the tip that crossed it. And the speed of the tip that
    // reached each node (0 where a crack started). The model keeps −1 for a node no crack has
    // reached; the frames write NaN there, since there is no such time or speed.
    const double none = std::numeric_limits<double>::quiet_NaN();
    auto reached_or_none = [&](const std::vector<double>& values) {
      std::vector<double> out(nn, none);
      for (std::size_t i = 0; i < values.size() && i < nn; ++i)
        if (values[i] >= 0.0) out[i] = values[i];
      return out;
    };
    grid.point_fields.push_back({"crack_time", 1, reached_or_none(model.nodes.crack_time)});
    grid.point_fields.push_back({"crack_speed", 1, reached_or_none(model.nodes.crack_speed)});
  }

  if (model.cohesive.element_count() > 0) {
    // The largest damage of the interface points at each node (NaN off the interfaces, where
    // there is none): a threshold at 1 shows where the plies have come apart.
    const std::vector<std::int32_t> index = index_of_ids(model.nodes.id, model.next_node_id);
    std::vector<double> damage(model.nodes.count(), std::numeric_limits<double>::quiet_NaN());
    const CohesiveElements& c = model.cohesive;
    for (std::size_t p = 0; p < c.point_count(); ++p)
      for (const std::int64_t id : {c.node_a[p], c.node_b[p]}) {
        const std::int32_t i = id >= 0 && id < model.next_node_id ? index[static_cast<std::size_t>(id)] : -1;
        if (i >= 0) damage[i] = std::isnan(damage[i]) ? c.damage[p] : std::max(damage[i], c.damage[p]);
      }
    grid.point_fields.push_back({"interface_damage", 1, std::move(damage)});
  }

  // Cell fields: the mean over each element's integration points.
  auto cell_field = [&](const char* name, int components, auto per_point) {
    VtuField f{name, components, {}};
    f.values.reserve(components * ne);
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      const Part& part = model.parts[p];
      const int npts = part.type->points;
      for (std::size_t e = 0; e < part.element_count(); ++e)
        for (int c = 0; c < components; ++c) {
          double sum = 0;
          for (int q = 0; q < npts; ++q) sum += per_point(p, part, npts * e + q, c);
          f.values.push_back(sum / npts);
        }
    }
    grid.cell_fields.push_back(std::move(f));
  };
  auto tensor = [](const std::vector<double>& a) {
    return [&a](std::size_t, const Part&, std::size_t q, int c) { return a[kTensorSize * q + c]; };
  };
  if (wants(fields, "stress"))
    cell_field("stress", 6, [](std::size_t, const Part& part, std::size_t q, int c) {
      return part.stress[kTensorSize * q + c];
    });
  if (wants(fields, "strain"))
    cell_field("strain", 6, [](std::size_t, const Part& part, std::size_t q, int c) {
      return part.strain[kTensorSize * q + c];
    });
  (void)tensor;
  if (wants(fields, "von_mises"))
    cell_field("von_mises", 1, [](std::size_t, const Part& part, std::size_t q, int) {
      const double* s = &part.stress[kTensorSize * q];
      const double j2 = ((s[xx] - s[yy]) * (s[xx] - s[yy]) + (s[yy] - s[zz]) * (s[yy] - s[zz]) +
                         (s[zz] - s[xx]) * (s[zz] - s[xx])) / 6.0 +
                        s[xy] * s[xy] + s[yz] * s[yz] + s[zx] * s[zx];
      return std::sqrt(3.0 * j2);
    });
  if (wants(fields, "pressure"))
    cell_field("pressure", 1, [](std::size_t, const Part& part, std::size_t q, int) {
      const double* s = &part.stress[kTensorSize * q];
      return -(s[xx] + s[yy] + s[zz]) / 3.0;
    });
  if (wants(fields, "temperature"))
    cell_field("temperature", 1, [](std::size_t, const Part& part, std::size_t q, int) {
      return part.temperature[q];
    });
  if (wants(fields, "part"))
    cell_field("part", 1, [](std::size_t p, const Part&, std::size_t, int) { return static_cast<double>(p); });
  {
    // One field per history variable name ("state": all of them, or those named in `fields`);
    // NaN in parts whose material lacks it: there is no such quantity there, and a zero would
    // read as a value (a failure factor of 0, "intact", in a material that has none).
    const bool all = wants(fields, "state");
    std::vector<std::string> names;
    for (const auto& part : model.parts)
      for (const auto& n : materials[part.material]->state_names())
        if ((all || wants(fields, n.c_str())) && std::find(names.begin(), names.end(), n) == names.end())
          names.push_back(n);
    for (const auto& name : names) {
      // Slot of the variable in each part's state (−1: absent), found once per field.
      std::vector<int> slot, stride;
      for (const auto& part : model.parts) {
        const auto own = materials[part.material]->state_names();
        const auto it = std::find(own.begin(), own.end(), name);
        slot.push_back(it == own.end() ? -1 : static_cast<int>(it - own.begin()));
        stride.push_back(static_cast<int>(own.size()));
      }
      cell_field(name.c_str(), 1, [&](std::size_t p, const Part& part, std::size_t q, int) {
        if (slot[p] < 0) return std::numeric_limits<double>::quiet_NaN();
        return part.state[static_cast<std::size_t>(stride[p]) * q + static_cast<std::size_t>(slot[p])];
      });
    }
  }
  grid.field_data.push_back({"TimeValue", 1, {time}});
  return grid;
}

}  // namespace shard
