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

PathResponse ComputePathResponse(const Budget& budget, const BudgetResult& result, std::size_t contributor,
                                 std::size_t output, const std::vector<double>& f_hz, int threads) {
  DEB_DEMAND(contributor < budget.contributors.size() && output < budget.outputs.size());
  const Contributor& c = budget.contributors[contributor];
  const Output& out = budget.outputs[output];
  const Source& source = budget.FindSource(c.source);
  const Path& path = budget.FindPath(c.path);
  const int row = path.OutputIndex(out.signal);
  DEB_DEMAND(row >= 0);
  const auto analysis = result.paths.find(c.path);
  DEB_DEMAND(analysis != result.paths.end());
  const int position = analysis->second->Position(row);
  DEB_DEMAND(position >= 0);
  const int m = path.system.inputs();

  const std::vector<UnitConversion> in_conv = InputConversions(source, path);
  const UnitConversion out_conv = OutputConversion(path, row, out);
  const std::vector<double> w2 = WeightingGain2(out, f_hz, threads);

  PathResponse r;
  r.contributor = c.name;
  r.output = out.name;
  r.channels = source.channel_names;
  r.unit = Grouped(out.unit) + "/" + Grouped(source.unit);
  r.gain2.assign(m, std::vector<double>(f_hz.size(), 0.0));
  analysis->second->ForEachResponse(
          f_hz,
          [&](std::size_t i, const Eigen::MatrixXcd& h) {
            const double common = out_conv.PsdFactor(f_hz[i]) * (w2.empty() ? 1.0 : w2[i]);
            for (int k = 0; k < m; ++k)
              r.gain2[k][i] = std::norm(h(position, k) * in_conv[k].ResponseFactor(f_hz[i])) * common;
          },
          threads);
  return r;
}

}  // namespace deb
