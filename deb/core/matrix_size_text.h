// Internal: not part of the public API.
// "3x4": a matrix's rows x columns, as messages about matrix shapes say it.
#pragma once

#include <Eigen/Dense>
#include <string>

namespace deb {

inline std::string SizeText(const Eigen::MatrixXd& m) {
  return std::to_string(m.rows()) + "x" + std::to_string(m.cols());
}

}  // namespace deb
