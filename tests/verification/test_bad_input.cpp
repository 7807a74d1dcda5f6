// Bad input: every scenario in tests/bad_input/ is wrong in one way, and says in its first
// comment lines what shard must answer:
//
//   # expect-line: 7                      the scenario line the message points at
//   # expect-key: analysis.end_tme        the key it names ("(none)": a YAML syntax error,
//                                         which names no key)
//   # expect-message: did you mean 'end_time'   text the message must contain
//
// For each file, both `shard check FILE` and `shard run FILE -o DIR/out` must exit with status 2
// (bad input), say "FILE:LINE:", "key 'KEY'" and the expected text on stderr, and leave DIR/out
// uncreated (nothing is written for bad input). One ctest entry per file; a further test keeps
// the folder from silently shrinking. See tests/bad_input/README.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#ifndef _WIN32
#include <sys/wait.h>
#endif

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMinimumCases = 20;

fs::path case_folder() { return fs::path(SHARD_SOURCE_DIR "/tests/bad_input"); }

std::vector<fs::path> case_files() {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(case_folder(), ec))
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// The `# expect-NAME: value` lines at the head of a case file (comment lines before the first
/// line that is not a comment).
std::map<std::string, std::string> expectations(const fs::path& file) {
  std::map<std::string, std::string> out;
  std::ifstream in(file);
  const std::string prefix = "# expect-";
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] != '#') break;
    if (line.compare(0, prefix.size(), prefix) != 0) continue;
    const auto colon = line.find(':', prefix.size());
    if (colon == std::string::npos) continue;
    std::string value = line.substr(colon + 1);
    value.erase(0, value.find_first_not_of(' '));
    while (!value.empty() && (value.back() == ' ' || value.back() == '\r')) value.pop_back();
    out[line.substr(prefix.size(), colon - prefix.size())] = value;
  }
  return out;
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

struct Result {
  int status = -1;
  std::string out, err;
};

/// Runs the shard executable with `arguments` (already quoted), stdout and stderr to files.
Result run_shard(const std::string& arguments, const fs::path& scratch) {
  const fs::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string command = quoted(SHARD_EXECUTABLE) + " " + arguments + " >" +
                              quoted(out.string()) + " 2>" + quoted(err.string());
  const int raw = std::system(command.c_str());
  Result r;
#ifdef _WIN32
  r.status = raw;
#else
  r.status = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
#endif
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

/// A fresh empty folder of its own under the system temp folder; removed on destruction.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name) {
    std::random_device random;
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = fs::temp_directory_path() /
              ("shard_bad_input_" + name + "_" + std::to_string(random()) + std::to_string(attempt));
      if (fs::create_directory(path_)) return;
    }
    throw std::runtime_error("cannot make a scratch folder under " + fs::temp_directory_path().string());
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// The case file as passed on the command line: relative to the current folder where possible,
/// so that the test also checks that messages repeat the path as the person typed it.
std::string given_path(const fs::path& file) {
  std::error_code ec;
  const fs::path relative = fs::relative(file, ec);
  return !ec && !relative.empty() ? relative.string() : file.string();
}

std::string test_name(const ::testing::TestParamInfo<fs::path>& info) {
  std::string name = info.param.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class BadInput : public ::testing::TestWithParam<fs::path> {};

TEST_P(BadInput, IsRejectedWithFileLineKeyAndReason) {
  const fs::path file = GetParam();
  const auto expect = expectations(file);
  for (const char* field : {"line", "key", "message"})
    ASSERT_TRUE(expect.count(field) && !expect.at(field).empty())
        << file << ": the header lacks '# expect-" << field << ": ...'";
  const int line = std::atoi(expect.at("line").c_str());
  ASSERT_GT(line, 0) << file << ": expect-line must be a line number, got '" << expect.at("line") << "'";
  const std::string key = expect.at("key");
  const std::string message = expect.at("message");

  const std::string scenario = given_path(file);
  const std::string where = scenario + ":" + std::to_string(line) + ":";
  ScratchDir scratch(file.stem().string());
  const fs::path output = scratch.path() / "out";

  const std::vector<std::pair<std::string, std::string>> commands = {
      {"check", "check " + quoted(scenario)},
      {"run", "run " + quoted(scenario) + " -o " + quoted(output.string())}};
  for (const auto& [label, arguments] : commands) {
    SCOPED_TRACE("shard " + label + " " + scenario);
    const Result r = run_shard(arguments, scratch.path());
    EXPECT_EQ(r.status, 2) << "exit status; stderr:\n" << r.err;
    EXPECT_TRUE(contains(r.err, where)) << "expected '" << where << "' in:\n" << r.err;
    if (key == "(none)")
      EXPECT_FALSE(contains(r.err, "key '")) << "expected no key in:\n" << r.err;
    else
      EXPECT_TRUE(contains(r.err, "key '" + key + "'")) << "expected key '" << key << "' in:\n" << r.err;
    EXPECT_TRUE(contains(r.err, message)) << "expected '" << message << "' in:\n" << r.err;
    EXPECT_FALSE(contains(r.err, "internal error")) << r.err;
    EXPECT_FALSE(fs::exists(output)) << "bad input must write nothing, but " << output << " exists";
  }
}

INSTANTIATE_TEST_SUITE_P(Files, BadInput, ::testing::ValuesIn(case_files()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(BadInput);  // the next test reports an empty folder

TEST(BadInputSuite, HoldsEnoughDistinctCases) {
  const auto files = case_files();
  EXPECT_GE(files.size(), kMinimumCases) << "tests/bad_input/ must hold at least " << kMinimumCases
                                         << " cases (" << case_folder() << ")";
  // Distinct: no two files expect the same key with the same message.
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& f : files) {
    const auto e = expectations(f);
    const auto key = e.count("key") ? e.at("key") : "";
    const auto message = e.count("message") ? e.at("message") : "";
    EXPECT_TRUE(seen.insert({key, message}).second)
        << f << " repeats the expectation of another case: key '" << key << "', '" << message << "'";
  }
}

}  // namespace
