#include "deb/signal/coherence_csv.h"

#include <complex>
#include <sstream>

#include "deb/core/number_text.h"

namespace deb {
namespace {

// 10 significant digits.
std::string Number(double v) { return SignificantText(v, 10); }

}  // namespace

std::string CoherenceCsvText(const CsdEstimate& csd) {
  std::ostringstream out;
  out << "# coherence |S_ab|^2/(S_aa S_bb) and CSD phase arg S_ab = arg <conj(X_a) X_b>, rad\n";
  for (const std::string& l : csd.provenance.Describe()) out << "# " << l << "\n";
  out << "f_hz";
  // Coherence and phase of each pair over all bins, built once per pair.
  Eigen::MatrixXd columns(static_cast<Eigen::Index>(csd.f_hz.size()), csd.channels * (csd.channels - 1));
  Eigen::Index column = 0;
  for (int b = 0; b < csd.channels; ++b)
    for (int a = 0; a < b; ++a) {
      const std::string pair =
          csd.channel_names[static_cast<std::size_t>(a)] + "_" + csd.channel_names[static_cast<std::size_t>(b)];
      out << ", coherence_" << pair << ", phase_" << pair;
      columns.col(column++) = csd.Coherence(a, b);
      columns.col(column++) = csd.Cross(a, b).unaryExpr([](const std::complex<double>& s) { return std::arg(s); });
    }
  out << "\n";
  for (Eigen::Index k = 0; k < columns.rows(); ++k) {
    out << Number(csd.f_hz[static_cast<std::size_t>(k)]);
    for (Eigen::Index c = 0; c < columns.cols(); ++c) out << ", " << Number(columns(k, c));
    out << "\n";
  }
  return out.str();
}

}  // namespace deb
