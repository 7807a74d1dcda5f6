#include "material/laminate.hpp"

#include <cctype>
#include <cmath>
#include <numbers>

namespace shard {

namespace {

/// Recursive-descent reader of the stacking code.
class LayupReader {
 public:
  explicit LayupReader(const std::string& code) : s_(code) {}

  std::vector<double> read() {
    skip_space();
    if (!at('[')) fail("a stacking sequence starts with '['");
    ++i_;
    std::vector<double> plies = sequence(']');
    ++i_;
    repeat(plies);
    skip_space();
    if (i_ < s_.size() && (s_[i_] == 's' || s_[i_] == 'S')) {
      ++i_;
      std::vector<double> mirror(plies.rbegin(), plies.rend());
      plies.insert(plies.end(), mirror.begin(), mirror.end());
      if (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) {  // "[0/90]s2"
        const std::vector<double> one = plies;
        const int n = count();
        if (one.size() * static_cast<std::size_t>(n) > kMaxPlies) fail("more than " + std::to_string(kMaxPlies) + " plies");
        for (int k = 1; k < n; ++k) plies.insert(plies.end(), one.begin(), one.end());
      }
    }
    skip_space();
    if (i_ != s_.size()) fail("unexpected '" + std::string(1, s_[i_]) + "'");
    if (plies.empty()) fail("no ply");
    return plies;
  }

 private:
  std::vector<double> sequence(char close) {
    std::vector<double> out;
    while (true) {
      skip_space();
      std::vector<double> item = element();
      out.insert(out.end(), item.begin(), item.end());
      skip_space();
      if (at('/')) {
        ++i_;
        continue;
      }
      if (at(close)) return out;
      fail(i_ < s_.size() ? "expected '/' or '" + std::string(1, close) + "', got '" + std::string(1, s_[i_]) + "'"
                          : "missing '" + std::string(1, close) + "'");
    }
  }

  std::vector<double> element() {
    std::vector<double> item;
    if (at('(') || at('[')) {
      const char close = at('(') ? ')' : ']';
      ++i_;
      item = sequence(close);
      ++i_;
    } else if (at('+') && i_ + 1 < s_.size() && s_[i_ + 1] == '-') {
      i_ += 2;
      const double a = angle();
      item = {a, -a};
    } else if (s_.compare(i_, 2, "±") == 0) {
      i_ += 2;
      const double a = angle();
      item = {a, -a};
    } else {
      item = {angle()};
    }
    repeat(item);
    return item;
  }

  double angle() {
    skip_space();
    const std::size_t start = i_;
    if (at('+') || at('-')) ++i_;
    while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.')) ++i_;
    if (i_ == start || (i_ == start + 1 && !std::isdigit(static_cast<unsigned char>(s_[start]))))
      fail("expected a ply angle in degrees");
    double a = 0;
    try {
      a = std::stod(s_.substr(start, i_ - start));
    } catch (const std::exception&) {
      fail("'" + s_.substr(start, i_ - start) + "' is not a ply angle");
    }
    if (std::abs(a) > 180) fail("a ply angle lies within ±180°, got " + s_.substr(start, i_ - start));
    return a;
  }

  /// A repeat count after an item: "_n" or a plain number right after a closing bracket.
  void repeat(std::vector<double>& item) {
    const bool subscript = at('_');
    const bool after_bracket = i_ > 0 && (s_[i_ - 1] == ')' || s_[i_ - 1] == ']');
    if (subscript) ++i_;
    if (!(subscript || after_bracket) || i_ >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[i_]))) {
      if (subscript) fail("expected a repeat count after '_'");
      return;
    }
    const int n = count();
    if (item.size() * static_cast<std::size_t>(n) > kMaxPlies) fail("more than " + std::to_string(kMaxPlies) + " plies");
    const std::vector<double> one = item;
    for (int k = 1; k < n; ++k) item.insert(item.end(), one.begin(), one.end());
  }

  static constexpr std::size_t kMaxPlies = 10000;

  int count() {
    int n = 0;
    while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_])) && n <= 1000) n = 10 * n + (s_[i_++] - '0');
    if (n < 1 || n > 1000) fail("a repeat count is between 1 and 1000");
    return n;
  }

  bool at(char c) const { return i_ < s_.size() && s_[i_] == c; }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw LayupError("stacking sequence '" + s_ + "', at character " + std::to_string(i_ + 1) + ": " + why);
  }

  const std::string& s_;
  std::size_t i_ = 0;
};

}  // namespace

std::vector<double> parse_layup(const std::string& code) { return LayupReader(code).read(); }

std::array<double, 6> ply_axes(const std::array<double, 3>& reference, const std::array<double, 3>& normal,
                               double angle_degrees) {
  auto cross = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  auto unit = [](std::array<double, 3> a) {
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(n > 0)) throw std::invalid_argument("a zero direction");
    for (double& c : a) c /= n;
    return a;
  };
  const auto n = unit(normal);
  const double rn = reference[0] * n[0] + reference[1] * n[1] + reference[2] * n[2];
  std::array<double, 3> r{reference[0] - rn * n[0], reference[1] - rn * n[1], reference[2] - rn * n[2]};
  const double rr = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double ref = std::sqrt(reference[0] * reference[0] + reference[1] * reference[1] + reference[2] * reference[2]);
  if (!(rr > 1e-6 * ref)) throw std::invalid_argument("the reference direction is parallel to the ply normal");
  r = unit(r);
  const auto s = cross(n, r);
  const double t = angle_degrees * std::numbers::pi / 180.0;
  const std::array<double, 3> a1 = unit({std::cos(t) * r[0] + std::sin(t) * s[0], std::cos(t) * r[1] + std::sin(t) * s[1],
                                         std::cos(t) * r[2] + std::sin(t) * s[2]});
  const auto a2 = cross(n, a1);
  return {a1[0], a1[1], a1[2], a2[0], a2[1], a2[2]};
}

}  // namespace shard
