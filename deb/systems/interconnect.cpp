#include "deb/systems/interconnect.h"

#include <sstream>
#include <utility>

#include "deb/core/error.h"

namespace deb {
namespace {

using Eigen::MatrixXd;

void RequireEqual(const char* operation, const char* what_a, int a, const char* what_b, int b) {
  if (a == b) return;
  std::ostringstream os;
  os << operation << ": size mismatch, " << what_a << " = " << a << " but " << what_b << " = "
     << b;
  throw InputError(os.str());
}

MatrixXd BlockDiag(const MatrixXd& x, const MatrixXd& y) {
  MatrixXd m = MatrixXd::Zero(x.rows() + y.rows(), x.cols() + y.cols());
  m.topLeftCorner(x.rows(), x.cols()) = x;
  m.bottomRightCorner(y.rows(), y.cols()) = y;
  return m;
}

MatrixXd VStack(const MatrixXd& x, const MatrixXd& y) {
  MatrixXd m(x.rows() + y.rows(), x.cols());
  m << x, y;
  return m;
}

MatrixXd HStack(const MatrixXd& x, const MatrixXd& y) {
  MatrixXd m(x.rows(), x.cols() + y.cols());
  m << x, y;
  return m;
}

}  // namespace

StateSpace Series(const StateSpace& first, const StateSpace& second) {
  RequireEqual("Series", "second.inputs", second.inputs(), "first.outputs", first.outputs());
  // x = (x1, x2): x2' = A2 x2 + B2 (C1 x1 + D1 u).
  const int n1 = first.states(), n2 = second.states();
  MatrixXd a = MatrixXd::Zero(n1 + n2, n1 + n2);
  a.topLeftCorner(n1, n1) = first.A();
  a.bottomLeftCorner(n2, n1) = second.B() * first.C();
  a.bottomRightCorner(n2, n2) = second.A();
  return StateSpace(std::move(a), VStack(first.B(), second.B() * first.D()),
                    HStack(second.D() * first.C(), second.C()), second.D() * first.D());
}

StateSpace Parallel(const StateSpace& a, const StateSpace& b) {
  RequireEqual("Parallel", "a.inputs", a.inputs(), "b.inputs", b.inputs());
  RequireEqual("Parallel", "a.outputs", a.outputs(), "b.outputs", b.outputs());
  return StateSpace(BlockDiag(a.A(), b.A()), VStack(a.B(), b.B()), HStack(a.C(), b.C()),
                    a.D() + b.D());
}

StateSpace Append(const StateSpace& a, const StateSpace& b) {
  return StateSpace(BlockDiag(a.A(), b.A()), BlockDiag(a.B(), b.B()), BlockDiag(a.C(), b.C()),
                    BlockDiag(a.D(), b.D()));
}

StateSpace BlockDiagonal(const std::vector<StateSpace>& systems) {
  if (systems.empty()) throw InputError("BlockDiagonal: needs at least one system");
  int n = 0, m = 0, p = 0;
  for (const auto& s : systems) {
    n += s.states();
    m += s.inputs();
    p += s.outputs();
  }
  MatrixXd a = MatrixXd::Zero(n, n), b = MatrixXd::Zero(n, m);
  MatrixXd c = MatrixXd::Zero(p, n), d = MatrixXd::Zero(p, m);
  int xn = 0, xm = 0, xp = 0;
  for (const auto& s : systems) {
    a.block(xn, xn, s.states(), s.states()) = s.A();
    b.block(xn, xm, s.states(), s.inputs()) = s.B();
    c.block(xp, xn, s.outputs(), s.states()) = s.C();
    d.block(xp, xm, s.outputs(), s.inputs()) = s.D();
    xn += s.states();
    xm += s.inputs();
    xp += s.outputs();
  }
  return StateSpace(std::move(a), std::move(b), std::move(c), std::move(d));
}

StateSpace StackOutputs(const StateSpace& a, const StateSpace& b) {
  RequireEqual("StackOutputs", "a.inputs", a.inputs(), "b.inputs", b.inputs());
  return StateSpace(BlockDiag(a.A(), b.A()), VStack(a.B(), b.B()), BlockDiag(a.C(), b.C()),
                    VStack(a.D(), b.D()));
}

StateSpace Feedback(const StateSpace& plant, const StateSpace& controller, int sign) {
  if (sign != 1 && sign != -1) {
    std::ostringstream os;
    os << "Feedback: sign = " << sign << " must be +1 or -1";
    throw InputError(os.str());
  }
  RequireEqual("Feedback", "controller.inputs", controller.inputs(), "plant.outputs",
               plant.outputs());
  RequireEqual("Feedback", "controller.outputs", controller.outputs(), "plant.inputs",
               plant.inputs());
  const double s = sign;
  const MatrixXd& ap = plant.A();
  const MatrixXd& bp = plant.B();
  const MatrixXd& cp = plant.C();
  const MatrixXd& dp = plant.D();
  const MatrixXd& ak = controller.A();
  const MatrixXd& bk = controller.B();
  const MatrixXd& ck = controller.C();
  const MatrixXd& dk = controller.D();
  const int m = plant.inputs();
  // u_p = u + s (C_k x_k + D_k (C_p x_p + D_p u_p))
  //   =>  u_p = E (u + s D_k C_p x_p + s C_k x_k),   E = (I - s D_k D_p)^-1.
  const MatrixXd loop = MatrixXd::Identity(m, m) - s * dk * dp;
  MatrixXd e = MatrixXd::Identity(m, m);
  if (!dk.isZero(0.0) && !dp.isZero(0.0)) {
    const Eigen::PartialPivLU<MatrixXd> lu(loop);
    const double rcond = lu.rcond();
    if (!(rcond > 1e-12)) {
      std::ostringstream os;
      os << "Feedback: algebraic loop I " << (sign < 0 ? "+" : "-")
         << " D_k D_p through the direct feedthrough of plant and controller is singular"
         << " (reciprocal condition number " << rcond << "); the loop is not well posed";
      throw InputError(os.str());
    }
    e = lu.solve(MatrixXd::Identity(m, m));
  }
  const MatrixXd up_xp = s * e * dk * cp;  // u_p in terms of x_p
  const MatrixXd up_xk = s * e * ck;       // u_p in terms of x_k
  const MatrixXd y_xp = cp + dp * up_xp, y_xk = dp * up_xk, y_u = dp * e;
  const int np = plant.states(), nk = controller.states();
  MatrixXd a(np + nk, np + nk), b(np + nk, m), c(plant.outputs(), np + nk);
  a << ap + bp * up_xp, bp * up_xk, bk * y_xp, ak + bk * y_xk;
  b << bp * e, bk * y_u;
  c << y_xp, y_xk;
  return StateSpace(std::move(a), std::move(b), std::move(c), y_u);
}

}  // namespace deb
