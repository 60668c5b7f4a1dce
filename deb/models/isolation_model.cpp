#include "deb/models/isolation_model.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <limits>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"

namespace deb {
namespace {

// R_phi of eq. 3-9: local (p, q, r) -> body (x, y, z), thesis sign convention.
Eigen::Matrix3d RotationPhi(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  Eigen::Matrix3d r;
  r << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

// R_0i of eq. 3-13, the cross-product matrix of r_i.
Eigen::Matrix3d Skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d s;
  s << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return s;
}

// T_i = [I; R_0i]: maps a force at P_i to CoG force and moment; T_i^T maps q
// to the displacement of P_i (x + theta x r_i).
Eigen::Matrix<double, 6, 3> PointMap(const Eigen::Vector3d& r) {
  Eigen::Matrix<double, 6, 3> t;
  t << Eigen::Matrix3d::Identity(), Skew(r);
  return t;
}

// F_i = k_ri (w + a y_i + b x_i), from sum F = m g, sum F y = sum F x = 0.
Eigen::VectorXd StaticForces(const IsolationSystem& s) {
  const auto n = static_cast<Eigen::Index>(s.isolators.size());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  if (s.body.gravity == 0.0) return f;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  for (const Isolator& iso : s.isolators) {
    const Eigen::Vector3d u(1.0, iso.position.y(), iso.position.x());
    normal += iso.stiffness.z() * u * u.transpose();
  }
  const Eigen::Vector3d c =
      normal.fullPivLu().solve(Eigen::Vector3d(s.body.mass * s.body.gravity, 0.0, 0.0));
  for (Eigen::Index i = 0; i < n; ++i) {
    const Isolator& iso = s.isolators[i];
    f(i) = iso.stiffness.z() * (c(0) + c(1) * iso.position.y() + c(2) * iso.position.x());
  }
  return f;
}

// Eq. 3-13 with per-isolator pre-stress F_i (zero: no gravity terms).
Matrix6d Stiffness(const IsolationSystem& s, const Eigen::VectorXd& forces) {
  Matrix6d k = Matrix6d::Zero();
  for (std::size_t i = 0; i < s.isolators.size(); ++i) {
    const Isolator& iso = s.isolators[i];
    Eigen::Vector3d kp = iso.stiffness;
    if (iso.spring_length) kp.head<2>().array() -= forces(i) / *iso.spring_length;  // eq. 3-7
    const Eigen::Matrix3d r = RotationPhi(iso.rotation_rad);
    const Eigen::Matrix<double, 6, 3> t = PointMap(iso.position);
    k += t * (r * kp.asDiagonal() * r.transpose()) * t.transpose();
    k(3, 3) += forces(i) * iso.position.z();
    k(4, 4) += forces(i) * iso.position.z();
  }
  return 0.5 * (k + k.transpose());  // exactly symmetric, not just to round-off
}

Matrix6d Damping(const IsolationSystem& s) {
  Matrix6d d = Matrix6d::Zero();
  for (const Isolator& iso : s.isolators) {
    const Eigen::Matrix3d r = RotationPhi(iso.rotation_rad);
    const Eigen::Matrix<double, 6, 3> t = PointMap(iso.position);
    d += t * (r * iso.damping.asDiagonal() * r.transpose()) * t.transpose();
  }
  return 0.5 * (d + d.transpose());
}

Eigen::Vector3d Unit(int axis) { return Eigen::Vector3d::Unit(axis); }

// Pseudo-inverse of a matrix that must have rank 6 (its 6-sided dimension).
Eigen::MatrixXd FullRankPinv(const Eigen::MatrixXd& m, const std::string& what) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  int rank = 0;
  for (Eigen::Index i = 0; i < sv.size(); ++i)
    if (sv(i) > 1e-10 * sv(0)) ++rank;
  if (sv.size() < 6 || rank < 6) throw InputError(what + " (rank " + std::to_string(rank) + " < 6)");
  return svd.matrixV() * sv.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
}

Eigen::MatrixXd StateMatrix(const Matrix6d& m_inv, const Matrix6d& k, const Matrix6d& d) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(12, 12);
  a.topRightCorner(6, 6).setIdentity();
  a.bottomLeftCorner(6, 6) = -m_inv * k;
  a.bottomRightCorner(6, 6) = -m_inv * d;
  return a;
}

std::string PoleText(std::complex<double> p) {
  std::ostringstream os;
  os << std::setprecision(6) << p.real() << (p.imag() < 0 ? " - " : " + ")
     << std::abs(p.imag()) << "j";
  return os.str();
}

// Exact variances need every pole strictly in the left half plane; a pole at
// (numerically) zero is a DOF that is neither supported nor controlled.
bool IsUnstablePole(std::complex<double> p, double scale) { return p.real() >= -1e-10 * scale; }

double PoleScale(const Eigen::VectorXcd& p) {
  return p.size() ? std::max(1.0, p.cwiseAbs().maxCoeff()) : 1.0;
}

bool IsAsymptoticallyStable(const Eigen::VectorXcd& p) {
  for (Eigen::Index i = 0; i < p.size(); ++i)
    if (IsUnstablePole(p(i), PoleScale(p))) return false;
  return true;
}

void RequireStable(const Eigen::MatrixXd& a, const std::string& what) {
  const Eigen::VectorXcd p = Eigen::EigenSolver<Eigen::MatrixXd>(a, false).eigenvalues();
  std::string bad;
  for (Eigen::Index i = 0; i < p.size(); ++i)
    if (IsUnstablePole(p(i), PoleScale(p)) && p(i).imag() >= 0.0)
      bad += (bad.empty() ? "" : ", ") + PoleText(p(i));
  if (!bad.empty())
    throw InputError(what + " is not stable; poles with Re >= 0 [rad/s]: " + bad +
                     " (check the skyhook gains, the sensing and motor matrices and their signs, "
                     "and that every DOF is supported or controlled)");
}

std::vector<IsolationMode> Modes(const Matrix6d& m, const Matrix6d& k, const Matrix6d& d) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> es(k, m);
  std::vector<IsolationMode> modes;
  for (int j = 0; j < 6; ++j) {
    const double w2 = es.eigenvalues()(j);
    const Vector6d phi = es.eigenvectors().col(j);  // phi^T M phi = 1
    IsolationMode mode;
    mode.f_hz = (w2 >= 0 ? 1.0 : -1.0) * std::sqrt(std::abs(w2)) / (2 * kPi);
    mode.damping_ratio = w2 > 0 ? phi.dot(d * phi) / (2 * std::sqrt(w2))
                                : std::numeric_limits<double>::quiet_NaN();
    mode.energy_share = phi.cwiseProduct(m * phi);
    mode.energy_share.maxCoeff(&mode.dominant_dof);
    mode.shape = phi / phi(mode.dominant_dof);
    modes.push_back(mode);
  }
  return modes;
}

}  // namespace

const std::vector<std::string>& CogDofNames() {
  static const std::vector<std::string> names = {"x", "y", "z", "alpha", "beta", "gamma"};
  return names;
}

IsolationModel::IsolationModel(IsolationSystem system) : system_(std::move(system)) {
  system_.Validate();
  const IsolationSystem& s = system_;

  mass_ = Matrix6d::Zero();
  mass_.topLeftCorner<3, 3>() = s.body.mass * Eigen::Matrix3d::Identity();
  mass_.bottomRightCorner<3, 3>() = s.body.inertia;
  static_forces_ = StaticForces(s);
  stiffness_ = Stiffness(s, static_forces_);
  stiffness_no_gravity_ = Stiffness(s, Eigen::VectorXd::Zero(static_forces_.size()));
  damping_ = Damping(s);

  // eq. 3-38..3-41: a sensor reads e_axis^T T_i^T q'.
  sensor_kinematics_.resize(static_cast<Eigen::Index>(s.sensors.size()), 6);
  for (std::size_t j = 0; j < s.sensors.size(); ++j) {
    const Isolator& iso = s.isolators[s.IsolatorIndex(s.sensors[j].isolator)];
    sensor_kinematics_.row(j) =
        (PointMap(iso.position) * Unit(static_cast<int>(s.sensors[j].axis))).transpose();
  }
  // eq. 3-18: an actuator pushes along R_phi e_axis at P_i.
  actuator_map_.resize(6, static_cast<Eigen::Index>(s.actuators.size()));
  for (std::size_t j = 0; j < s.actuators.size(); ++j) {
    const Isolator& iso = s.isolators[s.IsolatorIndex(s.actuators[j].isolator)];
    actuator_map_.col(j) = PointMap(iso.position) * RotationPhi(iso.rotation_rad) *
                           Unit(static_cast<int>(s.actuators[j].axis));
  }

  if (!s.sensors.empty()) {
    sensing_ = s.control.sensing.size() > 0
                   ? s.control.sensing
                   : FullRankPinv(sensor_kinematics_,
                                  "control.sensing: not given, and it cannot be derived as the "
                                  "pseudo-inverse of the sensor kinematics because the sensors "
                                  "do not observe all six DOF");
  }
  if (!s.actuators.empty()) {
    motor_ = s.control.motor.size() > 0
                 ? s.control.motor
                 : FullRankPinv(actuator_map_,
                                "control.motor: not given, and it cannot be derived as the "
                                "pseudo-inverse of the actuator map because the actuators "
                                "do not reach all six DOF");
  }

  const Matrix6d m_inv = mass_.inverse();
  a_open_ = StateMatrix(m_inv, stiffness_, damping_);
  if (has_control()) {
    a_closed_ = a_open_;
    a_closed_.bottomRightCorner(6, 6) -= m_inv * actuator_map_ * motor_ *
                                         s.control.gains.asDiagonal() * sensing_ *
                                         sensor_kinematics_;
  }
}

StateSpace IsolationModel::Path(Loop loop, const Eigen::MatrixXd& b, Outputs outputs,
                                const char* what) const {
  if (loop == Loop::kClosed) {
    if (!has_control())
      throw InputError(std::string(what) +
                       ": a closed loop needs at least one sensor and one actuator");
    RequireStable(a_closed_, std::string("closed loop (") + what + ")");
  }
  const int ny = outputs == Outputs::kVelocity ? 6 : 12;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(ny, 12);
  c.topRightCorner(6, 6).setIdentity();
  if (ny == 12) c.bottomLeftCorner(6, 6).setIdentity();
  return StateSpace(loop == Loop::kClosed ? a_closed_ : a_open_, b, c,
                    Eigen::MatrixXd::Zero(ny, b.cols()));
}

StateSpace IsolationModel::FloorToCog(Loop loop, Outputs outputs) const {
  // States (q - E x_f, q'): q_r' = q' - E v_f, M q'' = ... + D E v_f.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(12, 3);
  b.topRows(3) = -Eigen::Matrix3d::Identity();
  b.bottomRows(6) = mass_.inverse() * damping_.leftCols(3);
  return Path(loop, b, outputs, "floor -> CoG");
}

StateSpace IsolationModel::SensorNoiseToCog(Outputs outputs) const {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(12, sensor_kinematics_.rows());
  if (has_control())
    b.bottomRows(6) = -mass_.inverse() * actuator_map_ * motor_ *
                      system_.control.gains.asDiagonal() * sensing_;
  return Path(Loop::kClosed, b, outputs, "sensor noise -> CoG");
}

StateSpace IsolationModel::ActuatorToCog(Loop loop, Outputs outputs) const {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(12, actuator_map_.cols());
  b.bottomRows(6) = mass_.inverse() * actuator_map_;
  return Path(loop, b, outputs, "actuator force -> CoG");
}

std::vector<std::string> IsolationModel::OutputNames(Outputs outputs) {
  std::vector<std::string> names;
  for (const auto& n : CogDofNames()) names.push_back(n + "_dot");
  if (outputs == Outputs::kVelocityAndPosition)
    for (const auto& n : CogDofNames()) names.push_back(n);
  return names;
}

std::vector<std::string> IsolationModel::FloorInputNames() {
  return {"floor_x_dot", "floor_y_dot", "floor_z_dot"};
}

IsolationModelSummary IsolationModel::Summary() const {
  IsolationModelSummary sum;
  for (const auto& iso : system_.isolators) sum.isolators.push_back(iso.name);
  sum.static_forces = static_forces_;
  sum.modes = Modes(mass_, stiffness_, damping_);
  sum.modes_without_gravity = Modes(mass_, stiffness_no_gravity_, damping_);
  sum.has_control = has_control();
  if (has_control()) {
    const Eigen::VectorXcd poles = Eigen::EigenSolver<Eigen::MatrixXd>(a_closed_, false).eigenvalues();
    sum.closed_loop_modes = ModesFromPoles(poles);
    sum.closed_loop_stable = IsAsymptoticallyStable(poles);
  }
  return sum;
}

std::string IsolationModelSummary::Report() const {
  std::ostringstream os;
  os << std::fixed;
  os << "Static pre-stress of the vertical springs (force units; sum = m g):\n";
  os << "  " << std::left << std::setw(16) << "isolator" << std::right << std::setw(14) << "F_i"
     << "\n";
  for (std::size_t i = 0; i < isolators.size(); ++i)
    os << "  " << std::left << std::setw(16) << isolators[i] << std::right << std::setw(14)
       << std::setprecision(4) << static_forces(static_cast<Eigen::Index>(i)) << "\n";

  const auto table = [&os](const char* title, const std::vector<IsolationMode>& modes) {
    os << title << "\n";
    os << "   #    f [Hz]  zeta [%]  dominant   energy share [%], signed as the shape:\n";
    os << "                                   ";
    for (const auto& n : CogDofNames()) os << std::setw(8) << n;
    os << "\n";
    for (std::size_t j = 0; j < modes.size(); ++j) {
      const IsolationMode& m = modes[j];
      os << std::setw(4) << j + 1 << std::setw(10) << std::setprecision(4) << m.f_hz;
      if (std::isnan(m.damping_ratio))
        os << std::setw(10) << "-";
      else
        os << std::setw(10) << std::setprecision(2) << 100 * m.damping_ratio;
      os << "  " << std::left << std::setw(9) << CogDofNames()[m.dominant_dof] << std::right
         << std::setprecision(1);
      for (int k = 0; k < 6; ++k) {
        const double pct = (m.shape(k) < 0 ? -100.0 : 100.0) * m.energy_share(k);
        os << std::setw(8) << (std::abs(pct) < 0.05 ? 0.0 : pct);  // no "-0.0"
      }
      os << "\n";
    }
  };
  table("Open-loop modes with gravity terms (undamped f, modal damping; f < 0: divergent):",
        modes);
  table("Open-loop modes without gravity terms (g = 0):", modes_without_gravity);

  if (!has_control) {
    os << "Closed loop: none (no sensors or no actuators).\n";
    return os.str();
  }
  os << "Closed-loop modes (" << (closed_loop_stable ? "stable" : "NOT stable") << "):\n";
  os << "      f [Hz]  zeta [%]      pole [rad/s]\n";
  for (const Mode& m : closed_loop_modes)
    os << std::setw(12) << std::setprecision(4) << m.f_n_hz << std::setw(10)
       << std::setprecision(2) << 100 * m.damping_ratio << "      " << PoleText(m.pole_rad_s)
       << (m.pair ? " (pair)" : "") << "\n";
  return os.str();
}

}  // namespace deb
