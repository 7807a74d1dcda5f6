#include "material/composite_damage.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/tensor_ops.hpp"

namespace shard {

namespace {

// Voigt slots of the material frame follow the spatial ones: 11, 22, 33, 12, 23, 13.
// The damage variable of each: d1, d2, d3 on the normal moduli, d4 on G12, d6 on G23, d5 on G13.
constexpr int kDamageOf[6] = {0, 1, 2, 3, 5, 4};

constexpr const char* kDamageMaxKeys[6] = {"d1_max", "d2_max", "d3_max", "d4_max", "d5_max", "d6_max"};

double positive(double x) { return x > 0.0 ? x : 0.0; }

/// Eq. (12): the coupling of the paper (d5 driven by r5 as well as r3, r4).
constexpr std::array<std::array<double, 5>, 6> kCouplingEq12{{{1, 1, 1, 0, 0},
                                                              {0, 0, 1, 1, 0},
                                                              {0, 0, 1, 0, 1},
                                                              {1, 1, 1, 1, 1},
                                                              {0, 0, 1, 1, 1},
                                                              {1, 1, 1, 0, 1}}};
/// The earlier form the paper improves on: d5 not driven by the delamination ratio r5.
constexpr std::array<std::array<double, 5>, 6> kCouplingD5WithoutR5{{{1, 1, 1, 0, 0},
                                                                     {0, 0, 1, 1, 0},
                                                                     {0, 0, 1, 0, 1},
                                                                     {1, 1, 1, 1, 1},
                                                                     {0, 0, 1, 1, 0},
                                                                     {1, 1, 1, 0, 1}}};

/// The paper's model 3: the compression modes (φ2, φ3) do not damage G12 (d4).
constexpr std::array<std::array<double, 5>, 6> kCouplingModel3{{{1, 1, 1, 0, 0},
                                                                {0, 0, 1, 1, 0},
                                                                {0, 0, 1, 0, 1},
                                                                {1, 0, 0, 1, 1},
                                                                {0, 0, 1, 1, 1},
                                                                {1, 1, 1, 0, 1}}};
/// The paper's model 4: as model 3, and no damage on the out-of-plane moduli (d3, d5, d6), which
/// the cohesive interfaces carry.
constexpr std::array<std::array<double, 5>, 6> kCouplingModel4{{{1, 1, 1, 0, 0},
                                                                {0, 0, 1, 1, 0},
                                                                {0, 0, 0, 0, 0},
                                                                {1, 0, 0, 1, 1},
                                                                {0, 0, 0, 0, 0},
                                                                {0, 0, 0, 0, 0}}};

/// Solves the 3×3 system A x = b by Cramer's rule (A well conditioned: see secant_stress).
void solve3(const double A[3][3], const double* b, double* x) {
  const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                     A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                     A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  for (int c = 0; c < 3; ++c) {
    double M[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) M[r][k] = k == c ? b[r] : A[r][k];
    x[c] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
            M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
           det;
  }
}

/// The components of a symmetric tensor (Voigt, tensor shears) in the frame of the orthonormal
/// axes a[0..2]: t'_ij = a_i · t · a_j; `to_axes` false does the inverse, t = Σ t'_ij a_i ⊗ a_j.
void change_frame(const double a[3][3], const double* t, double* out, bool to_axes) {
  static constexpr int kPair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
  const double T[3][3] = {{t[xx], t[xy], t[zx]}, {t[xy], t[yy], t[yz]}, {t[zx], t[yz], t[zz]}};
  for (int k = 0; k < 6; ++k) {
    const int i = kPair[k][0], j = kPair[k][1];
    double sum = 0.0;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        sum += to_axes ? a[i][r] * T[r][c] * a[j][c] : a[r][i] * T[r][c] * a[c][j];
    out[k] = sum;
  }
}

}  // namespace

std::array<std::array<double, 5>, 6> coupling_matrix(const std::string& name) {
  if (name == "eq12") return kCouplingEq12;
  if (name == "d5_without_r5") return kCouplingD5WithoutR5;
  if (name == "model_3") return kCouplingModel3;
  if (name == "model_4") return kCouplingModel4;
  throw ParameterError("coupling", "expected eq12, d5_without_r5, model_3 or model_4, not '" + name + "'");
}

std::array<std::array<double, 3>, 3> OrthotropicConstants::normal_compliance() const {
  std::array<std::array<double, 3>, 3> S{};
  S[0][0] = 1.0 / E1;
  S[1][1] = 1.0 / E2;
  S[2][2] = 1.0 / E3;
  S[0][1] = S[1][0] = -nu12 / E1;
  S[0][2] = S[2][0] = -nu13 / E1;
  S[1][2] = S[2][1] = -nu23 / E2;
  return S;
}

double OrthotropicConstants::largest_stiffness() const {
  const auto S = normal_compliance();
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = S[r][c];
  const Eigen::Matrix3d C = m.inverse();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C, Eigen::EigenvaluesOnly);
  // Mandel form: the shear block is 2G on each tensor shear.
  return std::max({eig.eigenvalues()(2), 2.0 * G12, 2.0 * G13, 2.0 * G23});
}

CompositeDamage::CompositeDamage(std::string name, double density, CompositeDamageParameters p)
    : Material(std::move(name), density), p_(p), S0_(p.elastic.normal_compliance()) {
  // The stable step, the bulk viscosity and the hourglass control see an isotropic stand-in
  // whose P-wave modulus is the stiffest the material has (a bound on every wave speed).
  const double shear = std::max({p.elastic.G12, p.elastic.G13, p.elastic.G23});
  const double constrained = p.elastic.largest_stiffness();
  wave_moduli_ = {constrained - 4.0 * shear / 3.0, shear};
}

std::vector<std::string> CompositeDamage::state_names() const {
  return {"axis1_x", "axis1_y", "axis1_z", "axis2_x", "axis2_y", "axis2_z", "strain_11", "strain_22",
          "strain_33", "strain_12", "strain_23", "strain_13", "r1", "r2", "r3", "r4", "r5", "d1", "d2",
          "d3", "d4", "d5", "d6", "failed", "energy_density", "point_volume", "strain_rate"};
}

void CompositeDamage::initialise(double* state, std::size_t points) const {
  std::fill(state, state + points * slot_count, 0.0);
  for (std::size_t q = 0; q < points; ++q) {
    double* s = state + q * slot_count;
    s[axis1_x] = 1.0;  // global axes until set-up applies the part's orientation
    s[axis2_y] = 1.0;
    for (int j = 0; j < 5; ++j) s[r1 + j] = 1.0;
  }
}

void CompositeDamage::secant_stress(const double* strain, const double* d, double* stress, double* effective) const {
  // S(d) σ = ε with σ = (1 − d) σ̃ reads A σ̃ = ε, A_ii = 1/E_i, A_ij = S0_ij (1 − d_j): finite
  // and well conditioned even where a d_i reaches 1 (unlike S(d) itself).
  double A[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A[i][j] = i == j ? S0_[i][i] : S0_[i][j] * (1.0 - d[j]);
  double eff[6];
  solve3(A, strain, eff);
  const OrthotropicConstants& c = p_.elastic;
  eff[3] = 2.0 * c.G12 * strain[3];
  eff[4] = 2.0 * c.G23 * strain[4];
  eff[5] = 2.0 * c.G13 * strain[5];
  for (int k = 0; k < 6; ++k) {
    stress[k] = (1.0 - d[kDamageOf[k]]) * eff[k];
    if (effective) effective[k] = eff[k];
  }
}

void CompositeDamage::load_ratios(const double* s, double f, double* ratio) const {
  const double s11 = s[0], s22 = s[1], s33 = s[2], s12 = s[3], s23 = s[4], s13 = s[5];
  const double XT = f * p_.XT, XC = f * p_.XC, YT = f * p_.YT, YC = f * p_.YC, ZT = f * p_.ZT;
  const double ZC = f * p_.ZC, S12 = f * p_.S12, S13 = f * p_.S13, S23 = f * p_.S23, Sfs = f * p_.Sfs;
  const double tphi = p_.tan_friction;
  auto sq = [](double x) { return x * x; };
  // Eq. (5): fibre tension with fibre–matrix debonding.
  ratio[0] = sq(positive(s11) / XT) + (s12 * s12 + s13 * s13) / (Sfs * Sfs);
  // Eq. (6): fibre compression, helped by transverse compression.
  ratio[1] = sq(positive(-s11 + 0.5 * positive(-s22 - s33)) / XC);
  // Eq. (7): crush under pressure.
  ratio[2] = sq(positive(-(s11 + s22 + s33)) / (3.0 * ZC));
  // Eq. (8): transverse (matrix) cracking; compression across the ply raises the shear strength.
  ratio[3] = sq(positive(s22) / YT) + sq(positive(-s22) / YC) + sq(s12 / (S12 + positive(-s22) * tphi)) +
             sq(s23 / (S23 + positive(-s22) * tphi));
  // Eq. (9): delamination (out of plane); the paper writes Y_T, equal to Z_T in its table.
  ratio[4] = sq(positive(s33) / ZT) + sq(s13 / (S13 + positive(-s33) * tphi)) +
             sq(s23 / (S23 + positive(-s33) * tphi));
  for (int j = 0; j < 5; ++j) ratio[j] = std::sqrt(ratio[j]);
}

void CompositeDamage::update(MaterialPointBatch& batch) const {
  const double m = p_.m;
  for (std::size_t q = 0; q < batch.count; ++q) {
    // A point without volume belongs to an element that has left the force computation (eroded,
    // by its shape or its state, or turned inside out): the kernel books what it held; nothing
    // changes here.
    if (batch.volume && !(batch.volume[q] > 0.0)) continue;
    double* hs = batch.state + q * slot_count;
    double* sig = batch.stress + kTensorSize * q;
    const double* de = batch.strain_increment + kTensorSize * q;
    // 1. The axes turn with the material: a ← R a by the step's Hughes–Winget rotation, then
    // re-orthonormalised (R is orthogonal; this only stops round-off from accumulating).
    double a[3][3] = {{hs[axis1_x], hs[axis1_y], hs[axis1_z]}, {hs[axis2_x], hs[axis2_y], hs[axis2_z]}, {}};
    if (batch.spin) {
      const double* w = batch.spin + 3 * q;
      double R[3][3];
      hughes_winget_rotation(w[0], w[1], w[2], 0.5 * batch.dt, R);
      for (int i = 0; i < 2; ++i) {
        const double v[3] = {a[i][0], a[i][1], a[i][2]};
        for (int r = 0; r < 3; ++r) a[i][r] = R[r][0] * v[0] + R[r][1] * v[1] + R[r][2] * v[2];
      }
    }
    const double n1 = std::sqrt(a[0][0] * a[0][0] + a[0][1] * a[0][1] + a[0][2] * a[0][2]);
    for (int r = 0; r < 3; ++r) a[0][r] /= n1;
    const double dot = a[0][0] * a[1][0] + a[0][1] * a[1][1] + a[0][2] * a[1][2];
    for (int r = 0; r < 3; ++r) a[1][r] -= dot * a[0][r];
    const double n2 = std::sqrt(a[1][0] * a[1][0] + a[1][1] * a[1][1] + a[1][2] * a[1][2]);
    for (int r = 0; r < 3; ++r) a[1][r] /= n2;
    a[2][0] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
    a[2][1] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
    a[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    for (int r = 0; r < 3; ++r) {
      hs[axis1_x + r] = a[0][r];
      hs[axis2_x + r] = a[1][r];
    }

    // 2. Total strain in the axes.
    double de_axes[6];
    change_frame(a, de, de_axes, true);
    double* eps = hs + strain_11;
    for (int k = 0; k < 6; ++k) eps[k] += de_axes[k];

    // 3. Damage: load ratios from the effective stress at the damage of the last step.
    double* d = hs + d1;
    double sigma_axes[6], effective[6];
    if (p_.damage) {
      double factor = 1.0;
      if (p_.rate_coefficient > 0.0 && batch.dt > 0.0) {
        const double eq = std::sqrt(2.0 / 3.0 * double_contraction(de, de)) / batch.dt;
        hs[strain_rate] += batch.dt / (batch.dt + p_.rate_filter_time) * (eq - hs[strain_rate]);
        if (hs[strain_rate] > p_.threshold_strain_rate)
          factor = std::max(1.0, 1.0 + p_.rate_coefficient * std::log(hs[strain_rate] / p_.reference_strain_rate));
      }
      secant_stress(eps, d, sigma_axes, effective);
      double ratio[5];
      load_ratios(effective, factor, ratio);
      double phi[5];
      for (int j = 0; j < 5; ++j) {
        hs[r1 + j] = std::max(hs[r1 + j], ratio[j]);
        phi[j] = 1.0 - std::exp((1.0 - std::pow(hs[r1 + j], m)) / m);  // eq. (11)
      }
      for (int i = 0; i < 6; ++i) {
        double sum = 0.0;
        for (int j = 0; j < 5; ++j) sum += p_.coupling[i][j] * phi[j];
        d[i] = std::max(d[i], std::min(sum, p_.d_max[i]));  // never heals
      }
      if (p_.erosion != CompositeErosion::none && hs[failed] < 1.0) {
        const double level = p_.erosion_level;
        bool holds = false;
        if (p_.erosion == CompositeErosion::shear_modulus) holds = d[3] >= level * p_.d_max[3];  // eq. (17)
        if (p_.erosion == CompositeErosion::moduli)  // eq. (18)
          holds = d[0] >= level * p_.d_max[0] || d[1] >= level * p_.d_max[1];
        if (p_.erosion == CompositeErosion::load_ratios) holds = phi[3] >= level && phi[4] >= level;  // eq. (19)
        if (holds) hs[failed] = 1.0;
      }
    }
    secant_stress(eps, d, sigma_axes, nullptr);

    // 4. Back to the spatial frame; the energy Ψ = ½ σ : ε, and the dissipation as the stress
    // work less the change of Ψ V (the same split as the other softening models).
    const double old[6] = {sig[0], sig[1], sig[2], sig[3], sig[4], sig[5]};
    change_frame(a, sigma_axes, sig, false);
    const double energy = 0.5 * double_contraction(sigma_axes, eps);
    double mid[6];
    for (int k = 0; k < 6; ++k) mid[k] = 0.5 * (old[k] + sig[k]);
    const double v = batch.volume ? batch.volume[q] : 1.0;
    batch.fracture_work += double_contraction(mid, de) * v - (energy * v - hs[energy_density] * hs[point_volume]);
    hs[energy_density] = energy;
    hs[point_volume] = v;
  }
}

KeyList CompositeDamage::parameters(bool damage) {
  KeyList keys;
  keys.quantity("E11", dim::pressure, "Young's modulus along the fibres (axis 1)").above(0).must_be_given();
  keys.quantity("E22", dim::pressure, "Young's modulus across the fibres in the ply (axis 2)").above(0).must_be_given();
  keys.quantity("E33", dim::pressure, "Young's modulus through the thickness (axis 3); default E22").above(0);
  keys.quantity("G12", dim::pressure, "in-plane shear modulus").above(0).must_be_given();
  keys.quantity("G13", dim::pressure, "out-of-plane shear modulus of the 13 plane; default G12").above(0);
  keys.quantity("G23", dim::pressure, "transverse shear modulus of the 23 plane").above(0).must_be_given();
  const char* pairs[3][2] = {{"nu12", "nu21"}, {"nu13", "nu31"}, {"nu23", "nu32"}};
  for (const auto& pr : pairs) {
    keys.quantity(pr[0], dim::none,
                  std::string("Poisson's ratio ") + pr[0] + " = −ε_j/ε_i under σ_i (give it or " + pr[1] + ")")
        .above(-1)
        .below(1);
    keys.quantity(pr[1], dim::none, std::string("the minor ratio, ") + pr[1] + " = " + pr[0] + "·E_j/E_i (give it or " +
                                        pr[0] + ")")
        .above(-1)
        .below(1);
  }
  keys.quantity("E_f", dim::pressure,
                "a modulus that replaces E11 (the CFRP-crushing paper's flexural modulus of the crush case); "
                "default E11")
      .above(0);
  if (!damage) return keys;
  const char* strengths[][2] = {{"XT", "fibre tensile strength X_T"},
                                {"XC", "fibre compressive strength X_C"},
                                {"YT", "transverse tensile strength Y_T"},
                                {"YC", "transverse compressive strength Y_C"},
                                {"ZT", "through-thickness tensile strength Z_T"},
                                {"ZC", "crush strength Z_C (eq. 7 compares the pressure with it)"},
                                {"S12", "in-plane shear strength S_12"},
                                {"S23", "transverse shear strength S_23"},
                                {"Sfs", "fibre–matrix debonding shear strength S_fs (eq. 5)"}};
  for (const auto& s : strengths) keys.quantity(s[0], dim::pressure, s[1]).above(0).must_be_given();
  keys.quantity("S13", dim::pressure, "out-of-plane shear strength S_13; default S12").above(0);
  keys.quantity("friction_angle", dim::none,
                "φ in degrees: compression across a plane adds ⟨−σ⟩ tan φ to its shear strength (eqs. 8, 9)")
      .at_least(0)
      .below(90)
      .defaults_to("0");
  keys.quantity("m", dim::none, "brittleness exponent of φ_j = 1 − exp((1 − r_jᵐ)/m) (eq. 11)").above(0).defaults_to("10");
  for (const char* name : kDamageMaxKeys)
    keys.quantity(name, dim::none, "the largest value its damage variable reaches").at_least(0).at_most(1).defaults_to("1");
  keys.choice("coupling", {"eq12", "d5_without_r5", "model_3", "model_4"},
              "the coupling matrix q_ij: the paper's eq. (12); the earlier form without r5 in d5; its "
              "model 3 (no compression damage on G12); its model 4 (also none on E33, G13, G23)")
      .defaults_to("eq12");
  keys.choice("erosion_criterion", {"none", "I", "II", "III"},
              "when a point has failed (state `failed`, read by the erosion rule): I d4 at d4_max "
              "(eq. 17), II d1 at d1_max or d2 at d2_max (eq. 18), III φ4 and φ5 at 1 (eq. 19)")
      .defaults_to("none");
  keys.quantity("erosion_level", dim::none, "the fraction of its limit at which a damage or φ counts as reached")
      .above(0)
      .at_most(1)
      .defaults_to("0.99");
  keys.quantity("rate_coefficient", dim::none, "C of the strength increase 1 + C ln(ε̇/ε̇_ref) (eq. 10); 0: off")
      .at_least(0)
      .defaults_to("0");
  keys.quantity("reference_strain_rate", dim::rate, "ε̇_ref of eq. (10)").above(0).defaults_to("750");
  keys.quantity("threshold_strain_rate", dim::rate, "strengths rise only above this filtered strain rate")
      .at_least(0)
      .defaults_to("400");
  keys.quantity("rate_filter_time", dim::time, "time constant of the filter on the equivalent strain rate")
      .at_least(0)
      .defaults_to("1 us");
  return keys;
}

namespace {

double one_of(const ParameterValues& v, const char* major, const char* minor, double Ei, double Ej) {
  if (v.has(major) == v.has(minor))
    throw ParameterError(major, std::string("give exactly one of ") + major + " and " + minor);
  return v.has(major) ? v.number(major) : v.number(minor) * Ei / Ej;
}

}  // namespace

CompositeDamageParameters CompositeDamage::from(const ParameterValues& v, bool damage) {
  CompositeDamageParameters p;
  OrthotropicConstants& c = p.elastic;
  c.E1 = v.has("E_f") ? v.number("E_f") : v.number("E11");
  c.E2 = v.number("E22");
  c.E3 = v.has("E33") ? v.number("E33") : c.E2;
  c.G12 = v.number("G12");
  c.G13 = v.has("G13") ? v.number("G13") : c.G12;
  c.G23 = v.number("G23");
  c.nu12 = one_of(v, "nu12", "nu21", c.E1, c.E2);
  c.nu13 = one_of(v, "nu13", "nu31", c.E1, c.E3);
  c.nu23 = one_of(v, "nu23", "nu32", c.E2, c.E3);
  const auto S = c.normal_compliance();
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) m(r, k) = S[r][k];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m, Eigen::EigenvaluesOnly);
  if (!(eig.eigenvalues()(0) > 0.0)) {
    std::ostringstream out;
    out << "these Poisson's ratios make the compliance indefinite (smallest eigenvalue " << eig.eigenvalues()(0)
        << " 1/Pa): an orthotropic material needs 1 − ν12ν21 − ν23ν32 − ν13ν31 − 2ν21ν32ν13 > 0";
    throw ParameterError("nu12", out.str());
  }
  p.damage = damage;
  if (!damage) return p;
  p.XT = v.number("XT");
  p.XC = v.number("XC");
  p.YT = v.number("YT");
  p.YC = v.number("YC");
  p.ZT = v.number("ZT");
  p.ZC = v.number("ZC");
  p.S12 = v.number("S12");
  p.S13 = v.has("S13") ? v.number("S13") : p.S12;
  p.S23 = v.number("S23");
  p.Sfs = v.number("Sfs");
  p.tan_friction = std::tan(v.number("friction_angle") * std::numbers::pi / 180.0);
  p.m = v.number("m");
  for (int i = 0; i < 6; ++i) p.d_max[i] = v.number(kDamageMaxKeys[i]);
  p.coupling = coupling_matrix(v.texts.count("coupling") ? v.texts.at("coupling") : "eq12");
  const std::string criterion = v.texts.count("erosion_criterion") ? v.texts.at("erosion_criterion") : "none";
  p.erosion = criterion == "I"     ? CompositeErosion::shear_modulus
              : criterion == "II"  ? CompositeErosion::moduli
              : criterion == "III" ? CompositeErosion::load_ratios
                                   : CompositeErosion::none;
  p.erosion_level = v.number("erosion_level");
  p.rate_coefficient = v.number("rate_coefficient");
  p.reference_strain_rate = v.number("reference_strain_rate");
  p.threshold_strain_rate = v.number("threshold_strain_rate");
  p.rate_filter_time = v.number("rate_filter_time");
  return p;
}

namespace {

std::unique_ptr<Material> make(const std::string& name, const ParameterValues& v, bool damage) {
  return std::make_unique<CompositeDamage>(name, v.number("density"), CompositeDamage::from(v, damage));
}

const bool registered_damage = MaterialRegistry::add(
    {"composite_damage",
     "orthotropic ply with continuum damage: five failure modes, six damage variables, erosion "
     "criteria I–III (Matzenmiller, Lubliner & Taylor 1995; the CFRP-crushing paper's eqs. 3–19)",
     "docs/theory/composite_damage.md", [] { return CompositeDamage::parameters(true); },
     [](const std::string& name, const ParameterValues& v) { return make(name, v, true); }});
const bool registered_elastic = MaterialRegistry::add(
    {"orthotropic_elastic", "orthotropic linear elasticity in material axes that turn with the material",
     "docs/theory/composite_damage.md", [] { return CompositeDamage::parameters(false); },
     [](const std::string& name, const ParameterValues& v) { return make(name, v, false); }});

}  // namespace

}  // namespace shard
