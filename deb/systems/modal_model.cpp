#include "deb/systems/modal_model.h"

#include <cmath>
#include <set>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

void ValidateNames(const std::vector<std::string>& names, Eigen::Index rows, const char* side) {
  const std::string what = std::string(side) + " DOF";
  if (static_cast<Eigen::Index>(names.size()) != rows)
    throw InputError(std::to_string(names.size()) + " " + what + " name(s) for " + std::to_string(rows) +
                     " row(s) of shapes");
  if (names.empty()) throw InputError("no " + what + "s: give at least one");
  if (static_cast<int>(names.size()) > limits::kMaxChannels)
    throw InputError(std::to_string(names.size()) + " " + what + "s; at most " +
                     std::to_string(limits::kMaxChannels) + " are allowed");
  std::set<std::string> seen;
  for (const std::string& n : names) {
    if (n.empty()) throw InputError(what + " name is empty");
    if (!seen.insert(n).second) throw InputError(what + " '" + n + "' is given twice");
  }
}

void ValidateShapes(const Eigen::MatrixXd& phi, const std::vector<std::string>& names, const char* side) {
  for (Eigen::Index k = 0; k < phi.cols(); ++k)
    for (Eigen::Index i = 0; i < phi.rows(); ++i)
      if (!std::isfinite(phi(i, k)))
        throw InputError(std::string(side) + " shape of DOF '" + names[i] + "' in mode " + std::to_string(k + 1) +
                         " is not finite");
}

}  // namespace

int DerivativeOrder(ModalQuantity q) {
  switch (q) {
    case ModalQuantity::kDisplacement: return 0;
    case ModalQuantity::kVelocity: return 1;
    case ModalQuantity::kAcceleration: return 2;
  }
  return 0;
}

std::string ModeFrequencyProblem(double f_hz) {
  if (!std::isfinite(f_hz)) return "natural frequency " + NumberText(f_hz) + " Hz is not finite";
  if (f_hz < 0.0) return "natural frequency " + NumberText(f_hz) + " Hz is negative; it must be >= 0 (0: a rigid-body mode)";
  return "";
}

std::string ModeDampingProblem(double f_hz, double zeta) {
  if (!std::isfinite(zeta)) return "damping ratio " + NumberText(zeta) + " is not finite";
  if (zeta >= 1.0)
    return "damping ratio " + NumberText(zeta) +
           " is >= 1: that is no oscillating mode; model overdamped dynamics as real poles (type: state_space)";
  if (f_hz > 0.0 && !(zeta > 0.0))
    return "damping ratio " + NumberText(zeta) + " of a mode at " + NumberText(f_hz) +
           " Hz must be > 0 (an undamped mode has an infinite variance under white forcing)";
  if (zeta < 0.0) return "damping ratio " + NumberText(zeta) + " is negative";
  return "";
}

void ModalModel::Validate() const {
  const int n = modes();
  if (n == 0) throw InputError("a modal path needs at least one mode");
  if (n > limits::kMaxModes)
    throw InputError(std::to_string(n) + " modes; at most " + std::to_string(limits::kMaxModes) + " are allowed");
  if (static_cast<int>(zeta.size()) != n)
    throw InputError(std::to_string(zeta.size()) + " damping ratio(s) for " + std::to_string(n) + " mode(s)");
  if (phi_in.cols() != n)
    throw InputError("input shapes have " + std::to_string(phi_in.cols()) + " mode(s), the mode table has " +
                     std::to_string(n));
  if (phi_out.cols() != n)
    throw InputError("output shapes have " + std::to_string(phi_out.cols()) + " mode(s), the mode table has " +
                     std::to_string(n));
  for (int k = 0; k < n; ++k) {
    std::string problem = ModeFrequencyProblem(f_hz[k]);
    if (problem.empty()) problem = ModeDampingProblem(f_hz[k], zeta[k]);
    if (!problem.empty()) throw InputError("mode " + std::to_string(k + 1) + ": " + problem);
  }
  if (residual.size() > 0 && (residual.rows() != phi_out.rows() || residual.cols() != phi_in.rows()))
    throw InputError("the static residual is " + std::to_string(residual.rows()) + "x" +
                     std::to_string(residual.cols()) + ", the model has " + std::to_string(phi_out.rows()) +
                     " output(s) and " + std::to_string(phi_in.rows()) + " input(s)");
  ValidateNames(input_names, phi_in.rows(), "input");
  ValidateNames(output_names, phi_out.rows(), "output");
  ValidateShapes(phi_in, input_names, "input");
  ValidateShapes(phi_out, output_names, "output");
}

ModalModel ModalModel::Truncated(double max_hz, bool static_residual) const {
  std::vector<bool> keep(f_hz.size());
  for (std::size_t k = 0; k < f_hz.size(); ++k) keep[k] = f_hz[k] <= max_hz;
  return Kept(keep, static_residual);
}

ModalModel ModalModel::FirstModes(int count, bool static_residual) const {
  std::vector<bool> keep(f_hz.size());
  for (std::size_t k = 0; k < f_hz.size(); ++k) keep[k] = static_cast<int>(k) < count;
  return Kept(keep, static_residual);
}

ModalModel ModalModel::Kept(const std::vector<bool>& keep_mode, bool static_residual) const {
  if (static_residual && quantity != ModalQuantity::kDisplacement)
    throw InputError("residual: static needs output_quantity: displacement (the static correction of a " +
                     ToString(quantity) + " output is not a constant)");
  ModalModel t;
  t.input_names = input_names;
  t.output_names = output_names;
  t.quantity = quantity;
  t.residual = residual;
  t.notes = notes;
  if (static_residual) {
    if (t.residual.size() == 0) t.residual = Eigen::MatrixXd::Zero(phi_out.rows(), phi_in.rows());
    for (int k = 0; k < modes(); ++k) {
      if (keep_mode[static_cast<std::size_t>(k)]) continue;
      if (f_hz[k] == 0.0)
        throw InputError("residual: static cannot correct for a rigid-body mode (mode " + std::to_string(k + 1) +
                         ", 0 Hz: its static compliance is infinite); keep it");
      const double w = kTwoPi * f_hz[k];
      t.residual += phi_out.col(k) * phi_in.col(k).transpose() / (w * w);
    }
  }
  std::vector<Eigen::Index> keep;
  for (int k = 0; k < modes(); ++k)
    if (keep_mode[static_cast<std::size_t>(k)]) keep.push_back(k);
  t.phi_in.resize(phi_in.rows(), static_cast<Eigen::Index>(keep.size()));
  t.phi_out.resize(phi_out.rows(), static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    t.f_hz.push_back(f_hz[keep[j]]);
    t.zeta.push_back(zeta[keep[j]]);
    t.phi_in.col(static_cast<Eigen::Index>(j)) = phi_in.col(keep[j]);
    t.phi_out.col(static_cast<Eigen::Index>(j)) = phi_out.col(keep[j]);
  }
  return t;
}

std::complex<double> ModalPole(double f_hz, double zeta) {
  const double w = kTwoPi * f_hz;
  return {-zeta * w, w * std::sqrt((1.0 - zeta) * (1.0 + zeta))};
}

ModalRealisationParts ModalRealisation(const ModalModel& model) {
  model.Validate();
  const int n = model.modes();
  const Eigen::Index m = model.phi_in.rows(), p = model.phi_out.rows();
  ModalRealisationParts parts;
  parts.blocks.resize(static_cast<std::size_t>(n));
  parts.b = Eigen::MatrixXd::Zero(2 * n, m);
  parts.c = Eigen::MatrixXd::Zero(p, 2 * n);
  parts.d = Eigen::MatrixXd::Zero(p, m);
  for (int k = 0; k < n; ++k) {
    const double w = kTwoPi * model.f_hz[k];
    const double w2 = w * w, two_zeta_w = model.f_hz[k] > 0.0 ? 2.0 * model.zeta[k] * w : 0.0;
    parts.blocks[static_cast<std::size_t>(k)] << 0.0, 1.0, -w2, -two_zeta_w;
    parts.b.row(2 * k + 1) = model.phi_in.col(k).transpose();
    switch (model.quantity) {
      case ModalQuantity::kDisplacement: parts.c.col(2 * k) = model.phi_out.col(k); break;
      case ModalQuantity::kVelocity: parts.c.col(2 * k + 1) = model.phi_out.col(k); break;
      case ModalQuantity::kAcceleration:
        parts.c.col(2 * k) = -w2 * model.phi_out.col(k);
        parts.c.col(2 * k + 1) = -two_zeta_w * model.phi_out.col(k);
        break;
    }
  }
  if (model.quantity == ModalQuantity::kAcceleration) parts.d = model.phi_out * model.phi_in.transpose();
  if (model.residual.size() > 0) parts.d += model.residual;
  return parts;
}

StateSpace ModalStateSpace(const ModalModel& model) {
  ModalRealisationParts parts = ModalRealisation(model);
  const int n = model.modes();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  for (int k = 0; k < n; ++k) a.block<2, 2>(2 * k, 2 * k) = parts.blocks[static_cast<std::size_t>(k)];
  return StateSpace(std::move(a), std::move(parts.b), std::move(parts.c), std::move(parts.d));
}

}  // namespace deb
