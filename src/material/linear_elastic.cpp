#include "material/linear_elastic.hpp"

#include <cmath>
#include <sstream>

#include "core/voigt.hpp"

namespace shard {

void LinearElastic::update(MaterialPointBatch& batch) const {
  const double lambda = moduli_.lame();
  const double two_g = 2.0 * moduli_.shear;
  for (std::size_t p = 0; p < batch.count; ++p) {
    const double* de = batch.strain_increment + kTensorSize * p;
    double* s = batch.stress + kTensorSize * p;
    const double volumetric = lambda * (de[xx] + de[yy] + de[zz]);
    s[xx] += volumetric + two_g * de[xx];
    s[yy] += volumetric + two_g * de[yy];
    s[zz] += volumetric + two_g * de[zz];
    s[xy] += two_g * de[xy];
    s[yz] += two_g * de[yz];
    s[zx] += two_g * de[zx];
  }
}

KeyList LinearElastic::parameters() {
  KeyList keys;
  keys.quantity("youngs_modulus", dim::pressure, "Young's modulus E (give exactly two of E, ν, K, G)")
      .above(0);
  keys.quantity("poissons_ratio", dim::none, "Poisson's ratio ν").above(-1).below(0.5);
  keys.quantity("bulk_modulus", dim::pressure, "bulk modulus K").above(0);
  keys.quantity("shear_modulus", dim::pressure, "shear modulus G").above(0);
  return keys;
}

ElasticModuli LinearElastic::moduli_from(const ParameterValues& v) {
  const char* names[] = {"youngs_modulus", "poissons_ratio", "bulk_modulus", "shear_modulus"};
  int given = 0;
  for (const char* n : names) given += v.has(n) ? 1 : 0;
  if (given != 2) {
    std::ostringstream out;
    out << "give exactly two of youngs_modulus, poissons_ratio, bulk_modulus, shear_modulus (got "
        << given << ")";
    throw ParameterError(given > 2 ? "youngs_modulus" : "model", out.str());
  }
  const bool hE = v.has("youngs_modulus"), hn = v.has("poissons_ratio"), hK = v.has("bulk_modulus"),
             hG = v.has("shear_modulus");
  double K = 0, G = 0;
  // Relations between isotropic constants (any elasticity text, e.g. Sadd, table 6.1).
  if (hK && hG) {
    K = v.number("bulk_modulus");
    G = v.number("shear_modulus");
  } else if (hE && hn) {
    const double E = v.number("youngs_modulus"), nu = v.number("poissons_ratio");
    K = E / (3 * (1 - 2 * nu));
    G = E / (2 * (1 + nu));
  } else if (hE && hG) {
    const double E = v.number("youngs_modulus");
    G = v.number("shear_modulus");
    K = E * G / (3 * (3 * G - E));
  } else if (hE && hK) {
    const double E = v.number("youngs_modulus");
    K = v.number("bulk_modulus");
    G = 3 * K * E / (9 * K - E);
  } else if (hK && hn) {
    const double nu = v.number("poissons_ratio");
    K = v.number("bulk_modulus");
    G = 3 * K * (1 - 2 * nu) / (2 * (1 + nu));
  } else {  // G and ν
    const double nu = v.number("poissons_ratio");
    G = v.number("shear_modulus");
    K = 2 * G * (1 + nu) / (3 * (1 - 2 * nu));
  }
  if (!(K > 0) || !(G > 0) || !std::isfinite(K) || !std::isfinite(G)) {
    std::ostringstream out;
    out << "these constants give K = " << K << " Pa, G = " << G
        << " Pa; an isotropic material needs K > 0 and G > 0 (-1 < ν < 0.5)";
    throw ParameterError(hE ? "youngs_modulus" : "bulk_modulus", out.str());
  }
  return {K, G};
}

namespace {
const bool registered = MaterialRegistry::add(
    {"linear_elastic", "linear isotropic elasticity (rate form, objective Jaumann update)",
     "docs/theory/elements_and_kinematics.md", &LinearElastic::parameters,
     [](const std::string& name, const ParameterValues& v) -> std::unique_ptr<Material> {
       return std::make_unique<LinearElastic>(name, v.number("density"),
                                              LinearElastic::moduli_from(v));
     }});
}  // namespace

}  // namespace shard
