#include "io/particle_sample.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "core/error.hpp"
#include "core/parameters.hpp"
#include "core/text.hpp"
#include "io/output_file.hpp"

namespace shard {

namespace {

std::string column_line(int dim) { return dim == 3 ? "id,x,y,z,radius,material" : "id,x,y,radius,material"; }

/// The shortest text that reads back as the same double: a re-imported sample has the same bits.
void put(std::ostream& out, double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.write(buffer, r.ptr - buffer);
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view s, char by) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t end = s.find(by, start);
    out.push_back(trimmed(s.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
    if (end == std::string_view::npos) return out;
    start = end + 1;
  }
}

template <class T>
bool parse(std::string_view s, T& value) {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

/// Reads a sample file line by line: the comment header (lattice, automaton_size, interphase),
/// the column line, then one automaton a row. Every error names the file's line.
class SampleReader {
 public:
  SampleReader(const SampleReference& where, int dim, const std::vector<std::string>& materials)
      : where_(where), materials_(materials) {
    sample_.dim = dim;
  }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw InputError(where_.scenario, where_.line, where_.key, where_.shown + ":" + std::to_string(line) + ": " + what);
  }

  void read_line(int line, std::string_view text) {
    text = trimmed(text);
    if (text.empty()) return;
    if (text.front() == '#') {
      if (!columns_seen_) header(line, trimmed(text.substr(1)));
      return;
    }
    if (!columns_seen_) return columns(line, text);
    row(line, text);
  }

  ParticleSample finish(int last_line) {
    if (!columns_seen_) fail(last_line, "no column line '" + column_line(sample_.dim) + "'");
    if (sample_.count() == 0) fail(last_line, "the sample holds no automaton (no rows after the column line)");
    return std::move(sample_);
  }

 private:
  /// "# key: value"; comment lines with other keys (or none) are commentary.
  void header(int line, std::string_view text) {
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos) return;
    const std::string_view key = trimmed(text.substr(0, colon)), value = trimmed(text.substr(colon + 1));
    if (key == "lattice") return lattice(line, value);
    if (key == "automaton_size") {
      if (!parse(value, sample_.automaton_size) || !std::isfinite(sample_.automaton_size) || !(sample_.automaton_size > 0))
        fail(line, "'# automaton_size:' expected a positive length in m, got '" + std::string(value) + "'");
      return;
    }
    if (key == "interphase") interphase(line, value);
  }

  void lattice(int line, std::string_view value) {
    const bool three_d = value == "fcc" || value == "simple_cubic";
    if (value == "hexagonal") sample_.lattice = Lattice::hexagonal_2d;
    else if (value == "square") sample_.lattice = Lattice::square_2d;
    else if (value == "fcc") sample_.lattice = Lattice::fcc;
    else if (value == "simple_cubic") sample_.lattice = Lattice::simple_cubic;
    else fail(line, "'# lattice:' expected hexagonal, square, fcc or simple_cubic, got '" + std::string(value) + "'");
    if (three_d != (sample_.dim == 3))
      fail(line, "lattice '" + std::string(value) + "' does not fit this " + std::to_string(sample_.dim) +
                     "D model (2D: hexagonal, square; 3D: fcc, simple_cubic)");
    lattice_seen_ = true;
  }

  /// "# interphase: <matrix> <inclusion> <levels>": the graded materials the rows may name.
  void interphase(int line, std::string_view value) {
    std::vector<std::string_view> words;
    for (auto w : split(value, ' '))
      if (!w.empty()) words.push_back(w);
    ParticleSample::Interphase g;
    if (words.size() != 3 || !parse(words[2], g.levels) || g.levels < 1)
      fail(line, "'# interphase:' expected '<matrix> <inclusion> <levels>', got '" + std::string(value) + "'");
    g.matrix = std::string(words[0]);
    g.inclusion = std::string(words[1]);
    for (const auto& m : {g.matrix, g.inclusion}) known_material(line, "'# interphase:' ", m, materials_);
    for (int l = 0; l < g.levels; ++l) graded_.push_back(g.matrix + "_interphase_" + std::to_string(l));
    sample_.interphase = g;
  }

  /// `name` is one of `names`, or an error that begins with `what` (the column or header).
  void known_material(int line, const std::string& what, const std::string& name,
                      const std::vector<std::string>& names) const {
    if (std::find(names.begin(), names.end(), name) != names.end()) return;
    std::string reason = what + "no automaton material named '" + name + "' in the scenario";
    const std::string close = closest_match(name, names);
    if (!close.empty()) reason += " (did you mean '" + close + "'?)";
    fail(line, reason);
  }

  void columns(int line, std::string_view text) {
    if (!lattice_seen_) fail(line, "no '# lattice: ...' line before the columns (hexagonal, square, fcc or simple_cubic)");
    if (!(sample_.automaton_size > 0)) fail(line, "no '# automaton_size: ...' line (m) before the columns");
    if (text != column_line(sample_.dim))
      fail(line, "expected the column line '" + column_line(sample_.dim) + "' of a " + std::to_string(sample_.dim) +
                     "D model, got '" + std::string(text) + "'");
    columns_seen_ = true;
  }

  double number(int line, std::string_view field, const char* column) const {
    double v = 0;
    if (!parse(field, v) || !std::isfinite(v))
      fail(line, std::string("column '") + column + "': expected a number, got '" + std::string(field) + "'");
    return v;
  }

  void row(int line, std::string_view text) {
    const auto f = split(text, ',');
    const int D = sample_.dim;
    if (f.size() != static_cast<std::size_t>(D + 3))
      fail(line, "expected " + std::to_string(D + 3) + " values (" + column_line(D) + "), got " + std::to_string(f.size()));
    std::int64_t id = -1;
    if (!parse(f[0], id) || id < 0)
      fail(line, "column 'id': expected an integer of 0 or more, got '" + std::string(f[0]) + "'");
    if (const auto [at, fresh] = id_lines_.emplace(id, line); !fresh)
      fail(line, "column 'id': id " + std::to_string(id) + " is also at line " + std::to_string(at->second));
    static const char* axes[3] = {"x", "y", "z"};
    for (int k = 0; k < D; ++k) sample_.x.push_back(number(line, f[1 + k], axes[k]));
    const double r = number(line, f[1 + D], "radius");
    if (!(r > 0)) fail(line, "column 'radius': expected a positive length, got '" + std::string(f[1 + D]) + "'");
    sample_.id.push_back(id);
    sample_.radius.push_back(r);
    sample_.material.push_back(material(line, std::string(f[2 + D])));
  }

  int material(int line, const std::string& name) {
    if (const auto it = index_.find(name); it != index_.end()) return it->second;
    if (std::find(graded_.begin(), graded_.end(), name) == graded_.end()) {
      std::vector<std::string> names = materials_;
      names.insert(names.end(), graded_.begin(), graded_.end());
      known_material(line, "column 'material': ", name, names);
    }
    sample_.material_names.push_back(name);
    return index_[name] = static_cast<int>(sample_.material_names.size()) - 1;
  }

  const SampleReference& where_;
  const std::vector<std::string>& materials_;
  std::vector<std::string> graded_;  ///< the names of the declared interphase's levels
  ParticleSample sample_;
  bool lattice_seen_ = false, columns_seen_ = false;
  std::unordered_map<std::int64_t, int> id_lines_;
  std::unordered_map<std::string, int> index_;
};

}  // namespace

void write_particle_sample(const std::filesystem::path& path, const ParticleSample& s, const std::string& about) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# shard particle sample: " << about << " (docs/outputs.md, \"Particle samples\"; SI units)\n";
    out << "# lattice: " << lattice_name(s.lattice) << "\n# automaton_size: ";
    put(out, s.automaton_size);
    out << '\n';
    if (s.interphase)
      out << "# interphase: " << s.interphase->matrix << ' ' << s.interphase->inclusion << ' ' << s.interphase->levels
          << '\n';
    out << column_line(s.dim) << '\n';
    for (std::size_t i = 0; i < s.count(); ++i) {
      out << s.id[i];
      for (int k = 0; k < s.dim; ++k) {
        out << ',';
        put(out, s.x[s.dim * i + k]);
      }
      out << ',';
      put(out, s.radius[i]);
      out << ',' << s.material_names[s.material[i]] << '\n';
    }
  });
}

ParticleSample read_particle_sample(const std::filesystem::path& path, int dim,
                                    const std::vector<std::string>& materials, const SampleReference& where) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(where.scenario, where.line, where.key, "cannot read the sample file '" + where.shown + "'");
  std::ostringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  SampleReader reader(where, dim, materials);
  if (const auto bad = first_non_text_byte(text)) {
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(*bad), '\n'));
    reader.fail(line, "not a text file (byte " + byte_hex(text[*bad]) + ")");
  }
  int line = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    reader.read_line(++line, std::string_view(text).substr(start, end - start));
    start = end + 1;
  }
  return reader.finish(std::max(line, 1));
}

}  // namespace shard
