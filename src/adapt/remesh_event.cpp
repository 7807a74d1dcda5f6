#include "adapt/remesh_event.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "adapt/planar_mesh.hpp"
#include "adapt/size_field.hpp"
#include "contact/contact_surface.hpp"

namespace shard {

namespace {

std::string format(const char* pattern, double a, double b = 0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, pattern, a, b);
  return buffer;
}

std::vector<std::int32_t> all_elements(const Part& part) {
  std::vector<std::int32_t> e(part.element_count());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = static_cast<std::int32_t>(i);
  return e;
}

/// The crack-face nodes and the nodes of the part's elements that hold one.
std::vector<char> near_crack_nodes(const Part& part, const std::vector<char>& crack_face) {
  std::vector<char> near = crack_face;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    const std::int32_t* c = &part.connectivity[3 * e];
    if (crack_face[c[0]] || crack_face[c[1]] || crack_face[c[2]]) near[c[0]] = near[c[1]] = near[c[2]] = 1;
  }
  return near;
}

/// The nodes on part p's boundary: those of its faces no other face matches, but for the faces
/// at a subdomain's cut (Model::cut_faces), which are no boundary of the body (as for contact).
std::vector<char> boundary_nodes(const Model& model, std::size_t p) {
  const FaceGroups groups = group_faces(model);
  const auto& cut = model.cut_faces;
  std::vector<char> out(model.nodes.count(), 0);
  for (std::size_t k = 0; k < groups.group_count(); ++k) {
    if (groups.group_begin[k + 1] - groups.group_begin[k] != 1) continue;
    const FaceGroups::Face& face = groups.faces[groups.order[groups.group_begin[k]]];
    if (static_cast<std::size_t>(face.part) != p || std::binary_search(cut.begin(), cut.end(), FaceGroups::key(model, face)))
      continue;
    const Part& part = model.parts[p];
    for (const int local : part.type->faces[static_cast<std::size_t>(face.local)])
      out[part.connectivity[3 * static_cast<std::size_t>(face.element) + static_cast<std::size_t>(local)]] = 1;
  }
  return out;
}

/// Whether a remesh kept element e as it was (a patch where a boundary crosses itself or lips
/// could not be given back, a small fragment, or with keep_cracked an element on a crack face):
/// remesh_part marks it by a negative reference area. No remesh changes it while the cause lasts,
/// so its shape and size are not looked at, or it would ask for a remesh at every check.
bool kept_as_it_was(const Part& part, std::size_t e) {
  return part.shape_reference.size() >= 4 * (e + 1) && part.shape_reference[4 * e] < 0;
}

/// A corner's angle is poor when beyond min_angle or max_angle and, if the corner was made beyond
/// it too (the element's shape_reference), worse than made by a fifth (of the angle, or of π minus
/// it): a triangle made poor (by Gmsh between lip nodes kept as they are, or in the user's mesh)
/// would be made so again by a remesh, and would ask for one at every check; one that has become
/// poor since is what a remesh fixes. The smallest and largest poor angles go to `low` and `high`.
constexpr double kAngleWorsening = 0.8;

void poor_angles(const Part& part, const NodeArrays& nodes, std::size_t e, const RemeshTriggers& t, double& low,
                 double& high) {
  const std::int32_t* c = &part.connectivity[3 * e];
  const auto angles = triangle_angles(&nodes.x[2 * c[0]], &nodes.x[2 * c[1]], &nodes.x[2 * c[2]]);
  const bool made = part.shape_reference.size() >= 4 * (e + 1) && part.shape_reference[4 * e] > 0;
  for (int k = 0; k < 3; ++k) {
    const double a = angles[k], a0 = made ? part.shape_reference[4 * e + 1 + k] : 0.0, pi = std::numbers::pi;
    const bool made_small = made && a0 < t.min_angle, made_large = made && a0 > t.max_angle;
    if (t.min_angle > 0 && a < t.min_angle && (!made_small || a < kAngleWorsening * a0)) low = std::min(low, a);
    if (t.max_angle > 0 && a > t.max_angle && (!made_large || pi - a < kAngleWorsening * (pi - a0)))
      high = std::max(high, a);
  }
}

}  // namespace

RemeshEvent::RemeshEvent(const std::vector<std::unique_ptr<Material>>& materials, std::vector<RemeshedPart> parts,
                         RemeshTriggers triggers, std::vector<std::int64_t> kept_nodes)
    : parts_(std::move(parts)),
      triggers_(triggers),
      kept_nodes_(std::move(kept_nodes)),
      seconds_(parts_.size(), 0.0),
      kept_noted_(parts_.size(), 0) {
  for (const auto& m : materials) materials_.push_back(m.get());
}

std::vector<EnergyTerm> RemeshEvent::energy_terms() const {
  using G = EnergyGroup;
  return {{"remesh_elastic",
           "stored energy a remesh took from the elements (the carried stresses store less; negative: more)",
           energy_rank::eroded + 5, {{G::internal, -1}, {G::dissipated, +1}}, "remesh"},
          {"remesh_kinetic", "kinetic energy a remesh took from the nodes (the carried velocities on the new masses)",
           energy_rank::eroded + 6, {{G::dissipated, +1}}, "remesh"}};
}

RemeshEvent::Due RemeshEvent::due(const Model& model, std::size_t i, std::int64_t step) const {
  return assess(model, i, step, all_elements(model.parts[parts_[i].part]));
}

RemeshEvent::Due RemeshEvent::assess(const Model& model, std::size_t i, std::int64_t step,
                                     const std::vector<std::int32_t>& elements) const {
  const std::size_t p = parts_[i].part;
  const Part& part = model.parts[p];
  const std::int64_t last = p < model.remesh_step.size() ? model.remesh_step[p] : 0;
  if (triggers_.max_interval > 0 && step - last >= triggers_.max_interval)
    return {format("%.0f steps since the last remesh", static_cast<double>(step - last))};
  double worst = 0, smallest = std::numbers::pi, largest = 0;
  for (const std::int32_t e : elements) {
    if (kept_as_it_was(part, static_cast<std::size_t>(e))) continue;
    worst = std::max(worst, element_distortion(part, model.nodes, static_cast<std::size_t>(e)).value());
    poor_angles(part, model.nodes, static_cast<std::size_t>(e), triggers_, smallest, largest);
  }
  // A size mismatch asks for the whole part, so it is looked for before the shapes (which a
  // patch may fix).
  if (triggers_.size_mismatch > 0) {
    const ElementSizes sizes = element_target_sizes(part, elements, model.nodes, *materials_[part.material],
                                                    model.formulation, parts_[i].settings.size);
    // Elements whose size a remesh may not be able to change are not looked at, or they would
    // ask for one at every check. Too large: those with a node on a crack face (the lips are
    // kept node for node, and Gmsh grows the elements around a lip node from the lip's segments).
    // Too small: those on the boundary (which keeps its corners, the nodes where node sets or
    // prescribed motion change, and the lips, and coarsens only within a chord tolerance) or next
    // to a crack face.
    std::vector<char> crack_face, near_crack, boundary;
    for (std::size_t e = 0; e < sizes.target.size(); ++e) {
      const double ratio = sizes.current[e] / sizes.target[e];
      const bool too_large = ratio > triggers_.size_mismatch, too_small = ratio < 1.0 / triggers_.size_mismatch;
      if (!too_large && !too_small) continue;
      if (kept_as_it_was(part, static_cast<std::size_t>(elements[e]))) continue;  // a remesh keeps it again
      if (near_crack.empty()) {
        crack_face = model.crack_face_nodes();
        near_crack = near_crack_nodes(part, crack_face);
        boundary = boundary_nodes(model, p);
      }
      const std::int32_t* c = &part.connectivity[3 * static_cast<std::size_t>(elements[e])];
      if (too_large && (crack_face[c[0]] || crack_face[c[1]] || crack_face[c[2]])) continue;
      if (too_small && (boundary[c[0]] || boundary[c[1]] || boundary[c[2]])) continue;
      if (too_small && (near_crack[c[0]] || near_crack[c[1]] || near_crack[c[2]])) continue;
      return {format("an element %.2f times the size asked for (allowed %.2f)", ratio, triggers_.size_mismatch)};
    }
  }
  const double degree = std::numbers::pi / 180.0;
  if (triggers_.distortion > 0 && worst > triggers_.distortion)
    return {format("an element distorted by %.2f %% (allowed %.2f %%)", 100 * worst, 100 * triggers_.distortion), true};
  if (smallest < std::numbers::pi)
    return {format("an angle of %.1f deg (below %.1f)", smallest / degree, triggers_.min_angle / degree), true};
  if (largest > 0)
    return {format("an angle of %.1f deg (above %.1f)", largest / degree, triggers_.max_angle / degree), true};
  return {};
}

bool RemeshEvent::may_be_due(const Model& model, const std::vector<std::vector<std::int32_t>>& owned,
                             std::int64_t step) const {
  if (!checks(step)) return false;
  for (std::size_t i = 0; i < parts_.size(); ++i) {
    const std::size_t p = parts_[i].part;
    if (p < model.remesh_retry_step.size() && step < model.remesh_retry_step[p]) continue;
    // The energy-norm error is normalised over the whole part (eq. 6): a part of it cannot tell.
    if (triggers_.size_mismatch > 0 && parts_[i].settings.size.measure == SizeMeasure::error) return true;
    // Refined ahead, an element's target depends on elements around it that may be another rank's.
    if (triggers_.size_mismatch > 0 && parts_[i].settings.size.refine_ahead > 0) return true;
    if (!assess(model, i, step, owned[p]).why.empty()) return true;
  }
  return false;
}

std::vector<std::int32_t> RemeshEvent::poor_elements(const Model& model, std::size_t i) const {
  const Part& part = model.parts[parts_[i].part];
  std::vector<std::int32_t> out;
  for (std::size_t e = 0; e < part.element_count(); ++e) {
    if (kept_as_it_was(part, e)) continue;  // as in assess
    double low = std::numbers::pi, high = 0;
    poor_angles(part, model.nodes, e, triggers_, low, high);
    const bool poor = (triggers_.distortion > 0 && element_distortion(part, model.nodes, e).value() > triggers_.distortion) ||
                      low < std::numbers::pi || high > 0;
    if (poor) out.push_back(static_cast<std::int32_t>(e));
  }
  return out;
}

RemeshOutcome RemeshEvent::remesh(Model& model, std::size_t i, const Due& why, bool& local) {
  const std::size_t p = parts_[i].part;
  const Material& material = *materials_[model.parts[p].material];
  local = false;
  if (why.shape && triggers_.patch_rings > 0) {
    const std::vector<std::int32_t> patch = grow_patch(model, p, poor_elements(model, i), triggers_.patch_rings);
    if (!patch.empty() &&
        static_cast<double>(patch.size()) <= triggers_.patch_max_fraction * static_cast<double>(model.parts[p].element_count())) {
      RemeshOutcome out = remesh_patch(model, p, material, parts_[i].settings, patch, kept_nodes_, triggers_.min_angle);
      if (out.remeshed) {
        local = true;
        return out;
      }
      notes_.push_back("part '" + model.parts[p].name + "': a patch of " + std::to_string(patch.size()) +
                       " elements was not remeshed (" + out.skipped + "); the whole part is remeshed instead");
    }
  }
  return remesh_part(model, p, material, parts_[i].settings, kept_nodes_);
}

void RemeshEvent::size_records(Model& model) const {
  for (auto* record : {&model.remesh_count, &model.remesh_step, &model.remesh_local_count, &model.remesh_failures,
                       &model.remesh_retry_step})
    record->resize(model.parts.size(), 0);
}

void RemeshEvent::copy_records(const Model& from, Model& to) {
  to.remesh_count = from.remesh_count;
  to.remesh_step = from.remesh_step;
  to.remesh_local_count = from.remesh_local_count;
  to.remesh_failures = from.remesh_failures;
  to.remesh_retry_step = from.remesh_retry_step;
}

void RemeshEvent::measure_new_elements(Model& model) const {
  for (const RemeshedPart& r : parts_) {
    Part& part = model.parts[r.part];
    // Elements made since the last look (the first step) are measured now.
    if (part.shape_reference.size() != 4 * part.element_count())
      measure_reference_shape(part, model.nodes, part.shape_reference);
  }
}

void RemeshEvent::run(Model& model, EventContext& context) {
  size_records(model);
  measure_new_elements(model);
  if (!checks(context.step)) return;
  bool changed = false;
  for (std::size_t i = 0; i < parts_.size(); ++i) {
    const std::size_t p = parts_[i].part;
    // Elements eroded in this step leave at its end (the solver's compaction, after this event):
    // the part is assessed at the next check.
    const auto& eroded = model.parts[p].eroded;
    if (std::find(eroded.begin(), eroded.end(), 1) != eroded.end()) continue;
    if (context.step < model.remesh_retry_step[p]) continue;  // backing off after a failure
    const Due why_due = due(model, i, context.step);
    const std::string& why = why_due.why;
    if (why.empty()) continue;
    const auto start = std::chrono::steady_clock::now();
    bool local = false;
    const RemeshOutcome out = remesh(model, i, why_due, local);
    seconds_[i] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!out.remeshed) {
      // What failed once will mostly fail again on a mesh that has hardly changed, and a failed
      // remesh of a large cracked part can cost as much as a thousand steps: the next attempt
      // waits twice as long as the one before (up to 64 checks).
      const std::int64_t failures = ++model.remesh_failures[p];
      model.remesh_retry_step[p] = context.step + (triggers_.check_interval << std::min<std::int64_t>(failures, 6));
      notes_.push_back("part '" + model.parts[p].name + "' not remeshed at step " + std::to_string(context.step) +
                       " (t = " + format("%.6g s", context.time) + "), due to " + why + ": " + out.skipped +
                       "; not assessed again before step " + std::to_string(model.remesh_retry_step[p]));
      continue;
    }
    if (out.bodies_kept > 0 && !kept_noted_[i]) {
      kept_noted_[i] = 1;
      notes_.push_back("the remesh of part '" + model.parts[p].name + "' at step " + std::to_string(context.step) +
                       " kept " + std::to_string(out.elements_kept) + " elements (" + std::to_string(out.bodies_kept) +
                       (out.bodies_kept == 1 ? " patch" : " patches") +
                       ") as they were, where its boundary crosses itself (crack faces pressed into each "
                       "other, or a fragment folded over), which Gmsh cannot mesh, or where a closed crack's lips "
                       "turned a new triangle over or Gmsh made a sliver; later remeshes that do the same are not "
                       "noted");
    }
    model.remesh_failures[p] = 0;
    model.remesh_retry_step[p] = 0;
    changed = true;
    model.remesh_count[p]++;
    model.remesh_local_count[p] += local;
    if (!local) model.remesh_step[p] = context.step;  // max_interval counts whole-part remeshes
    const double elastic = out.stored_before - out.stored_after, kinetic = out.kinetic_before - out.kinetic_after;
    context.energy.at("remesh_elastic") += elastic;
    context.energy.at("remesh_kinetic") += kinetic;
    // Booked, the balance closes whatever a remesh changed; a change of more than 1 % of the
    // energy in play is a transfer gone wrong, and the log says so.
    const EnergyLedger& E = context.energy;
    const double scale = std::max({std::abs(E.initial()), std::abs(E.external()),
                                   E.kinetic() + std::abs(E.internal()) + E.dissipated()});
    if (std::abs(elastic + kinetic) > 0.01 * scale)
      notes_.push_back("the remesh of part '" + model.parts[p].name + "' at step " + std::to_string(context.step) +
                       format(" changed the stored and kinetic energy by %.4g J (%.3g %% of the energy in play)",
                              -(elastic + kinetic), 100 * std::abs(elastic + kinetic) / scale) +
                       ": booked as remesh, but look at the frames around it");
    if (context.part_stored && p < context.part_stored->size()) (*context.part_stored)[p] -= elastic;
  }
  if (!changed) return;
  rebuild_penalty(model.contact);
  context.topology.changed(model, Remap{});
}

void RemeshEvent::rebuild_penalty(ContactState& contact) {
  // The contact penalty is built on the element step of the first step with contact and on the
  // masses of the nodes it joins (docs/theory/contact.md, "Normal force: penalty"). New elements
  // have their own step: kept, the old one would make the springs of a refined surface as much
  // softer as its nodes are lighter, and bodies in contact would sink into each other. The next
  // step builds it again.
  contact.penalty_time_step.clear();
}

std::vector<std::string> RemeshEvent::take_notes() {
  std::vector<std::string> out;
  out.swap(notes_);
  return out;
}

std::vector<double> RemeshEvent::distortion(const Model& model, std::size_t part) const {
  std::vector<double> out;
  for (const RemeshedPart& r : parts_)
    if (r.part == part)
      for (std::size_t e = 0; e < model.parts[part].element_count(); ++e)
        out.push_back(element_distortion(model.parts[part], model.nodes, e).value());
  return out;
}

std::vector<double> RemeshEvent::target_size(const Model& model, std::size_t part) const {
  for (const RemeshedPart& r : parts_)
    if (r.part == part) {
      const Part& p = model.parts[part];
      return element_target_sizes(p, all_elements(p), model.nodes, *materials_[p.material], model.formulation,
                                  r.settings.size)
          .target;
    }
  return {};
}

}  // namespace shard
