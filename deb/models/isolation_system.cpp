#include "deb/models/isolation_system.h"

#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

#include "deb/core/error.h"

namespace deb {
namespace {

std::string Num(double v) {
  std::ostringstream os;
  os << std::setprecision(15) << v;
  return os.str();
}

std::string Vec(const Eigen::Vector3d& v) {
  return "(" + Num(v.x()) + ", " + Num(v.y()) + ", " + Num(v.z()) + ")";
}

std::string Path(const char* list, std::size_t i, const char* field) {
  return std::string(list) + "[" + std::to_string(i) + "]." + field;
}

[[noreturn]] void Fail(const std::string& path, const std::string& rule) {
  throw InputError(path + ": " + rule);
}

bool AllFinite(const Eigen::MatrixXd& m) { return m.allFinite(); }

void CheckNames(const std::vector<std::string>& names, const char* list) {
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].empty()) Fail(Path(list, i, "name"), "must not be empty");
    if (!seen.insert(names[i]).second)
      Fail(Path(list, i, "name"), "'" + names[i] + "' is used twice; names must be unique");
  }
}

std::string KnownIsolators(const std::vector<Isolator>& isolators) {
  std::string s;
  for (const auto& iso : isolators) s += (s.empty() ? "" : ", ") + iso.name;
  return s;
}

// The supports carry the body only if their plan-view points span a plane:
// rank([1 x_i y_i]) = 3, judged relative to the layout's size.
void CheckNotCollinear(const std::vector<Isolator>& isolators) {
  const auto n = static_cast<Eigen::Index>(isolators.size());
  Eigen::MatrixXd p(n, 3);
  double extent = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    extent = std::max(extent, isolators[i].position.head<2>().cwiseAbs().maxCoeff());
  const double scale = extent > 0.0 ? extent : 1.0;
  for (Eigen::Index i = 0; i < n; ++i)
    p.row(i) << 1.0, isolators[i].position.x() / scale, isolators[i].position.y() / scale;
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(p).singularValues();
  if (sv(2) <= 1e-9 * sv(0))
    Fail("isolators",
         "the supports must not all lie on one line seen from above (x, y positions); "
         "the body could tip over that line");
}

}  // namespace

void RigidBody::Validate() const {
  if (!std::isfinite(mass) || mass <= 0.0)
    Fail("body.mass", Num(mass) + " must be finite and > 0");
  if (!AllFinite(inertia)) Fail("body.inertia", "all entries must be finite");
  const double size = inertia.cwiseAbs().maxCoeff();
  if (!((inertia - inertia.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * size))
    Fail("body.inertia", "must be symmetric (J_ij = J_ji)");
  const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  if (!(eig(0) > 1e-12 * size))
    Fail("body.inertia", "must be positive definite; smallest principal moment is " +
                             Num(eig(0)));
  if (!std::isfinite(gravity) || gravity < 0.0)
    Fail("body.gravity", Num(gravity) + " must be finite and >= 0 (0 = no gravity effects)");
}

int IsolationSystem::IsolatorIndex(const std::string& name) const {
  for (std::size_t i = 0; i < isolators.size(); ++i)
    if (isolators[i].name == name) return static_cast<int>(i);
  return -1;
}

void IsolationSystem::Validate() const {
  body.Validate();

  if (isolators.size() < 3)
    Fail("isolators", "need at least 3 (not all on one line) to carry the body, got " +
                          std::to_string(isolators.size()));
  std::vector<std::string> names;
  for (const auto& iso : isolators) names.push_back(iso.name);
  CheckNames(names, "isolators");
  for (std::size_t i = 0; i < isolators.size(); ++i) {
    const Isolator& iso = isolators[i];
    if (!iso.position.allFinite())
      Fail(Path("isolators", i, "position"), Vec(iso.position) + " must be finite");
    if (!iso.stiffness.allFinite())
      Fail(Path("isolators", i, "stiffness"), Vec(iso.stiffness) + " must be finite");
    if (!(iso.stiffness.z() > 0.0))
      Fail(Path("isolators", i, "stiffness"),
           "k_r = " + Num(iso.stiffness.z()) + " must be > 0 (the vertical springs carry the body)");
    if (!iso.damping.allFinite() || iso.damping.minCoeff() < 0.0)
      Fail(Path("isolators", i, "damping"), Vec(iso.damping) + " must be finite and >= 0");
    if (!std::isfinite(iso.rotation_rad))
      Fail(Path("isolators", i, "rotation"), Num(iso.rotation_rad) + " must be finite");
    if (iso.spring_length && !(std::isfinite(*iso.spring_length) && *iso.spring_length > 0.0))
      Fail(Path("isolators", i, "spring_length"), Num(*iso.spring_length) + " must be > 0");
  }
  CheckNotCollinear(isolators);

  names.clear();
  for (const auto& s : sensors) names.push_back(s.name);
  CheckNames(names, "sensors");
  for (std::size_t i = 0; i < sensors.size(); ++i)
    if (IsolatorIndex(sensors[i].isolator) < 0)
      Fail(Path("sensors", i, "isolator"), "'" + sensors[i].isolator +
                                               "' names no isolator (known: " +
                                               KnownIsolators(isolators) + ")");
  names.clear();
  for (const auto& a : actuators) names.push_back(a.name);
  CheckNames(names, "actuators");
  for (std::size_t i = 0; i < actuators.size(); ++i)
    if (IsolatorIndex(actuators[i].isolator) < 0)
      Fail(Path("actuators", i, "isolator"), "'" + actuators[i].isolator +
                                                 "' names no isolator (known: " +
                                                 KnownIsolators(isolators) + ")");

  const auto ns = static_cast<Eigen::Index>(sensors.size());
  const auto na = static_cast<Eigen::Index>(actuators.size());
  if (control.sensing.size() > 0 && (control.sensing.rows() != 6 || control.sensing.cols() != ns))
    Fail("control.sensing", "must be 6 x " + std::to_string(ns) + " (logical axes x sensors), got " +
                                std::to_string(control.sensing.rows()) + " x " +
                                std::to_string(control.sensing.cols()));
  if (control.motor.size() > 0 && (control.motor.rows() != na || control.motor.cols() != 6))
    Fail("control.motor", "must be " + std::to_string(na) + " x 6 (actuators x logical axes), got " +
                              std::to_string(control.motor.rows()) + " x " +
                              std::to_string(control.motor.cols()));
  if (!AllFinite(control.sensing)) Fail("control.sensing", "all entries must be finite");
  if (!AllFinite(control.motor)) Fail("control.motor", "all entries must be finite");
  for (int j = 0; j < 6; ++j)
    if (!std::isfinite(control.gains(j)))
      Fail("control.gains[" + std::to_string(j) + "]", Num(control.gains(j)) + " must be finite");
}

}  // namespace deb
