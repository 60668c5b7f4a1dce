#include "deb/budget/realisation_gradient.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/core/number_text.h"

namespace deb {

namespace {

bool IsRational(const Path& p) { return !p.measured && !p.modal; }

// p dM/dp of the four matrices, fourth order.
struct RealisationDerivative {
  Eigen::MatrixXd a, b, c, d;
};

// The derivative of one matrix from its values at p (1 +- h) and
// p (1 +- h/2); none (and *why) where the two central differences disagree
// beyond their truncation: the entries are not smooth in p.
std::optional<Eigen::MatrixXd> MatrixDerivative(const Eigen::MatrixXd& up, const Eigen::MatrixXd& down,
                                                const Eigen::MatrixXd& half_up, const Eigen::MatrixXd& half_down,
                                                double h) {
  const Eigen::MatrixXd d_h = (up - down) / (2.0 * h);
  const Eigen::MatrixXd d_half = (half_up - half_down) / h;
  const Eigen::MatrixXd d4 = (4.0 * d_half - d_h) / 3.0;
  if (d4.size() == 0) return d4;
  // Smooth entries: the two differ by ~(3/4) h^2 M'''; rounding adds
  // ~eps |M| / h. A basis that reorders between the steps differs by O(1/h).
  const double scale = std::max({up.cwiseAbs().maxCoeff(), down.cwiseAbs().maxCoeff()});
  const double rounding = 1e3 * std::numeric_limits<double>::epsilon() * scale / h;
  if ((d_half - d_h).cwiseAbs().maxCoeff() > 1e-2 * d4.cwiseAbs().maxCoeff() + rounding) return std::nullopt;
  return d4;
}

// The realisation of H + sigma dH (see the header).
StateSpace Probe(const StateSpace& s, const RealisationDerivative& d, double sigma) {
  const Eigen::Index n = s.states(), m = s.inputs(), r = s.outputs();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n), b(2 * n, m), c(r, 2 * n);
  a.topLeftCorner(n, n) = s.A();
  a.bottomLeftCorner(n, n) = d.a;
  a.bottomRightCorner(n, n) = s.A();
  b << s.B(), d.b;
  c << s.C() + sigma * d.c, sigma * s.C();
  return StateSpace(a, b, c, s.D() + sigma * d.d);
}

bool SameSize(const StateSpace& x, const StateSpace& y) {
  return x.states() == y.states() && x.inputs() == y.inputs() && x.outputs() == y.outputs();
}

// The contributors whose variance on some output differs beyond rounding
// (1e-12 of the output's total), each named once.
std::vector<std::string> MovedContributors(const BudgetResult& x, const BudgetResult& y) {
  std::vector<std::string> moved;
  DEB_DEMAND(x.outputs.size() == y.outputs.size());
  for (std::size_t o = 0; o < x.outputs.size(); ++o) {
    const OutputResult& a = x.outputs[o];
    const OutputResult& b = y.outputs[o];
    DEB_DEMAND(a.contributors.size() == b.contributors.size());
    const double tolerance = 1e-12 * std::max(std::abs(a.variance), std::numeric_limits<double>::min());
    for (std::size_t c = 0; c < a.contributors.size(); ++c)
      if (!(std::abs(a.contributors[c].variance - b.contributors[c].variance) <= tolerance) &&
          std::find(moved.begin(), moved.end(), a.contributors[c].name) == moved.end())
        moved.push_back(a.contributors[c].name);
  }
  return moved;
}

std::string QuotedList(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
  return list;
}

}  // namespace

RealisationGradient ComputeRealisationGradient(const Budget& budget, const BudgetResult& nominal,
                                               const std::array<Budget, 4>& scaled, double step,
                                               const EngineOptions& options, bool verify) {
  RealisationGradient g;
  const double h = step;
  DEB_DEMAND(h > 0.0 && std::isfinite(h));
  // Which rational paths the parameter changes, and their derivatives.
  std::vector<std::optional<RealisationDerivative>> derivative(budget.paths.size());
  std::vector<std::string> changed;
  for (std::size_t i = 0; i < budget.paths.size(); ++i) {
    const Path& p = budget.paths[i];
    for (const Budget& s : scaled) DEB_DEMAND(s.paths.size() == budget.paths.size() && s.paths[i].name == p.name);
    if (!IsRational(p)) continue;  // the check below finds it if it changes
    const StateSpace& nominal_system = p.system;
    bool moved = false;
    for (const Budget& s : scaled) {
      if (!IsRational(s.paths[i]) || !SameSize(s.paths[i].system, nominal_system)) {
        g.note = "path '" + p.name + "' changes its form or size with the parameter";
        return g;
      }
      const StateSpace& x = s.paths[i].system;
      moved = moved || x.A() != nominal_system.A() || x.B() != nominal_system.B() || x.C() != nominal_system.C() ||
              x.D() != nominal_system.D();
    }
    if (!moved) continue;
    const StateSpace& up = scaled[0].paths[i].system;
    const StateSpace& down = scaled[1].paths[i].system;
    const StateSpace& half_up = scaled[2].paths[i].system;
    const StateSpace& half_down = scaled[3].paths[i].system;
    const auto da = MatrixDerivative(up.A(), down.A(), half_up.A(), half_down.A(), h);
    const auto db = MatrixDerivative(up.B(), down.B(), half_up.B(), half_down.B(), h);
    const auto dc = MatrixDerivative(up.C(), down.C(), half_up.C(), half_down.C(), h);
    const auto dd = MatrixDerivative(up.D(), down.D(), half_up.D(), half_down.D(), h);
    if (!da || !db || !dc || !dd) {
      g.note = "path '" + p.name + "': its realisation is not smooth in the parameter (two central differences of "
               "its matrices disagree)";
      return g;
    }
    derivative[i] = RealisationDerivative{*da, *db, *dc, *dd};
    changed.push_back(p.name);
  }
  EngineOptions variances = EngineOptions::VariancesOnly();
  variances.threads = options.threads;
  variances.exact_tolerance = options.exact_tolerance;
  // Nothing else may move: p (1 + h) with the rational paths put back.
  if (verify) {
    Budget check = scaled[0];
    for (std::size_t i = 0; i < budget.paths.size(); ++i)
      if (IsRational(budget.paths[i])) check.paths[i] = budget.paths[i];
    const std::vector<std::string> moved = MovedContributors(Evaluate(check, variances), nominal);
    if (!moved.empty()) {
      g.note = "it moves " + QuotedList(moved) +
               " other than through a rational path's realisation (a source's spectrum, an output's unit or "
               "weighting, or a measured, modal, delayed or sampled path)";
      return g;
    }
  }
  g.exact = true;
  g.d_variance.resize(nominal.outputs.size());
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o)
    g.d_variance[o].assign(nominal.outputs[o].contributors.size(), 0.0);
  if (changed.empty()) {
    g.note = "exact, zero: it changes no path's realisation";
    return g;
  }
  std::array<BudgetResult, 2> probe;  // H + dH, H - dH
  for (int k = 0; k < 2; ++k) {
    Budget b = budget;
    b.grid = ExplicitGrid(nominal.grid);
    for (std::size_t i = 0; i < b.paths.size(); ++i)
      if (derivative[i]) b.paths[i].system = Probe(budget.paths[i].system, *derivative[i], k == 0 ? 1.0 : -1.0);
    probe[k] = Evaluate(b, variances);
  }
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& n = nominal.outputs[o];
    for (std::size_t c = 0; c < n.contributors.size(); ++c) {
      const ContributorResult& cr = n.contributors[c];
      if (std::find(changed.begin(), changed.end(), cr.path) == changed.end()) continue;
      const ContributorResult& plus = probe[0].outputs[o].contributors[c];
      const ContributorResult& minus = probe[1].outputs[o].contributors[c];
      DEB_DEMAND(plus.psd.size() == cr.psd.size() && minus.psd.size() == cr.psd.size());
      DEB_DEMAND(plus.tones.size() == cr.tones.size() && minus.tones.size() == cr.tones.size());
      const std::vector<double> q = IntegralGradientWeights(nominal.grid, cr.psd);
      double dv = 0.0;
      for (std::size_t k = 0; k < q.size(); ++k) dv += q[k] * (0.5 * (plus.psd[k] - minus.psd[k]));
      for (std::size_t t = 0; t < cr.tones.size(); ++t) dv += 0.5 * (plus.tones[t].variance - minus.tones[t].variance);
      g.d_variance[o][c] = dv;
    }
  }
  g.note = "exact, through the realisation of " + QuotedList(changed);
  return g;
}

}  // namespace deb
