// The Python module for scripted studies: the same scenario, overrides and run as the command
// line (`shard run X.yaml --set key=value`), with the history handed back as NumPy arrays and the
// summary as a dict. A run releases the interpreter while it steps.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/eval.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/run.hpp"
#include "core/error.hpp"
#include "io/scenario.hpp"

namespace py = pybind11;

namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

[[noreturn]] void raise_file_not_found(const std::string& what) {
  PyErr_SetString(PyExc_FileNotFoundError, what.c_str());
  throw py::error_already_set();
}

/// history.csv as {column: numpy array}, every value read back to the same double. `path` is the
/// file or the run folder that holds it; a file that is not a history (its header does not start
/// with time,step,dt) or a value that is not a number is a ValueError naming the file and line.
py::object read_history(std::filesystem::path path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) path /= "history.csv";
  std::ifstream in(path);
  if (!std::filesystem::is_regular_file(path, ec) || !in)
    raise_file_not_found(path.string() + ": no such history file (give a run folder or its history.csv)");
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.rfind("time,step,dt", 0) != 0)
    throw py::value_error(path.string() + ": not a shard history (its first line does not start with time,step,dt)");
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) names.push_back(c);
  std::vector<std::vector<double>> columns(names.size());
  for (std::size_t row = 2; std::getline(in, line); ++row) {
    // A last line without its newline is a row a killed run was writing (shard ends every row
    // with one): it is left out, and the rows before it stand.
    if (in.eof()) break;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a file saved with Windows line ends
    const std::string where = path.string() + ":" + std::to_string(row) + ": ";
    std::vector<double> values;
    const char* p = line.c_str();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c > 0 && p[-1] != ',')
        throw py::value_error(where + "the row has " + std::to_string(c) + " values, the header " +
                              std::to_string(columns.size()) + " columns");
      char* end = nullptr;
      values.push_back(std::strtod(p, &end));
      if (end == p && (*p == ',' || *p == '\0'))
        throw py::value_error(where + "column '" + names[c] + "' has no value");
      if (end == p || (*end != ',' && *end != '\0'))
        throw py::value_error(where + "column '" + names[c] + "' is not a number");
      p = *end == ',' ? end + 1 : end;
    }
    if (p[-1] == ',' || *p != '\0')
      throw py::value_error(where + "the row has more values than the header's " + std::to_string(columns.size()) +
                            " columns");
    for (std::size_t c = 0; c < columns.size(); ++c) columns[c].push_back(values[c]);
  }
  py::dict history;
  for (std::size_t c = 0; c < names.size(); ++c)
    history[py::str(names[c])] = py::array_t<double>(static_cast<py::ssize_t>(columns[c].size()), columns[c].data());
  return py::module_::import("shard").attr("History")(history);
}

/// A value from Python as the text of a --set: None is YAML's null (removes the key), text is
/// given as it is, and anything else (numbers, lists, tuples, dicts, NumPy arrays and scalars, at
/// any depth) as JSON, which is YAML, with plain numbers and every digit of a float (the module's
/// `_override_json`, defined once at import).
std::string override_text(const py::object& value) {
  if (value.is_none()) return "~";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  return py::module_::import("shard").attr("_override_json")(value).cast<std::string>();
}

/// A scenario file with the overrides put over it, as `shard run FILE --set KEY=VALUE ...` has.
/// The file is read when the object is made; check() and run() refuse it if it changed since, so
/// that a study runs the scenario it checked.
class Scenario {
 public:
  explicit Scenario(const std::filesystem::path& file) : file_(std::filesystem::absolute(file)) {
    (void)shard::read_scenario(file_);  // a bad file is an error here, not at run()
    text_ = read_text(file_);
  }

  /// Puts `value` over `key` (text such as "450 MPa", a number in SI units, None to remove the
  /// key); checked at once.
  Scenario& set(const std::string& key, const py::object& value) { return set_all({{key, override_text(value)}}); }

  /// Puts several values at once, checked together: a swap of elastic constants (shear_modulus:
  /// None, youngs_modulus: "200 GPa") is never checked half done.
  Scenario& set_many(const py::dict& values) {
    std::vector<shard::ScenarioOverride> given;
    for (const auto& [key, value] : values) given.push_back({py::str(key), override_text(py::reinterpret_borrow<py::object>(value))});
    return set_all(given);
  }

  std::string check() const {
    still_as_read();
    return shard::check_scenario(file_, overrides_);
  }

  /// Runs into `output` with `threads` (0: OpenMP's default); returns {"history", "summary",
  /// "output"}.
  py::dict run(const std::filesystem::path& output, int threads, bool quiet) const {
    if (threads < 0) throw py::value_error("threads: a whole number >= 0 (0: OpenMP's default), not " + std::to_string(threads));
    shard::RunOptions options;
    options.output_dir = output;
    options.threads = threads;
    options.quiet = quiet;
    options.overrides = overrides_;
    still_as_read();
    // Ctrl-C: the interpreter's signal handlers run when asked, between steps; what they raise
    // (KeyboardInterrupt) is raised once the run has stopped and kept its outputs.
    // Only the main thread runs signal handlers, and the interpreter is asked at most every 50 ms:
    // a study running cases on other threads does not wait for the interpreter at every step.
    std::optional<py::error_already_set> raised;
    const py::object threading = py::module_::import("threading");
    if (threading.attr("current_thread")().is(threading.attr("main_thread")())) {
      auto asked = std::chrono::steady_clock::now();
      options.interrupted = [&raised, asked]() mutable {
        const auto now = std::chrono::steady_clock::now();
        if (now - asked < std::chrono::milliseconds(50)) return false;
        asked = now;
        py::gil_scoped_acquire held;
        if (PyErr_CheckSignals() == 0) return false;
        raised.emplace();
        return true;
      };
    }
    try {
      py::gil_scoped_release unlocked;
      (void)shard::run_scenario(file_, options);
    } catch (const shard::RunError&) {
      if (!raised) throw;
      raised->restore();
      throw py::error_already_set();
    }
    py::dict result;
    result["output"] = output.string();
    result["history"] = read_history(options.output_dir / "history.csv");
    result["summary"] = py::module_::import("json").attr("loads")(read_text(options.output_dir / "summary.json"));
    return result;
  }

  std::vector<std::pair<std::string, std::string>> overrides() const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& o : overrides_) out.emplace_back(o.key, o.value);
    return out;
  }

 private:
  Scenario& set_all(const std::vector<shard::ScenarioOverride>& given) {
    std::vector<shard::ScenarioOverride> all = overrides_;
    all.insert(all.end(), given.begin(), given.end());
    still_as_read();
    (void)shard::read_scenario(file_, all);
    overrides_ = std::move(all);
    return *this;
  }

  void still_as_read() const {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file_, ec))
      throw shard::InputError(file_.string(), 0, "", "the scenario file is gone since Scenario() read it");
    if (read_text(file_) != text_)
      throw shard::InputError(file_.string(), 0, "",
                              "the file changed since Scenario() read it: make a new Scenario to run what it says "
                              "now, or put the file back and set() the values to change");
  }

  std::filesystem::path file_;
  std::string text_;  ///< the file as read, to tell a later edit
  std::vector<shard::ScenarioOverride> overrides_;
};

}  // namespace

PYBIND11_MODULE(shard, m) {
  m.doc() = "shard: explicit dynamics of cracking, fragmenting and crushing solids (docs/python.md)";
  m.attr("__version__") = SHARD_VERSION;
  // The history as a dict whose missing column says which columns there are (a study's typo of
  // a column name was a bare KeyError).
  py::dict scope;
  scope["__builtins__"] = py::module_::import("builtins");
  scope["__name__"] = "shard";
  py::exec(R"(
class History(dict):
    """A run's history.csv as {column: numpy array}, the columns in the file's order."""

    def __missing__(self, key):
        raise KeyError(f"{key!r}: the history has no such column; it has: {', '.join(self)}")


def _plain(v):
    """A value with NumPy arrays and scalars and tuples made plain lists and numbers, at any depth."""
    if hasattr(v, "tolist") and not isinstance(v, str):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items()}
    if hasattr(v, "item") and not isinstance(v, (str, bool, int, float)):
        v = v.item()
    return v


def _override_json(value):
    """The text of a set() value that is not text: JSON, which YAML reads."""
    import json
    return json.dumps(_plain(value))
)",
           scope);
  m.attr("History") = scope["History"];
  m.attr("_override_json") = scope["_override_json"];
  static py::exception<shard::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<shard::RunError> run_error(m, "RunError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const shard::InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    } catch (const shard::RunError& e) {
      PyErr_SetString(run_error.ptr(), e.what());
    }
  });
  py::class_<Scenario>(m, "Scenario", "a scenario file and the overrides put over it")
      .def(py::init<const std::filesystem::path&>(), py::arg("file"))
      .def("set", &Scenario::set, py::arg("key"), py::arg("value"), py::return_value_policy::reference_internal,
           "put a value over a key (dotted, list entries from 1), e.g. set('materials.alumina.tensile_strength', "
           "'450 MPa'); checked at once (InputError)")
      .def("set", &Scenario::set_many, py::arg("values"), py::return_value_policy::reference_internal,
           "put several values at once, checked together: set({'materials.steel.shear_modulus': None, "
           "'materials.steel.youngs_modulus': '200 GPa'})")
      .def("check", &Scenario::check, "what `shard check` prints")
      .def("run", &Scenario::run, py::arg("output"), py::arg("threads") = 0, py::arg("quiet") = true,
           "run into the folder `output`; returns {'history': {column: numpy array}, 'summary': dict, 'output': str}")
      .def_property_readonly("overrides", &Scenario::overrides);
  m.def("read_history", [](const std::filesystem::path& path) { return read_history(path); }, py::arg("path"),
        "a run's history.csv (the file, or the run folder) as {column: numpy array}");
}
