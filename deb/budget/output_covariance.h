// The covariance matrix of a set of outputs (the budget's `covariance:`),
//   Cov_ab = sum over contributors of the integral of Re S_{y_a y_b}(f) df,
//   S_{y_a y_b}(f) = h_a(f) S_u(f) h_b(f)^H   (one-sided, docs/method.md),
// with h the contributor's transfer to each output as the engine applies it
// (path_response.h: unit conversions, weighting), plus each tone exactly,
// Re(y_a conj(y_b)) with y = h(f0) a. Contributors are uncorrelated
// (convention 6), so the matrix is the sum of theirs.
//
// The grid's rule: the cross integrals use the grid's rule that is linear in
// S (LinearQuadratureWeights: Gauss-Lobatto on panels, the trapezoid on the
// intervals outside them), and each contributor's density part is scaled by
// D = diag(sqrt(v_a / L_aa)), v_a the density variance the engine integrated
// (its power-law rule outside panels), so that the diagonal is each output's
// variance exactly and the matrix stays positive semi-definite. On the
// automatic grid (made of panels) D = 1 to rounding, and for an output
// c = a + k b, Var c = Var a + 2k Cov_ab + k^2 Var b holds to rounding.
//
// The exact matrix, where every contributor has an exact variance on every
// output of the set: C P C^T from one Lyapunov solve of the rows stacked
// (PathAnalysis::ExactCovariance; a modal path's in its modal closed form),
// plus the tones, summed over contributors. The grid's responses h are read
// from BudgetResult::traces where the engine kept them.
//
// Outputs with a `metric` have no covariance: a moving std is not a linear
// function of the signal, and a moving average's PSD factor is a lobe average
// without phase beyond OutputMetric::kResolvedLobes.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/budget.h"

namespace deb {

struct BudgetResult;

struct ContributorCovariance {
  std::string name;
  Eigen::MatrixXd matrix;  // unit_a x unit_b; its diagonal is the contributor's variances
};

struct CovarianceResult {
  std::vector<std::string> outputs;   // names, in the order requested
  std::vector<std::string> units;     // each output's unit
  std::vector<std::size_t> index;     // each output's position in BudgetResult::outputs
  Eigen::MatrixXd matrix;             // Cov_ab, unit_a x unit_b; diagonal = each output's variance
  // Cov_ab / sqrt(Cov_aa Cov_bb); NaN where an output's variance is zero.
  Eigen::MatrixXd correlation;
  // Over 0..infinity (Lyapunov), where every contributor has an exact
  // variance on every output; otherwise exact_note says why there is none.
  std::optional<Eigen::MatrixXd> exact_matrix;
  std::string exact_note;
  std::vector<ContributorCovariance> contributors;  // in the budget's order
};

// The request's rules, checked by Budget::Validate.
// @throws InputError at "covariance" (fewer than two outputs) or
//   "covariance[i]" (an output that does not exist, is named twice, or has
//   a metric).
void ValidateCovarianceRequest(const Budget& budget);

// The covariance of budget.covariance's outputs, from the result of
// Evaluate(budget) (its grid, paths and contributors' variances).
// DEB_DEMANDs a validated request.
// @throws InputError as the engine's propagation (poles on the grid).
CovarianceResult ComputeOutputCovariance(const Budget& budget, const BudgetResult& result, int threads = 0);

}  // namespace deb
