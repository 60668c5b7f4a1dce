#include "deb/budget/sweep.h"

#include <atomic>
#include <cmath>
#include <mutex>
#include <sstream>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"

namespace deb {

std::string ParameterLabelProblem(const std::string& label) {
  if (label.find_first_not_of(" \t") == std::string::npos)
    return "the label is empty; name the parameter, e.g. 'isolator height h'";
  if (label.size() > kMaxSweepLabelChars)
    return "the label has " + std::to_string(label.size()) + " characters, more than the " +
           std::to_string(kMaxSweepLabelChars) + " an axis can show";
  for (const char ch : label)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
      return "the label holds a control character (a line break?); write it on one line";
  return "";
}

std::string SweepParameter::Text(double value) const {
  if (!texts.empty()) {
    const auto i = static_cast<std::size_t>(value);
    DEB_DEMAND(value >= 0.0 && i < texts.size());
    return texts[i];
  }
  std::ostringstream os;
  os.precision(10);
  os << value;
  if (!value_unit.empty()) os << ' ' << value_unit;
  return os.str();
}

std::string SweepParameter::ShortText(double value) const {
  if (!texts.empty()) return Text(value);
  std::ostringstream os;
  os.precision(4);
  os << value;
  return os.str();
}

std::string SweepParameter::Name() const { return label.empty() ? key_path : label; }

std::string SweepParameter::AxisTitle() const { return unit.empty() ? Name() : Name() + " [" + unit + "]"; }

std::string SweepParameter::Setting(double value) const {
  return Name() + " = " + ShortText(value) + (unit.empty() || !texts.empty() ? "" : " " + unit);
}

std::vector<std::vector<double>> SweepSpec::Variants() const {
  std::vector<std::vector<double>> rows;
  if (parameters.empty()) return rows;
  for (const auto& p : parameters) DEB_DEMAND(!p.values.empty());
  if (mode == SweepMode::kZip) {
    const std::size_t n = parameters[0].values.size();
    for (const auto& p : parameters) DEB_DEMAND(p.values.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<double> row;
      for (const auto& p : parameters) row.push_back(p.values[i]);
      rows.push_back(row);
    }
    return rows;
  }
  std::vector<std::size_t> index(parameters.size(), 0);
  while (true) {
    std::vector<double> row;
    for (std::size_t k = 0; k < parameters.size(); ++k) row.push_back(parameters[k].values[index[k]]);
    rows.push_back(row);
    std::size_t k = parameters.size();
    while (k > 0) {  // odometer: the last parameter fastest
      --k;
      if (++index[k] < parameters[k].values.size()) break;
      index[k] = 0;
      if (k == 0) return rows;
    }
  }
}

std::vector<double> LinearRange(double from, double to, int count) {
  if (count < 1) throw InputError("a range needs count >= 1, got " + std::to_string(count));
  if (count == 1) return {from};
  std::vector<double> v(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) v[static_cast<std::size_t>(i)] = from + (to - from) * i / (count - 1);
  v.back() = to;
  return v;
}

std::vector<double> LogRange(double from, double to, int count) {
  if (!(from > 0.0 && to > 0.0)) {
    std::ostringstream os;
    os << "a log range needs ends > 0, got from " << from << " to " << to;
    throw InputError(os.str());
  }
  std::vector<double> v = LinearRange(std::log(from), std::log(to), count);
  for (double& x : v) x = std::exp(x);
  v.front() = from;
  if (count > 1) v.back() = to;
  return v;
}

std::vector<BudgetResult> EvaluateSweepPart(const SweepSpec& spec, const std::function<Budget(std::size_t)>& variant,
                                            const StudyShard& shard, int threads,
                                            const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::pair<std::size_t, std::size_t> range = shard.Range(spec.Variants().size());
  return EvaluateSweepRange(spec, variant, range.first, range.second, threads, progress);
}

std::vector<BudgetResult> EvaluateSweepRange(const SweepSpec& spec, const std::function<Budget(std::size_t)>& variant,
                                             std::size_t begin, std::size_t end, int threads,
                                             const std::function<void(std::size_t, std::size_t)>& progress) {
  const auto values = spec.Variants();
  DEB_DEMAND(begin <= end && end <= values.size());
  std::vector<BudgetResult> results(end - begin);
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  EngineOptions options;
  options.threads = 1;  // parallel across variants, not within
  options.response_traces = false;
  // Variants differ in cost (grid refinement): each thread takes the next
  // variant not yet started. Each result lands at its variant's index.
  ParallelForEach(
      end - begin,
      [&](std::size_t j) {
        const std::size_t i = begin + j;
        const Budget budget = variant(i);  // its errors name the variant already
        try {
          results[j] = Evaluate(budget, options);
        } catch (const InputError& e) {
          std::ostringstream os;
          os << "sweep variant " << i + 1 << " (";
          for (std::size_t k = 0; k < spec.parameters.size(); ++k)
            os << (k ? ", " : "") << spec.parameters[k].key_path << " = " << spec.parameters[k].Text(values[i][k]);
          os << "): " << e.message();
          throw InputError(e.location(), os.str());
        }
        const std::size_t n = ++done;
        if (progress) {
          const std::lock_guard<std::mutex> lock(progress_mutex);
          progress(n, end - begin);
        }
      },
      threads);
  return results;
}

std::vector<BudgetResult> EvaluateSweep(const SweepSpec& spec, const std::function<Budget(std::size_t)>& variant,
                                        int threads,
                                        const std::function<void(std::size_t, std::size_t)>& progress) {
  return EvaluateSweepPart(spec, variant, StudyShard{}, threads, progress);
}

std::vector<BudgetResult> EvaluateSweep(const SweepSpec& spec, const std::vector<Budget>& variants, int threads,
                                        const std::function<void(std::size_t, std::size_t)>& progress) {
  DEB_DEMAND(spec.Variants().size() == variants.size());
  return EvaluateSweep(
      spec, [&variants](std::size_t i) { return variants[i]; }, threads, progress);
}

std::string SweepCsv(const SweepSpec& spec, const std::vector<BudgetResult>& results) {
  const auto values = spec.Variants();
  DEB_DEMAND(values.size() == results.size());
  auto field = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  std::ostringstream os;
  os.precision(10);
  bool first = true;
  for (const auto& p : spec.parameters) {
    os << (first ? "" : ",") << field(p.key_path);
    first = false;
  }
  if (!results.empty())
    for (const auto& o : results[0].outputs) {
      os << "," << field(o.name + ".rms");
      for (const auto& c : o.contributors) os << "," << field(o.name + "." + c.name + ".rms");
    }
  os << "\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    for (std::size_t k = 0; k < values[i].size(); ++k) os << (k ? "," : "") << field(spec.parameters[k].Text(values[i][k]));
    for (const auto& o : results[i].outputs) {
      os << "," << o.rms();
      for (const auto& c : o.contributors) os << "," << std::sqrt(c.variance);
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace deb
