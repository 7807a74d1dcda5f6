#include "io/checkpoint.hpp"

#include "io/output_file.hpp"

#include <cstring>
#include <fstream>
#include <type_traits>
#include <vector>

#include "core/error.hpp"

namespace shard {

namespace {

// The last byte is the format version, '0' + n (':' is 10, ';' 11): 4 added the elements' reference
// length (distortion criterion) and the particles' ring length; 5 the cohesive elements; 6 their open flag and
// the crash force's running mean; 7 the automata's many-body share, the running means of the
// history's force columns, the node groups' reactions and work, and the pending half step of the
// contact dashpots' work; 8 the stored energy of each element part;
// 9 the elements' reference shape (adaptive remeshing); 10 the time a crack reached each node;
// 11 the count of local remeshes and the back-off of failed ones; 12 where the list of particle
// contacts was built (a restart takes the list up instead of building it), and the run's notes
// on its step; 13 the speed of the crack tip that reached each node; 14 the fragmentation damage's
// weakest-flaw stress (one more history variable per point); 15 the part each node was meshed
// with (nodes whose elements have eroded still count in it).
constexpr char kMagic[8] = {'S', 'H', 'A', 'R', 'D', 'C', 'K', '?'};

/// Scalars of SolverState and OutputCursor in one fixed order, for both directions.
template <class F>
void visit_scalars(SolverState& s, OutputCursor& c, F&& f) {
  f(s.step);
  f(s.time);
  f(s.dt_half);
  f(s.dt_next);
  f(s.stable_dt);
  f(s.initial_dt);
  f(s.eroded_elements);
  f(s.pending_external);
  f(s.pending_damping);
  f(s.pending_contact);
  f(s.pending_wall);
  f(s.pending_particle_wall);
  f(s.pending_contact_damping);
  f(c.next_frame);
  f(c.next_history);
  f(c.next_checkpoint);
  f(c.history_bytes);
  f(c.row_span);
}

/// Type tag of a checkpoint array, so that a reader never reinterprets one element type as another.
template <class T>
constexpr std::uint8_t type_code() {
  if constexpr (std::is_same_v<T, double>) return 1;
  else if constexpr (std::is_same_v<T, std::int32_t>) return 2;
  else if constexpr (std::is_same_v<T, std::int16_t>) return 3;
  else if constexpr (std::is_same_v<T, std::int64_t>) return 5;
  else {
    static_assert(sizeof(T) == 1, "checkpoint arrays hold double, int64, int32, int16 or 1-byte values");
    return 4;
  }
}

class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) {}
  template <class T>
  void raw(const T& v) {
    out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void text(const std::string& s) {
    raw<std::uint64_t>(s.size());
    out_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }
  template <class T>
  void array(const std::string& name, const std::vector<T>& a) {
    text(name);
    raw<std::uint8_t>(type_code<T>());
    raw<std::uint64_t>(a.size());
    out_.write(reinterpret_cast<const char*>(a.data()), static_cast<std::streamsize>(a.size() * sizeof(T)));
  }

 private:
  std::ostream& out_;
};

class Reader {
 public:
  Reader(std::ifstream& in, std::string file) : in_(in), file_(std::move(file)) {}
  template <class T>
  T raw() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
    check();
    return v;
  }
  std::string text() {
    const auto n = raw<std::uint64_t>();
    if (n > (1u << 20)) fail("corrupt name");
    std::string s(n, '\0');
    in_.read(s.data(), static_cast<std::streamsize>(n));
    check();
    return s;
  }
  template <class T>
  void array(const std::string& name, std::vector<T>& a) {
    const std::string got = text();
    if (got != name) fail("expected array '" + name + "', found '" + got + "' (a checkpoint of another model?)");
    const auto type = raw<std::uint8_t>();
    if (type != type_code<T>()) fail("array '" + name + "' has the wrong type");
    const auto n = raw<std::uint64_t>();
    a.resize(n);
    in_.read(reinterpret_cast<char*>(a.data()), static_cast<std::streamsize>(n * sizeof(T)));
    check();
  }
  [[noreturn]] void fail(const std::string& why) {
    throw InputError(file_, 0, "--restart", "cannot restart from this checkpoint: " + why);
  }

 private:
  void check() {
    if (!in_) fail("the file ends early (truncated?)");
  }
  std::ifstream& in_;
  std::string file_;
};

}  // namespace

void write_checkpoint(const std::filesystem::path& path, Model& model, const SolverState& state,
                      const OutputCursor& cursor, const std::string& fingerprint) {
  write_file_atomically(path, [&](std::ostream& out) {
    Writer w(out);
    out.write(kMagic, sizeof(kMagic));
    w.text(fingerprint);
    SolverState s = state;
    OutputCursor c = cursor;
    visit_scalars(s, c, [&](auto& v) { w.raw(v); });
    w.array("history_force_impulse", c.force_impulse);
    w.array("history_reaction_impulse", c.reaction_impulse);
    w.array("history_reaction_work", c.reaction_work);
    w.array("probe_bytes", c.probe_bytes);
    w.array("probe_next", c.probe_next);
    w.array("cohesive_step_note", c.cohesive_step_note);
    w.array("particle_step_note", c.particle_step_note);
    w.array("part_stored", s.part_stored);
    // The energy ledger, by name: every registered term.
    w.raw<std::uint64_t>(state.energy.terms().size());
    for (const EnergyTerm& t : state.energy.terms()) {
      w.text(t.name);
      w.raw(t.value);
    }
    model.visit_fields([&](const std::string& name, const FieldInfo& info, auto& a) {
      if (info.checkpoint) w.array(name, a);
    });
    model.visit_counters([&](const char*, std::int64_t& v) { w.raw(v); });
  });
}

void read_checkpoint(const std::filesystem::path& path, Model& model, SolverState& state,
                     OutputCursor& cursor, const std::string& fingerprint) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "--restart", "checkpoint file not found");
  Reader r(in, path.string());
  char magic[8];
  in.read(magic, sizeof(magic));
  if (!in || std::memcmp(magic, kMagic, sizeof(kMagic) - 1) != 0) r.fail("not a shard checkpoint");
  if (magic[7] != kMagic[7])
    r.fail("it was written by another version of shard (checkpoint format " + std::to_string(magic[7] - '0') +
           ", this one reads " + std::to_string(kMagic[7] - '0') + "): run the scenario again from the start");
  if (r.text() != fingerprint)
    r.fail("it was written by a different scenario (restart with the scenario that wrote it)");
  visit_scalars(state, cursor, [&](auto& v) { v = r.raw<std::decay_t<decltype(v)>>(); });
  r.array("history_force_impulse", cursor.force_impulse);
  r.array("history_reaction_impulse", cursor.reaction_impulse);
  r.array("history_reaction_work", cursor.reaction_work);
  r.array("probe_bytes", cursor.probe_bytes);
  r.array("probe_next", cursor.probe_next);
  r.array("cohesive_step_note", cursor.cohesive_step_note);
  r.array("particle_step_note", cursor.particle_step_note);
  r.array("part_stored", state.part_stored);
  const auto terms = r.raw<std::uint64_t>();
  if (terms > 4096) r.fail("corrupt energy ledger");
  for (std::uint64_t k = 0; k < terms; ++k) {
    const std::string name = r.text();
    const double value = r.raw<double>();
    if (state.energy.find(name) < 0)
      r.fail("it books an energy term '" + name + "' this run does not have (a checkpoint of another model?)");
    state.energy.at(name) = value;
  }
  model.visit_fields([&](const std::string& name, const FieldInfo& info, auto& a) {
    if (info.checkpoint) r.array(name, a);
  });
  model.visit_counters([&](const char*, std::int64_t& v) { v = r.raw<std::int64_t>(); });
}

}  // namespace shard
