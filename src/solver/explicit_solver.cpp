#include "solver/explicit_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "solver/erosion.hpp"
#include "solver/integrator.hpp"
#include "solver/particle_integration.hpp"

namespace shard {

namespace {
/// Nodes per chunk of the nodal update. Sums are formed per chunk and then added in chunk order,
/// so the energies are the same, bit for bit, for any number of threads.
constexpr std::size_t kNodeChunk = 2048;

[[noreturn]] void inverted_element(const Model& model, const Part& part, std::int64_t element, double time,
                                   std::int64_t step) {
  const int npe = part.type->nodes;
  std::ostringstream out;
  out << "element " << element << " of part '" << part.name << "' turned inside out (volume <= 0) at t = " << time
      << " s, step " << step << "; its nodes are at";
  for (int a = 0; a < npe; ++a) {
    const auto n = part.connectivity[npe * element + a];
    out << " (";
    for (int k = 0; k < model.dim(); ++k) out << (k ? ", " : "") << model.nodes.x[model.dim() * n + k];
    out << ")";
  }
  out << ". Usual causes: a time step too large (lower analysis.time_step_safety), too little "
         "hourglass control, or a load beyond what the mesh can follow";
  throw RunError(out.str());
}
}  // namespace

void lump_masses(Model& model, const std::vector<std::unique_ptr<Material>>& materials) {
  for (const Part& part : model.parts)
    add_lumped_masses(part, model.nodes, materials[part.material]->density(), model.formulation,
                      model.thickness, model.nodes.mass);
}

std::vector<EnergyTerm> solver_energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"kinetic", "½ m v² at the last full step (v: the half steps' velocities interpolated to it), rotation included", r::kinetic,
           {{G::kinetic, +1}}, ""},
          {"initial", "kinetic energy at t = 0 (the models start stress-free)", r::initial, {{G::initial, +1}}, "-"},
          {"external_work", "work of loads, prescribed motion, moving walls and gravity", r::external_work,
           {{G::external, +1}}, ""},
          {"damping", "dissipated by mass-proportional damping", r::damping, {{G::dissipated, +1}}, ""}};
}

std::vector<EnergyTerm> particle_energy_terms() {
  using G = EnergyGroup;
  namespace r = energy_rank;
  return {{"particle_elastic", "elastic energy the particles' models store now (automata and their pairs)",
           r::particle_elastic, {{G::internal, +1}}, "-"},
          {"particle_friction", "dissipated by sliding between particles (unlinked pairs of automata)",
           r::particle_friction, {{G::dissipated, +1}}, "friction"}};
}

std::vector<EnergyTerm> particle_model_energy_terms() {
  using G = EnergyGroup;
  return {{"automata_many_body_work",
           "work the automata's many-body force took from the motion beyond the energy it stores (its "
           "non-conservative part; negative: it gave energy)",
           energy_rank::particle_many_body, {{G::dissipated, +1}}, ""}};
}

ExplicitSolver::ExplicitSolver(Model& model,
                               const std::vector<std::unique_ptr<Material>>& materials,
                               const Loads& loads, SolverSettings settings)
    : model_(model), materials_(materials), loads_(loads), settings_(settings) {
  // The ledger: each piece that does work registers its terms (the contact on attaching).
  EnergyLedger& E = state_.energy;
  for (auto* terms : {solver_energy_terms, element_energy_terms, particle_energy_terms})
    for (auto& t : terms()) E.add(std::move(t));
  terms_ = {E.find("kinetic"),  E.find("initial"),   E.find("external_work"), E.find("damping"),
            E.find("stress_work"), E.find("viscosity"), E.find("hourglass"), E.find("plastic"),
            E.find("heat"),     E.find("fracture"),  E.find("eroded"),       E.find("particle_elastic"),
            E.find("particle_friction")};
  // Runs with a particle model (the automata) book the work of its many-body term.
  if (std::any_of(model_.particle_parts.begin(), model_.particle_parts.end(),
                  [](const ParticlePart& p) { return static_cast<bool>(p.model); })) {
    for (auto& t : particle_model_energy_terms()) E.add(std::move(t));
    terms_.particle_many_body = E.find("automata_many_body_work");
  }
  if (std::any_of(model_.parts.begin(), model_.parts.end(), [](const Part& p) { return p.erosion.to_particles; })) {
    for (auto& t : ErosionCompaction::conversion_energy_terms()) E.add(std::move(t));
    terms_.conversion_elastic = E.find("conversion_elastic");
  }
  topology_.add(*this);
  topology_changed(model_, Remap{});
  // The solver's own event: every run compacts eroded elements, after the events a scenario asks
  // for (crack growth, the automata's contact search), so that what they erode leaves in the
  // same step.
  if (settings_.compact_eroded_elements) own_events_.push_back(std::make_unique<ErosionCompaction>(materials_));
}

ExplicitSolver::~ExplicitSolver() = default;

void ExplicitSolver::restored() {
  for (ParticlePart& part : model_.particle_parts) {
    if (part.model) part.model->after_change(part);
    part.stable_time_step = 0;
  }
  model_.particle_contacts.restored();
  topology_.reset(model_);
}

void ExplicitSolver::attach_contact(ContactSystem* contact) {
  if (contact_) topology_.remove(*contact_);
  contact_ = contact;
  if (!contact_) return;
  topology_.add(*contact_);
  for (auto& t : ContactSystem::energy_terms()) state_.energy.add(std::move(t));
  terms_.wall_work = state_.energy.find("wall_work");
  terms_.contact_work = state_.energy.find("contact_work");
  terms_.friction = state_.energy.find("friction");
  terms_.contact_damping = state_.energy.find("contact_damping");
}

void ExplicitSolver::attach_particle_contact(ParticleContact* contact) {
  if (particle_contact_) topology_.remove(*particle_contact_);
  particle_contact_ = contact;
  if (!particle_contact_) return;
  topology_.add(*particle_contact_);
  const int history = ParticleContact::history_size(*particle_contact_->settings().law);
  if (model_.particle_contacts.history_size() != history) model_.particle_contacts = InteractionList(history);
  for (auto& t : ParticleContact::energy_terms()) state_.energy.add(std::move(t));
  terms_.particle_contact_elastic = state_.energy.find("particle_contact_elastic");
  terms_.particle_contact_dissipation = state_.energy.find("particle_contact_dissipation");
  terms_.particle_wall_work = state_.energy.find("particle_wall_work");
}

void ExplicitSolver::attach_cohesive(CohesiveInterfaces* cohesive) {
  if (cohesive_) topology_.remove(*cohesive_);
  cohesive_ = cohesive;
  if (!cohesive_) return;
  topology_.add(*cohesive_);
  for (auto& t : CohesiveInterfaces::energy_terms()) state_.energy.add(std::move(t));
  terms_.cohesive_work = state_.energy.find("cohesive_work");
  terms_.cohesive_released = state_.energy.find("cohesive_released");
}

void ExplicitSolver::topology_changed(const Model& model, const Remap&) {
  // Non-local neighbourhoods are checked against the points' reference positions every step
  // (split nodes keep them): kept unless parts come or go.
  part_caches_.resize(model.parts.size());
  node_dofs_ = prescribed_node_dofs(model);
  particle_dofs_.clear();
  for (const ParticlePart& pp : model.particle_parts) particle_dofs_.push_back(prescribed_particle_dofs(pp));
}

void ExplicitSolver::initialise() {
  topology_changed(model_, Remap{});  // prescriptions may have been added since construction
  std::fill(model_.nodes.mass.begin(), model_.nodes.mass.end(), 0.0);
  lump_masses(model_, materials_);
  const int dim = model_.dim();
  // Prescribed velocities hold from t = 0: they are part of the initial state, so the initial
  // kinetic energy includes them and no impulsive jump happens in the first step.
  for (const auto& c : node_dofs_) {
    const Prescription& p = loads_.prescriptions[c.prescription];
    const double value = loads_.tables[p.table].at(0.0);
    const std::size_t slot = static_cast<std::size_t>(dim) * c.point + c.component;
    model_.nodes.v[slot] =
        p.rotation < 0 ? value : rigid_velocity(loads_.rotations[p.rotation], value, &model_.nodes.x[slot - c.component], dim, c.component);
  }
  for (std::size_t i = 0; i < model_.nodes.count(); ++i) {
    const double m = model_.nodes.mass[i];
    if (!(m > 0)) {
      std::ostringstream out;
      out << "node " << i << " at (" << model_.nodes.x[dim * i] << ", " << model_.nodes.x[dim * i + 1]
          << ") has no mass: it belongs to no element of any part (a boundary group node "
             "outside the parts?)";
      throw RunError(out.str());
    }
  }
  for (std::size_t p = 0; p < model_.particle_parts.size(); ++p) {
    const MovingPoints points = moving_points(model_.particle_parts[p]);
    for (const auto& c : particle_dofs_[p])
      dof_of(points, c).velocity = loads_.tables[loads_.prescriptions[c.prescription].table].at(0.0);
  }
  ExactSum exact_kinetic = kinetic_energy(moving_points(model_));
  for (const ParticlePart& pp : model_.particle_parts) exact_kinetic += kinetic_energy(pp);
  sum_over_ranks(&exact_kinetic, 1);
  const double kinetic = exact_kinetic.value();
  EnergyLedger ledger = std::move(state_.energy);  // the registered terms stay
  ledger.clear();
  state_ = SolverState{};
  state_.energy = std::move(ledger);
  state_.energy[terms_.initial] = kinetic;
  state_.energy[terms_.kinetic] = kinetic;
}

bool ExplicitSolver::finished() const {
  return state_.time >= settings_.end_time * (1.0 - 1e-12);
}

void ExplicitSolver::add_element_forces(ForceSums& total) {
  StepContext ctx;
  ctx.formulation = model_.formulation;
  ctx.thickness = model_.thickness;
  ctx.dt = state_.dt_half;
  ctx.q_linear = settings_.q_linear;
  ctx.q_quadratic = settings_.q_quadratic;
  ctx.q_length = settings_.q_length;
  const std::size_t parts = model_.parts.size();
  part_caches_.resize(parts);
  state_.part_stored.resize(parts, 0.0);
  std::vector<ForceSums> part_sums(parts);
  for (std::size_t p = 0; p < parts; ++p) {
    Part& part = model_.parts[p];
    part_sums[p] = add_internal_forces(part, *materials_[part.material], model_.nodes, ctx, part_caches_[p]);
    if (part_sums[p].inverted_element >= 0)
      inverted_element(model_, part, part_sums[p].inverted_element, state_.time, state_.step);
  }
  if (global_sum_) sum_part_sums_over_ranks(part_sums);
  for (std::size_t p = 0; p < parts; ++p) {
    ForceSums& sums = part_sums[p];
    // The part's share of the internal group (stress_work − plastic − fracture − eroded or
    // conversion_elastic), booked in the same order as the ledger's terms.
    state_.part_stored[p] += sums.stress_work.value() - sums.plastic_work.value() - sums.fracture_work.value() -
                             sums.eroded_energy.value();
    if (model_.parts[p].erosion.to_particles) {
      // Elements that become particles: their elastic energy is a conversion term, not erosion.
      state_.energy[terms_.conversion_elastic] += sums.eroded_energy.value();
      sums.eroded_energy = ExactSum();
    }
    total.add(sums);
  }
  auto& E = state_.energy;
  E[terms_.stress_work] += total.stress_work.value();
  E[terms_.viscosity] += total.viscous_work.value();
  E[terms_.hourglass] += total.hourglass_work.value();
  E[terms_.plastic] += total.plastic_work.value();
  E[terms_.fracture] += total.fracture_work.value();
  E[terms_.heat] += total.heat.value();
  E[terms_.eroded] += total.eroded_energy.value();
}

void ExplicitSolver::sum_part_sums_over_ranks(std::vector<ForceSums>& part_sums) {
  // Seven exact sums per part, and its count of eroded elements, in one message.
  std::vector<ExactSum> sums;
  std::vector<std::int64_t> counts;
  for (const ForceSums& s : part_sums) {
    sums.insert(sums.end(), {s.stress_work, s.viscous_work, s.hourglass_work, s.plastic_work, s.fracture_work, s.heat,
                             s.eroded_energy});
    counts.push_back(s.eroded_elements);
  }
  sum_over_ranks(sums.data(), sums.size(), counts.data(), counts.size());
  for (std::size_t p = 0; p < part_sums.size(); ++p) {
    ForceSums& s = part_sums[p];
    const ExactSum* q = &sums[7 * p];
    s.stress_work = q[0], s.viscous_work = q[1], s.hourglass_work = q[2], s.plastic_work = q[3];
    s.fracture_work = q[4], s.heat = q[5], s.eroded_energy = q[6];
    s.eroded_elements = counts[p];
  }
}

void ExplicitSolver::sum_advance_over_ranks(AdvanceSums& sums, ContactWork& contact) {
  // The step's energy sums, then the reactions and work of the node groups, in one message.
  std::vector<ExactSum> all{sums.kinetic,          sums.damp_back,          sums.damp_ahead,
                            sums.external_back,    sums.external_ahead,     contact.contact_back,
                            contact.contact_ahead, contact.damping_back,    contact.damping_ahead};
  all.insert(all.end(), node_reaction_sums_.begin(), node_reaction_sums_.end());
  all.insert(all.end(), node_work_sums_.begin(), node_work_sums_.end());
  all.insert(all.end(), particle_reaction_sums_.begin(), particle_reaction_sums_.end());
  sum_over_ranks(all.data(), all.size());
  sums.kinetic = all[0], sums.damp_back = all[1], sums.damp_ahead = all[2];
  sums.external_back = all[3], sums.external_ahead = all[4];
  contact.contact_back = all[5], contact.contact_ahead = all[6], contact.damping_back = all[7];
  contact.damping_ahead = all[8];
  constexpr std::size_t first = 9;
  const std::size_t r = node_reaction_sums_.size();
  node_reactions_.resize(r);
  node_work_.resize(node_work_sums_.size());
  for (std::size_t i = 0; i < r; ++i) node_reactions_[i] = all[first + i].value();
  for (std::size_t i = 0; i < node_work_.size(); ++i) node_work_[i] = all[first + r + i].value();
  const std::size_t w = first + r + node_work_.size();
  particle_reactions_.resize(particle_reaction_sums_.size());
  for (std::size_t i = 0; i < particle_reactions_.size(); ++i) particle_reactions_[i] = all[w + i].value();
}

void ExplicitSolver::sum_over_ranks(ExactSum* sums, std::size_t count, std::int64_t* counts, std::size_t n_counts) {
  if (!global_sum_) return;
  constexpr auto W = static_cast<std::size_t>(ExactSum::kWords);
  std::vector<std::int64_t> words(W * count + n_counts);
  for (std::size_t i = 0; i < count; ++i) {
    const auto w = sums[i].words();
    std::copy(w.begin(), w.end(), words.begin() + static_cast<std::ptrdiff_t>(W * i));
  }
  std::copy(counts, counts + n_counts, words.begin() + static_cast<std::ptrdiff_t>(W * count));
  global_sum_(words.data(), static_cast<int>(words.size()));
  for (std::size_t i = 0; i < count; ++i) sums[i] = ExactSum::from_words(&words[W * i]);
  std::copy(words.begin() + static_cast<std::ptrdiff_t>(W * count), words.end(), counts);
}

namespace {
constexpr std::size_t kParticleTerms = 5;  // per part: plastic, fracture, friction, many-body work, stored
}  // namespace

double ExplicitSolver::add_particle_forces() {
  // Particle parts: forces at t_n, the dissipation of the increment, the stored elastic energy
  // (a state function) and each part's limit on the next step; then the contacts of particles,
  // which come after the models' forces (those start from zero). The sums are exact, over the
  // particles, pairs and contacts this process books: a decomposed run adds them up over its
  // ranks, in one message per step.
  double particle_dt = std::numeric_limits<double>::infinity();
  const std::size_t parts = model_.particle_parts.size();
  std::vector<ExactSum> sums(kParticleTerms * parts);
  for (std::size_t ip = 0; ip < parts; ++ip) {
    ParticlePart& pp = model_.particle_parts[ip];
    ParticleWork d = particle_forces(pp, state_.step, state_.dt_half, settings_.gravity);
    if (pp.model && !d.has_stored) d.stored = pp.model->stored_energy(pp);
    ExactSum* s = &sums[kParticleTerms * ip];
    s[0] = d.plastic, s[1] = d.fracture, s[2] = d.friction, s[3] = d.many_body_work, s[4] = d.stored;
    if (pp.count() > 0) particle_dt = std::min(particle_dt, particle_time_step_limit(pp));
  }
  if (particle_contact_) {
    const ParticleContactWork w = particle_contact_->add_forces(model_, state_.time, state_.dt_half);
    sums.push_back(w.stored);
    sums.push_back(w.dissipated);
    sums.insert(sums.end(), w.wall_force.begin(), w.wall_force.end());
    particle_dt = std::min(particle_dt, particle_contact_->stable_time_step(model_));
  }
  if (!sums.empty()) sum_over_ranks(sums.data(), sums.size());
  book_particle_sums(sums);
  return particle_dt;
}

void ExplicitSolver::book_particle_sums(const std::vector<ExactSum>& sums) {
  auto& E = state_.energy;
  const std::size_t parts = model_.particle_parts.size();
  state_.particle_part_stored.assign(parts, 0.0);
  double particle_elastic = 0;
  for (std::size_t ip = 0; ip < parts; ++ip) {
    const ExactSum* s = &sums[kParticleTerms * ip];
    const double plastic = s[0].value(), fracture = s[1].value();
    // The pair forces did the plastic and breaking work beyond what they store: stress work.
    E[terms_.stress_work] += plastic + fracture;
    E[terms_.plastic] += plastic;
    E[terms_.fracture] += fracture;
    E[terms_.particle_friction] += s[2].value();
    if (terms_.particle_many_body >= 0) E[terms_.particle_many_body] += s[3].value();
    state_.particle_part_stored[ip] = s[4].value();
    particle_elastic += state_.particle_part_stored[ip];
  }
  E[terms_.particle_elastic] = particle_elastic;
  if (!particle_contact_) return;
  const std::size_t c = kParticleTerms * parts, walls = sums.size() - c - 2;
  E[terms_.particle_contact_elastic] = sums[c].value();
  E[terms_.particle_contact_dissipation] += sums[c + 1].value();
  state_.particle_wall_force_on_bodies.assign(walls, 0.0);
  for (std::size_t i = 0; i < walls; ++i) state_.particle_wall_force_on_bodies[i] = -sums[c + 2 + i].value();
}

void ExplicitSolver::compute_forces() {
  auto& nodes = model_.nodes;
  std::fill(nodes.force.begin(), nodes.force.end(), 0.0);
  ForceSums total;
  add_element_forces(total);
  if (total.eroded_elements > 0) {
    state_.eroded_elements += total.eroded_elements;
    // The eroded elements' faces leave the contact surfaces (of the elements and of the
    // particles) and the faces they covered join them now; the elements themselves leave the
    // part at the end of the step (ErosionEvent).
    topology_.changed(model_, Remap{});
  }
  // A decomposed run: the whole model's element step, before the interfaces' and contact's
  // bounds are built on it, and once elements erode (a rank may then hold none that is live).
  if (global_minimum_ && (cohesive_ || contact_ || state_.eroded_elements > 0)) global_minimum_(&total.stable_dt, 1);
  const double particle_dt = add_particle_forces();
  if (cohesive_) {
    // Interfaces before contact: contact leaves the nodes they still hold to them.
    CohesiveInterfaces::Work w = cohesive_->add_forces(model_);
    if (global_sum_) combine_cohesive_over_ranks(w);
    state_.energy[terms_.cohesive_work] += w.work.value();
    state_.energy[terms_.cohesive_released] += w.released.value();
  }
  applied_.clear();
  add_pressure_forces(model_, loads_, state_.time, applied_);
  const auto& g = settings_.gravity;
  if (g[0] != 0 || g[1] != 0 || g[2] != 0) {
    const int dim = model_.dim();
    const std::size_t n = nodes.count();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < dim; ++k) nodes.force[dim * i + k] += nodes.mass[i] * g[k];
  }
  if (contact_) {
    // Faces exposed by erosion or by an interface that opened may meet already pressed.
    contact_->set_eroded_surfaces(state_.eroded_elements > 0 || (cohesive_ && cohesive_->open_elements() > 0));
    contact_->set_tied_nodes(cohesive_ ? &cohesive_->tied_nodes() : nullptr);
    // The penalty is built on the whole model's element step (agreed above).
    contact_->add_forces(model_, state_.time, state_.dt_half, total.stable_dt);
    if (global_sum_) combine_contact_over_ranks();
    state_.energy[terms_.friction] += contact_->friction_increment();
    const auto& wf = contact_->wall_forces();
    state_.wall_force_on_bodies.assign(wf.size(), 0.0);
    for (std::size_t i = 0; i < wf.size(); ++i) state_.wall_force_on_bodies[i] = -wf[i];
  }
  state_.dt_next = choose_time_step(total.stable_dt, particle_dt);
}

void ExplicitSolver::combine_contact_over_ranks() {
  ContactSystem::Booking& booked = contact_->booking();
  sum_over_ranks(booked.sums.data(), booked.sums.size(), &booked.active, 1);
  // Maxima as minima of their negatives: exact, as a minimum is.
  double maxima[3];
  for (int i = 0; i < 3; ++i) maxima[i] = -booked.maxima[i];
  global_minimum_(maxima, 3);
  for (int i = 0; i < 3; ++i) booked.maxima[i] = -maxima[i];
  contact_->take_booking();
}

void ExplicitSolver::combine_cohesive_over_ranks(CohesiveInterfaces::Work& w) {
  // The owned elements' work and counts summed, the springs' largest ω² taken over the ranks (as
  // the minimum of its negative: exact).
  ExactSum sums[2] = {w.work, w.released};
  std::int64_t counts[3] = {static_cast<std::int64_t>(cohesive_->failed_points()),
                            static_cast<std::int64_t>(cohesive_->intact_points()),
                            static_cast<std::int64_t>(cohesive_->open_elements())};
  sum_over_ranks(sums, 2, counts, 3);
  w.work = sums[0], w.released = sums[1];
  double most = -cohesive_->max_frequency_squared();
  if (global_minimum_) global_minimum_(&most, 1);
  cohesive_->set_whole_model(static_cast<std::size_t>(counts[0]), static_cast<std::size_t>(counts[1]),
                             static_cast<std::size_t>(counts[2]), -most);
}

double ExplicitSolver::choose_time_step(double element_stable_dt, double particle_dt) {
  // Contact springs may lower the stable step by up to the stated fraction (the automatic
  // penalty is built for that bound, docs/theory/contact.md): take it off before the safety factor.
  const double reduction = contact_ ? 1.0 - contact_->settings().time_step_reduction : 1.0;
  // With no element left to limit it (all eroded), the step stays what it was: free nodes fly on.
  const double element_dt = std::isfinite(element_stable_dt) || state_.stable_dt == 0
                                ? element_stable_dt
                                : state_.stable_dt / reduction;
  state_.stable_dt = element_dt * reduction;
  // Several contact springs on one light node can take ω² past that fraction: bound the step by
  // ω² ≤ ω_e² + ω_c², with ω_e = 2/Δt_e and ω_c² the contact's Gershgorin bound. The bound is
  // conservative: one spring stays within the reduced step, but ordinary two-body contact can
  // pass it by up to 1.45 times (up to 14 % shorter steps); piles of fragments pass it by 3.7.
  // The contact dashpots lower it further: central difference with damping is stable for
  // ω²Δt²/4 + γΔt/2 ≤ 1, γ the Gershgorin bound on M⁻¹C (for one mode γ = 2ξω, the usual
  // Δt = (2/ω)(√(1+ξ²) − ξ)), so Δt = 2/(γ/2 + √(γ²/4 + ω_e² + ω_c²)).
  if (contact_ && std::isfinite(element_dt) && contact_->max_frequency_squared() > 0) {
    const double omega_c2 = contact_->max_frequency_squared();
    const double gamma = 0.5 * contact_->max_damping_rate();
    const double omega2 = 4.0 / (element_dt * element_dt) + omega_c2;
    const double contact_dt = 2.0 / (gamma + std::sqrt(gamma * gamma + omega2));
    state_.stable_dt = std::min(state_.stable_dt, contact_dt);
  }
  // The cohesive springs likewise (Gershgorin's bound on their M⁻¹K); the run says so when they
  // limit the step (app/run.cpp).
  element_dt_ = cohesive_dt_ = state_.stable_dt;
  if (cohesive_ && std::isfinite(element_dt) && cohesive_->max_frequency_squared() > 0) {
    const double omega2 = cohesive_->max_frequency_squared();
    cohesive_dt_ = state_.stable_dt / std::sqrt(1.0 + 0.25 * omega2 * state_.stable_dt * state_.stable_dt);
    state_.stable_dt = cohesive_dt_;
  }
  double dt = settings_.time_step_safety * state_.stable_dt;
  dt = std::min(dt, particle_dt);
  if (settings_.max_time_step > 0) dt = std::min(dt, settings_.max_time_step);
  if (global_minimum_) {
    // A decomposed run: each rank saw only its elements. A minimum commutes with the safety
    // factor and the caps above, so the step is the whole model's, bit for bit.
    double values[2] = {state_.stable_dt, dt};
    global_minimum_(values, 2);
    state_.stable_dt = values[0];
    dt = values[1];
  }
  const double remaining = settings_.end_time - state_.time;
  if (remaining > 0 && remaining < 1.000001 * dt) dt = remaining;  // land on end_time
  if (state_.initial_dt == 0) state_.initial_dt = dt;
  const bool land_on_end = remaining > 0 && dt == remaining;
  if (!(dt > 0) || !std::isfinite(dt) || (!land_on_end && dt < 1e-6 * state_.initial_dt)) {
    std::ostringstream out;
    out << "the stable time step collapsed to " << dt << " s (initial " << state_.initial_dt
        << " s) at t = " << state_.time << " s, step " << state_.step
        << ": an element is being crushed to nothing (look at the last frame; lower the load, "
           "refine, or check contact penetration)";
    throw RunError(out.str());
  }
  return dt;
}

void ExplicitSolver::apply_prescribed_velocities(const AdvanceCoefficients& c, ExactSum& external_back,
                                                 ExactSum& external_ahead) {
  // Prescribed velocities, nodes and particles alike: the force becomes the one that gives
  // v+ = v_prescribed; the difference is the reaction, whose work is external work. The
  // particles' reactions are summed per group for the history (load-displacement curves).
  const double t_half = state_.time + 0.5 * state_.dt_next;
  node_reaction_sums_.assign(6 * loads_.node_groups.size(), ExactSum());
  node_work_sums_.assign(2 * loads_.node_groups.size(), ExactSum());
  apply_prescribed(moving_points(model_), node_dofs_, loads_, c, t_half, external_back, external_ahead,
                   &node_reaction_sums_, &node_work_sums_);
  particle_reaction_sums_.assign(6 * loads_.particle_groups.size(), ExactSum());
  for (std::size_t p = 0; p < model_.particle_parts.size(); ++p)
    apply_prescribed(moving_points(model_.particle_parts[p]), particle_dofs_[p], loads_, c, t_half, external_back,
                     external_ahead, &particle_reaction_sums_);
}

void ExplicitSolver::book_contact_work(const AdvanceCoefficients& c, ContactWork& work, double& wall_back,
                                       double& wall_ahead, double& particle_wall_back, double& particle_wall_ahead) {
  // Work of the contact forces on the nodes, and of moving rigid walls on the bodies they push
  // (F_wall→body · v_wall, external work); the particles' share of the walls' work is its own term.
  const int dim = model_.dim();
  const double back = c.back, ahead = c.ahead, dt_next = c.dt_next;
  if (contact_) {
    const double* V = model_.nodes.v.data();
    const double* F = model_.nodes.force.data();
    const double* M = model_.nodes.mass.data();
    const std::uint8_t* ghost = model_.ghost_node.empty() ? nullptr : model_.ghost_node.data();
    auto new_velocity = [&](std::size_t dof, double m) { return (c.d1 * V[dof] + c.dt_n * (F[dof] / m)) * c.d2; };
    for (const auto& [dof, f] : contact_->applied_forces()) {
      if (ghost && ghost[dof / dim]) continue;  // its owner books the work
      work.contact_back += f * back * V[dof];
      work.contact_ahead += f * ahead * new_velocity(dof, M[dof / dim]);
    }
    // The dashpots' share of that work, over the same half steps: dissipated (contact_damping).
    for (const auto& [dof, f] : contact_->damping_forces()) {
      if (ghost && ghost[dof / dim]) continue;
      work.damping_back -= f * back * V[dof];
      work.damping_ahead -= f * ahead * new_velocity(dof, M[dof / dim]);
    }
  }
  const std::vector<RigidWall>* walls = contact_ ? &contact_->settings().walls
                                        : particle_contact_ ? &particle_contact_->settings().walls
                                                            : nullptr;
  if (!walls) return;
  const auto& f = state_.wall_force_on_bodies;
  const auto& fp = state_.particle_wall_force_on_bodies;
  if (model_.contact.wall_offset.size() != walls->size() * dim) model_.contact.wall_offset.assign(walls->size() * dim, 0.0);
  for (std::size_t w = 0; w < walls->size(); ++w)
    for (int k = 0; k < dim; ++k) {
      const double vb = (*walls)[w].velocity[k].at(state_.time - 0.5 * state_.dt_half);
      const double va = (*walls)[w].velocity[k].at(state_.time + 0.5 * dt_next);
      if (dim * w + k < f.size()) {
        wall_back += f[dim * w + k] * back * vb;
        wall_ahead += f[dim * w + k] * ahead * va;
      }
      if (dim * w + k < fp.size()) {
        particle_wall_back += fp[dim * w + k] * back * vb;
        particle_wall_ahead += fp[dim * w + k] * ahead * va;
      }
      model_.contact.wall_offset[dim * w + k] += va * dt_next;
    }
}

double ExplicitSolver::last_increment() const {
  // Where a remesh has cut the stable step of the elements and contact by more than half (the
  // new elements smaller, their nodes lighter), the last increment counts as the next one: the
  // velocity update spans ½(Δt_n−1/2 + Δt_n+1/2), and with the old, long increment it would kick
  // the new elements and contact springs past their stable step once. The velocities are then
  // taken half a new step, not half an old one, before t_n (docs/theory/
  // time_integration_and_energy.md, section 1). The stable step, not the increment, decides: the
  // last increment is cut short to land on the end time. Only in runs that remesh, so that runs
  // without keep their bits.
  const bool remeshing = !model_.remesh_count.empty();
  const bool fallen = state_.dt_half > 2.0 * settings_.time_step_safety * state_.stable_dt;
  return remeshing && fallen ? state_.dt_next : state_.dt_half;
}

double ExplicitSolver::velocity_step() const {
  return state_.step == 0 ? 0.5 * state_.dt_next : 0.5 * (last_increment() + state_.dt_next);
}

void ExplicitSolver::advance() {
  run_events(StepEvent::Phase::after_forces);
  AdvanceCoefficients c;
  c.dt_next = state_.dt_next;
  const double last = last_increment();
  c.dt_n = velocity_step();
  // Central difference with mass-proportional damping taken at the mid-point:
  // m (v+ − v−)/Δt = F − α m (v+ + v−)/2  ⇒  v+ = ((1 − αΔt/2) v− + Δt F/m) / (1 + αΔt/2).
  c.alpha = settings_.mass_damping;
  c.d1 = 1.0 - 0.5 * c.alpha * c.dt_n;
  c.d2 = 1.0 / (1.0 + 0.5 * c.alpha * c.dt_n);
  c.gravity = settings_.gravity;
  // Work of a nodal force F_n is split at t_n: ½Δt_n−1/2 F_n·v_n−1/2 closes the interval
  // [t_n−1/2, t_n] and ½Δt_n+1/2 F_n·v_n+1/2 opens [t_n, t_n+1/2]. The second half is booked
  // next step, so that the reported energies all end at t_n, where the element stress work ends.
  c.back = 0.5 * last;
  c.ahead = 0.5 * c.dt_next;
  if (c.back + c.ahead > 0) c.kinetic_weight = c.back / (c.back + c.ahead);
  AdvanceSums sums;
  apply_prescribed_velocities(c, sums.external_back, sums.external_ahead);
  const int dim = model_.dim();
  const double* V = model_.nodes.v.data();
  const double* F = model_.nodes.force.data();
  const double* M = model_.nodes.mass.data();
  const std::uint8_t* ghost = model_.ghost_node.empty() ? nullptr : model_.ghost_node.data();
  for (const auto& [dof, f] : applied_) {
    if (ghost && ghost[dof / dim]) continue;  // its owner books the work
    const double m = M[dof / dim];
    sums.external_back += f * c.back * V[dof];
    sums.external_ahead += f * c.ahead * ((c.d1 * V[dof] + c.dt_n * (F[dof] / m)) * c.d2);
  }
  double wall_back = 0, wall_ahead = 0, pwall_back = 0, pwall_ahead = 0;
  ContactWork contact_work;
  book_contact_work(c, contact_work, wall_back, wall_ahead, pwall_back, pwall_ahead);

  // The nodes' gravity work adds to the external work.
  const std::int64_t bad_node = advance_points(moving_points(model_), c, sums, block_sums_);
  if (bad_node >= 0) {
    std::ostringstream out;
    out << "the velocity of node " << bad_node << " is not finite at t = " << state_.time << " s, step "
        << state_.step << " (the run has become unstable)";
    throw RunError(out.str());
  }
  for (ParticlePart& pp : model_.particle_parts) {
    const std::int64_t bad = advance_points(moving_points(pp), c, sums, block_sums_);
    if (bad >= 0) {
      std::ostringstream out;
      out << "the velocity of particle " << bad << " of particle part '" << pp.name << "' is not finite at t = "
          << state_.time << " s, step " << state_.step
          << " (the run has become unstable: lower the part's time_step_safety)";
      throw RunError(out.str());
    }
  }
  sum_advance_over_ranks(sums, contact_work);
  const double contact_back = contact_work.contact_back.value(), contact_ahead = contact_work.contact_ahead.value();
  const double dashpot_back = contact_work.damping_back.value(), dashpot_ahead = contact_work.damping_ahead.value();
  const double kinetic = sums.kinetic.value(), damp_back = sums.damp_back.value(),
               damp_ahead = sums.damp_ahead.value(), external_back = sums.external_back.value(),
               external_ahead = sums.external_ahead.value();
  const double dt_next = c.dt_next;
  auto& E = state_.energy;
  E[terms_.kinetic] = kinetic;
  E[terms_.damping] += state_.pending_damping + damp_back;
  E[terms_.external_work] += state_.pending_external + external_back + state_.pending_wall + wall_back;
  if (contact_) {
    E[terms_.wall_work] += state_.pending_wall + wall_back;
    E[terms_.contact_work] += state_.pending_contact + contact_back;
    E[terms_.contact_damping] += state_.pending_contact_damping + dashpot_back;
  }
  if (particle_contact_) E[terms_.particle_wall_work] += state_.pending_particle_wall + pwall_back;
  state_.pending_particle_wall = pwall_ahead;
  state_.pending_damping = damp_ahead;
  state_.pending_external = external_ahead;
  state_.pending_wall = wall_ahead;
  state_.pending_contact = contact_ahead;
  state_.pending_contact_damping = dashpot_ahead;
  state_.dt_half = dt_next;
  state_.time += dt_next;
  state_.step += 1;
  // Nodes that failed in this step split now, between steps, where mass, momentum and the
  // positions at t_n+1 carry over to the copies unchanged.
  run_events(StepEvent::Phase::after_advance);
}

void ExplicitSolver::remove_event(const StepEvent& event) {
  events_.erase(std::remove(events_.begin(), events_.end(), &event), events_.end());
}

void ExplicitSolver::leave_eroded_elements() {
  own_events_.erase(std::remove_if(own_events_.begin(), own_events_.end(),
                                   [](const auto& e) { return dynamic_cast<ErosionCompaction*>(e.get()) != nullptr; }),
                    own_events_.end());
}

void ExplicitSolver::run_events(StepEvent::Phase phase) {
  auto run = [&](StepEvent& event) {
    if (event.phase() != phase) return;
    EventContext context{state_.step, state_.time, state_.eroded_elements, state_.energy, topology_,
                         &state_.part_stored};
    event.run(model_, context);
  };
  for (StepEvent* event : events_) run(*event);
  for (auto& event : own_events_) run(*event);
}

}  // namespace shard
