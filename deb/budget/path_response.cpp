#include "deb/budget/path_response.h"

#include <complex>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"

namespace deb {
namespace {

std::string Grouped(const std::string& unit) {
  const std::string u = DisplayUnit(unit);
  return u.find_first_of("/ .*") == std::string::npos ? u : "(" + u + ")";
}

}  // namespace

std::vector<UnitConversion> InputConversions(const Source& source, const Path& path) {
  std::vector<UnitConversion> conv(path.input_units.size());
  for (std::size_t k = 0; k < conv.size(); ++k) conv[k] = ConvertUnit(source.unit, path.input_units[k]);
  return conv;
}

Eigen::MatrixXd WhiteInputIntensity(const Source& source, const std::vector<UnitConversion>& in_conv) {
  const auto white = source.spectrum->WhiteLevel();
  DEB_DEMAND(white.has_value());
  const Eigen::Index m = white->rows();
  DEB_DEMAND(static_cast<std::size_t>(m) == in_conv.size());
  Eigen::MatrixXd in_scale = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index j = 0; j < m; ++j) in_scale(j, j) = in_conv[static_cast<std::size_t>(j)].scale;
  return in_scale * *white * in_scale / 2.0;
}

std::string WeightedSignalUnit(const Path& path, int row, const Output& output) {
  return output.weighting ? UnitProduct(path.output_units[row], output.weighting->unit) : path.output_units[row];
}

UnitConversion OutputConversion(const Path& path, int row, const Output& output) {
  return ConvertUnit(WeightedSignalUnit(path, row, output), output.unit);
}

std::vector<double> WeightingGain2(const Output& output, const std::vector<double>& f_hz, int threads) {
  if (!output.weighting && !output.metric) return {};
  std::vector<double> g(f_hz.size(), 1.0);
  if (output.weighting)
    FrequencyResponse(output.weighting->system)
        .ForEach(f_hz, [&](std::size_t k, const Eigen::MatrixXcd& h) { g[k] = std::norm(h(0, 0)); }, threads);
  if (output.metric)
    for (std::size_t k = 0; k < f_hz.size(); ++k) g[k] *= output.metric->PsdFactor(f_hz[k]);
  return g;
}

std::vector<PathResponse> ComputePathResponses(const Budget& budget, const BudgetResult& result,
                                               std::size_t contributor, const std::vector<double>& f_hz,
                                               int threads) {
  DEB_DEMAND(contributor < budget.contributors.size());
  const Contributor& c = budget.contributors[contributor];
  const Source& source = budget.FindSource(c.source);
  const auto analysis = result.paths.find(ContributorPathKey(c));
  DEB_DEMAND(analysis != result.paths.end());
  const Path& path = analysis->second->path();
  const int m = path.system.inputs();
  const std::vector<UnitConversion> in_conv = InputConversions(source, path);

  const std::size_t outputs = budget.outputs.size();
  std::vector<PathResponse> r(outputs);
  std::vector<int> position(outputs);
  std::vector<UnitConversion> out_conv(outputs);
  std::vector<std::vector<double>> w2(outputs);
  std::vector<std::vector<std::complex<double>>> w(outputs);  // the weighting's response, for the phase
  for (std::size_t o = 0; o < outputs; ++o) {
    const Output& out = budget.outputs[o];
    const int row = path.OutputIndex(out.signal);
    DEB_DEMAND(row >= 0);
    position[o] = analysis->second->Position(row);
    DEB_DEMAND(position[o] >= 0);
    out_conv[o] = OutputConversion(path, row, out);
    w2[o] = WeightingGain2(out, f_hz, threads);
    if (out.weighting) {
      w[o].resize(f_hz.size());
      FrequencyResponse(out.weighting->system)
          .ForEach(f_hz, [&](std::size_t i, const Eigen::MatrixXcd& h) { w[o][i] = h(0, 0); }, threads);
    }
    r[o].contributor = c.name;
    r[o].output = out.name;
    r[o].channels = source.channel_names;
    r[o].unit = Grouped(out.unit) + "/" + Grouped(source.unit);
    r[o].gain2.assign(m, std::vector<double>(f_hz.size(), 0.0));
    r[o].phase_rad.assign(m, std::vector<double>(f_hz.size(), 0.0));
  }
  analysis->second->ForEachResponse(
      f_hz,
      [&](std::size_t i, const Eigen::MatrixXcd& h) {
        for (std::size_t o = 0; o < outputs; ++o) {
          const double common = out_conv[o].PsdFactor(f_hz[i]) * (w2[o].empty() ? 1.0 : w2[o][i]);
          const std::complex<double> outer =
              out_conv[o].ResponseFactor(f_hz[i]) * (w[o].empty() ? std::complex<double>(1.0) : w[o][i]);
          for (int k = 0; k < m; ++k) {
            const std::complex<double> hk = h(position[o], k) * in_conv[k].ResponseFactor(f_hz[i]);
            r[o].gain2[k][i] = std::norm(hk) * common;
            r[o].phase_rad[k][i] = std::arg(hk * outer);
          }
        }
      },
      threads);
  return r;
}

PathResponse ComputePathResponse(const Budget& budget, const BudgetResult& result, std::size_t contributor,
                                 std::size_t output, const std::vector<double>& f_hz, int threads) {
  DEB_DEMAND(output < budget.outputs.size());
  return std::move(ComputePathResponses(budget, result, contributor, f_hz, threads)[output]);
}

}  // namespace deb
