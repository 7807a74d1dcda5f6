// The energy ledger: every term of the energy balance, registered by name by the code that does
// the work (the element kernels, src/fem/; the contact, src/contact/; the automata,
// src/particle/; the solver itself; later the conversion to particles and cohesive interfaces),
// accumulated step by step. History columns,
// the summary and checkpoints iterate the registered terms; the balance closes over whatever is
// registered. Theory: docs/theory/time_integration_and_energy.md; recipe for a new term:
// docs/architecture.md.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shard {

/// The groups of the balance
///   residual = kinetic + internal + contact + dissipated − external − initial,
/// each the signed sum of the terms that enter it.
enum class EnergyGroup : std::uint8_t { kinetic, internal, contact, dissipated, external, initial };

/// A term of the ledger: where it enters the balance and where it is reported.
struct EnergyTerm {
  std::string name;  ///< e.g. "plastic"; unique
  std::string doc;   ///< one line for docs/outputs.md
  /// Its place within every group it enters (terms of a group are summed in increasing rank, so
  /// the same terms give the same bits in any run); the standard ranks are in energy.cpp.
  int rank = 0;
  struct Entry {
    EnergyGroup group;
    int sign;  ///< +1 or −1
  };
  std::vector<Entry> entries;
  /// The history column it is reported in: its own name by default; terms that name one column
  /// are summed into it; "-" for a term reported only through its groups.
  std::string column;
  double value = 0;
};

class EnergyLedger {
 public:
  /// Registers a term (a term of that name already registered is kept); returns its handle.
  int add(EnergyTerm term);
  /// The handle of a term, −1 if none has that name.
  int find(std::string_view name) const;
  /// A registered term's value; throws std::out_of_range for a name not registered.
  double& at(std::string_view name);
  double& operator[](int handle) { return terms_[static_cast<std::size_t>(handle)].value; }
  /// A term's value, 0 for a name not registered.
  double value(std::string_view name) const;
  /// Every value back to 0 (the terms stay registered).
  void clear();

  double group(EnergyGroup g) const;
  double kinetic() const { return group(EnergyGroup::kinetic); }
  /// Recoverable (elastic) internal energy: stress work less what the materials dissipated,
  /// plus the energy the automata store.
  double internal() const { return group(EnergyGroup::internal); }
  /// Contact ("sliding interface") energy: what the moving walls put in, less what the contact
  /// forces took from the nodes and what friction dissipated: the penalty springs' elastic energy
  /// plus the penalty method's discretisation error; it returns to ~0 when bodies separate.
  double contact() const { return group(EnergyGroup::contact); }
  double dissipated() const { return group(EnergyGroup::dissipated); }
  double external() const { return group(EnergyGroup::external); }
  double initial() const { return group(EnergyGroup::initial); }
  /// kinetic + internal + contact + dissipated − external work − initial
  double residual() const;
  /// residual relative to the largest energy in play (never the residual's own scale)
  double relative_error() const;

  /// Column names and values for history.csv (after time, step, dt), in one fixed order: the
  /// standard columns, then one per column of terms registered beyond them, then energy_error.
  std::vector<std::string> column_names() const;
  std::vector<double> column_values() const;

  /// Every term's value, in registration order.
  std::vector<double> values() const;
  /// The `count` terms whose values moved most since `before` (values() at that time; a term
  /// registered since then counts from 0), largest move first, as "name a → b J; ...". What a
  /// run that stops on its energy balance says went wrong.
  std::string largest_changes(const std::vector<double>& before, std::size_t count) const;

  /// The registered terms, in registration order (what checkpoints store, by name).
  const std::vector<EnergyTerm>& terms() const { return terms_; }
  std::vector<EnergyTerm>& terms() { return terms_; }

 private:
  std::vector<EnergyTerm> terms_;
  /// Per group, the handles of its terms in rank order, with their signs.
  std::vector<std::vector<std::pair<int, int>>> groups_;
};

/// The standard ranks: terms enter their groups, and columns, in this order.
namespace energy_rank {
inline constexpr int kinetic = 0, initial = 0, external_work = 0, stress_work = 10, viscosity = 20,
                     hourglass = 30, damping = 40, plastic = 50, heat = 55, fracture = 60,
                     particle_elastic = 62, wall_work = 64, contact_work = 66, friction = 70, contact_damping = 71,
                     particle_contact = 72, particle_friction = 75, particle_many_body = 77, eroded = 80,
                     later = 100;
}

}  // namespace shard
