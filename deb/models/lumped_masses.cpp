#include "deb/models/lumped_masses.h"

#include <cmath>

#include "deb/core/error.h"

namespace deb {
namespace {

std::string NameOf(const LumpedMasses& m, int i) {
  return i == LumpedMasses::kGround ? std::string("ground") : "'" + m.names[static_cast<std::size_t>(i)] + "'";
}

void RequireIndex(const LumpedMasses& m, int i, bool ground_allowed, const std::string& what) {
  const int n = static_cast<int>(m.mass_kg.size());
  if (i == LumpedMasses::kGround ? !ground_allowed : (i < 0 || i >= n))
    throw InputError(what + ": " + (i == LumpedMasses::kGround ? std::string("the ground") : "mass " + std::to_string(i)) +
                     " is not allowed here");
}

}  // namespace

void LumpedMasses::Validate() const {
  if (mass_kg.empty()) throw InputError("masses: give at least one mass");
  if (names.size() != mass_kg.size()) throw InputError("masses: one name per mass");
  for (std::size_t i = 0; i < mass_kg.size(); ++i)
    if (!(std::isfinite(mass_kg[i]) && mass_kg[i] > 0.0))
      throw InputError("mass '" + names[i] + "' must be > 0 kg and finite");
  for (std::size_t j = 0; j < couplings.size(); ++j) {
    const Coupling& c = couplings[j];
    const std::string at = "coupling " + std::to_string(j + 1);
    RequireIndex(*this, c.a, true, at);
    RequireIndex(*this, c.b, true, at);
    if (c.a == c.b) throw InputError(at + " joins " + NameOf(*this, c.a) + " to itself");
    if (!(std::isfinite(c.k_n_per_m) && c.k_n_per_m >= 0.0) || !(std::isfinite(c.c_n_s_per_m) && c.c_n_s_per_m >= 0.0))
      throw InputError(at + " (" + NameOf(*this, c.a) + " to " + NameOf(*this, c.b) +
                       "): k and c must be >= 0 and finite");
    if (c.k_n_per_m == 0.0 && c.c_n_s_per_m == 0.0)
      throw InputError(at + " (" + NameOf(*this, c.a) + " to " + NameOf(*this, c.b) + ") has neither k nor c");
  }
}

StateSpace LumpedMasses::Realise(const std::vector<Input>& inputs, const std::vector<Output>& outputs) const {
  Validate();
  const Eigen::Index n = static_cast<Eigen::Index>(mass_kg.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n), c = Eigen::MatrixXd::Zero(n, n);
  const auto add = [](Eigen::MatrixXd& m, int a, int b, double v) {
    if (a != kGround) m(a, a) += v;
    if (b != kGround) m(b, b) += v;
    if (a != kGround && b != kGround) {
      m(a, b) -= v;
      m(b, a) -= v;
    }
  };
  for (const Coupling& j : couplings) {
    add(k, j.a, j.b, j.k_n_per_m);
    add(c, j.a, j.b, j.c_n_s_per_m);
  }
  Eigen::VectorXd m_inv(n);
  for (Eigen::Index i = 0; i < n; ++i) m_inv(i) = 1.0 / mass_kg[static_cast<std::size_t>(i)];
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n).setIdentity();
  a.bottomLeftCorner(n, n) = -(m_inv.asDiagonal() * k);
  a.bottomRightCorner(n, n) = -(m_inv.asDiagonal() * c);

  const Eigen::Index m = static_cast<Eigen::Index>(inputs.size()), p = static_cast<Eigen::Index>(outputs.size());
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(2 * n, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Input& in = inputs[static_cast<std::size_t>(j)];
    const std::string at = "input " + std::to_string(j + 1);
    if (in.on == kGround) {
      if (in.reaction != kGround) throw InputError(at + ": the ground's acceleration has no reaction");
      b.col(j).tail(n).setConstant(-1.0);  // -M 1 a_g / M
      continue;
    }
    RequireIndex(*this, in.on, false, at);
    RequireIndex(*this, in.reaction, true, at);
    if (in.on == in.reaction) throw InputError(at + ": a force and its reaction on the same mass cancel");
    b(n + in.on, j) += m_inv(in.on);
    if (in.reaction != kGround) b(n + in.reaction, j) -= m_inv(in.reaction);
  }
  Eigen::MatrixXd cm = Eigen::MatrixXd::Zero(p, 2 * n);
  for (Eigen::Index i = 0; i < p; ++i) {
    const Output& out = outputs[static_cast<std::size_t>(i)];
    const std::string at = "output " + std::to_string(i + 1);
    RequireIndex(*this, out.of, false, at);
    RequireIndex(*this, out.relative_to, true, at);
    if (out.of == out.relative_to) throw InputError(at + ": a mass relative to itself does not move");
    const Eigen::Index offset = out.velocity ? n : 0;
    cm(i, offset + out.of) = 1.0;
    if (out.relative_to != kGround) cm(i, offset + out.relative_to) = -1.0;
  }
  return StateSpace(std::move(a), std::move(b), std::move(cm), Eigen::MatrixXd::Zero(p, m));
}

}  // namespace deb
