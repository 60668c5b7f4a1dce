// Normal modes from OP4 matrices (deb/formats/nastran_modes.h): the
// eigenvectors, the eigenvalues and optionally the generalised masses, each
// a matrix of the file, and the DOF of each eigenvector row from the budget.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/matrix_size_text.h"
#include "deb/core/number_text.h"
#include "deb/formats/nastran_reader.h"
#include "deb/formats/op4_file.h"

namespace deb::formats {

namespace {

// One value per mode from matrix `name` (a column, a row or a diagonal
// matrix of `modes` values), for `what` ("eigenvalues").
std::vector<double> PerMode(const Op4File& file, const std::string& name, Eigen::Index modes, const std::string& phi,
                            const std::string& what) {
  const Eigen::MatrixXd m = file.Matrix(name);
  const std::string rule = file.path() + ": matrix '" + name + "' is " + SizeText(m) + " but '" + phi + "' has " +
                           std::to_string(modes) + " column(s) (modes): the " + what + " need one per mode (" +
                           std::to_string(modes) + "x1, 1x" + std::to_string(modes) + " or a diagonal " +
                           std::to_string(modes) + "x" + std::to_string(modes) + ")";
  std::vector<double> v(static_cast<std::size_t>(modes));
  if (m.cols() == 1 && m.rows() == modes) {
    for (Eigen::Index k = 0; k < modes; ++k) v[static_cast<std::size_t>(k)] = m(k, 0);
  } else if (m.rows() == 1 && m.cols() == modes) {
    for (Eigen::Index k = 0; k < modes; ++k) v[static_cast<std::size_t>(k)] = m(0, k);
  } else if (m.rows() == modes && m.cols() == modes) {
    for (Eigen::Index j = 0; j < modes; ++j)
      for (Eigen::Index i = 0; i < modes; ++i)
        if (i != j && m(i, j) != 0.0)
          throw InputError(file.path() + ": matrix '" + name + "' is not diagonal (row " + std::to_string(i + 1) +
                           ", column " + std::to_string(j + 1) + " is " + NumberText(m(i, j)) + "): the " + what +
                           " of uncoupled modes are a diagonal matrix");
    for (Eigen::Index k = 0; k < modes; ++k) v[static_cast<std::size_t>(k)] = m(k, k);
  } else {
    throw InputError(rule);
  }
  return v;
}

class Op4Modes : public NastranModeFile::Reader {
 public:
  Op4Modes(const Op4File& file, const Op4ModeMatrices& matrices) : path_(file.path()), name_(matrices.phi) {
    phi_ = file.Matrix(matrices.phi);
    const Eigen::Index n = phi_.cols();
    if (n == 0 || phi_.rows() == 0)
      throw InputError(path_ + ": matrix '" + name_ + "' is " + SizeText(phi_) + ": no eigenvectors");
    if (static_cast<Eigen::Index>(matrices.rows.size()) != phi_.rows())
      throw InputError(path_ + ": " + std::to_string(matrices.rows.size()) + " row DOF(s) given (rows:) but '" +
                       name_ + "' has " + std::to_string(phi_.rows()) + " rows: give the DOF of each of its rows "
                       "(a grid id stands for its 6 rows T1..R3)");
    for (std::size_t r = 0; r < matrices.rows.size(); ++r) {
      const NastranDof& d = matrices.rows[r];
      const auto [at, fresh] = row_of_.emplace(std::make_pair(d.grid, d.component), static_cast<Eigen::Index>(r));
      if (!fresh)
        throw InputError(path_ + ": rows: " + NastranDofText(d) + " is given for row " + std::to_string(r + 1) +
                         " and for row " + std::to_string(at->second + 1));
      grids_.push_back(d.grid);
    }
    const std::vector<double> lambda = PerMode(file, matrices.lambda, n, name_, "eigenvalues");
    std::vector<double> mass;
    if (!matrices.mass.empty()) {
      mass = PerMode(file, matrices.mass, n, name_, "generalised masses");
      for (std::size_t k = 0; k < mass.size(); ++k)
        if (!(mass[k] > 0.0))
          throw InputError(path_ + ": matrix '" + matrices.mass + "': mode " + std::to_string(k + 1) +
                           " has the generalised mass " + NumberText(mass[k]) + "; a mass must be > 0");
    }
    // The modes by frequency (stable: the file's order among equal ones).
    order_.resize(static_cast<std::size_t>(n));
    std::iota(order_.begin(), order_.end(), Eigen::Index{0});
    std::stable_sort(order_.begin(), order_.end(), [&](Eigen::Index a, Eigen::Index b) {
      return lambda[static_cast<std::size_t>(a)] < lambda[static_cast<std::size_t>(b)];
    });
    for (Eigen::Index k : order_) {
      NastranMode m;
      m.number = k + 1;
      m.eigenvalue = lambda[static_cast<std::size_t>(k)];
      m.f_hz = std::sqrt(std::abs(m.eigenvalue)) / kTwoPi;
      m.generalized_mass = mass.empty() ? std::nan("") : mass[static_cast<std::size_t>(k)];
      m.generalized_stiffness = mass.empty() ? std::nan("") : m.eigenvalue * m.generalized_mass;
      modes.push_back(m);
    }
    const bool sorted = std::is_sorted(order_.begin(), order_.end());
    format = "OP4, " + file.EncodingText() + (sorted ? "" : "; modes sorted by frequency");
    table = "matrix " + name_ + " (" + SizeText(phi_) + "), eigenvalues " + matrices.lambda +
            (matrices.mass.empty() ? "" : ", generalised masses " + matrices.mass);
  }

  Eigen::MatrixXd Shapes(const std::vector<NastranDof>& dofs, int count) const override {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(dofs.size()), count);
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      const auto it = row_of_.find({dofs[i].grid, dofs[i].component});
      if (it == row_of_.end())
        throw InputError(path_ + ": " + NastranDofText(dofs[i]) + " is not among the rows of '" + name_ +
                         "', which are the DOFs of " + GridListText(grids_) + " (as rows: gives them)");
      for (int k = 0; k < count; ++k)
        out(static_cast<Eigen::Index>(i), k) = phi_(it->second, order_[static_cast<std::size_t>(k)]);
    }
    return out;
  }

 private:
  std::string path_, name_;
  Eigen::MatrixXd phi_;
  std::map<std::pair<long long, int>, Eigen::Index> row_of_;
  std::vector<long long> grids_;
  std::vector<Eigen::Index> order_;  // file column of each mode, by frequency
};

}  // namespace

std::unique_ptr<NastranModeFile::Reader> OpenOp4Modes(const Op4File& file, const Op4ModeMatrices& matrices) {
  return std::make_unique<Op4Modes>(file, matrices);
}

}  // namespace deb::formats
