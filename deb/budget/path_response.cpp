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

PathResponseRecorder::PathResponseRecorder(const Budget& budget, const PathAnalysis& analysis,
                                           std::size_t contributor, const std::vector<double>& f_hz, int threads)
    : f_hz_(f_hz) {
  DEB_DEMAND(contributor < budget.contributors.size());
  const Contributor& c = budget.contributors[contributor];
  const Source& source = budget.FindSource(c.source);
  const Path& path = analysis.path();
  const int m = path.system.inputs();
  in_conv_ = InputConversions(source, path);
  const std::size_t outputs = budget.outputs.size();
  r_.resize(outputs);
  position_.resize(outputs);
  out_conv_.resize(outputs);
  w2_.resize(outputs);
  w_.resize(outputs);
  for (std::size_t o = 0; o < outputs; ++o) {
    const Output& out = budget.outputs[o];
    const int row = path.OutputIndex(out.signal);
    DEB_DEMAND(row >= 0);
    position_[o] = analysis.Position(row);
    DEB_DEMAND(position_[o] >= 0);
    out_conv_[o] = OutputConversion(path, row, out);
    w2_[o] = WeightingGain2(out, f_hz, threads);
    if (out.weighting) {
      w_[o].resize(f_hz.size());
      FrequencyResponse(out.weighting->system)
          .ForEach(f_hz, [&](std::size_t i, const Eigen::MatrixXcd& h) { w_[o][i] = h(0, 0); }, threads);
    }
    r_[o].contributor = c.name;
    r_[o].output = out.name;
    r_[o].channels = source.channel_names;
    r_[o].unit = Grouped(out.unit) + "/" + Grouped(source.unit);
    r_[o].gain2.assign(m, std::vector<double>(f_hz.size(), 0.0));
    r_[o].phase_rad.assign(m, std::vector<double>(f_hz.size(), 0.0));
  }
}

void PathResponseRecorder::Record(std::size_t i, const Eigen::MatrixXcd& h) {
  const double f = f_hz_[i];
  for (std::size_t o = 0; o < r_.size(); ++o) {
    const double common = out_conv_[o].PsdFactor(f) * (w2_[o].empty() ? 1.0 : w2_[o][i]);
    const std::complex<double> outer =
        out_conv_[o].ResponseFactor(f) * (w_[o].empty() ? std::complex<double>(1.0) : w_[o][i]);
    for (std::size_t k = 0; k < in_conv_.size(); ++k) {
      const std::complex<double> hk = h(position_[o], static_cast<Eigen::Index>(k)) * in_conv_[k].ResponseFactor(f);
      r_[o].gain2[k][i] = std::norm(hk) * common;
      r_[o].phase_rad[k][i] = std::arg(hk * outer);
    }
  }
}

std::vector<PathResponse> ComputePathResponses(const Budget& budget, const BudgetResult& result,
                                               std::size_t contributor, const std::vector<double>& f_hz,
                                               int threads) {
  DEB_DEMAND(contributor < budget.contributors.size());
  const auto analysis = result.paths.find(ContributorPathKey(budget.contributors[contributor]));
  DEB_DEMAND(analysis != result.paths.end());
  PathResponseRecorder recorder(budget, *analysis->second, contributor, f_hz, threads);
  analysis->second->ForEachResponse(
      f_hz, [&](std::size_t i, const Eigen::MatrixXcd& h) { recorder.Record(i, h); }, threads);
  return recorder.Take();
}

PathResponse ComputePathResponse(const Budget& budget, const BudgetResult& result, std::size_t contributor,
                                 std::size_t output, const std::vector<double>& f_hz, int threads) {
  DEB_DEMAND(output < budget.outputs.size());
  return std::move(ComputePathResponses(budget, result, contributor, f_hz, threads)[output]);
}

}  // namespace deb
