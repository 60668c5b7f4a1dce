#include "deb/budget/path.h"

#include <set>
#include <sstream>

#include "deb/core/error.h"

namespace deb {
namespace {

void RequireNames(const std::vector<std::string>& names, int expected, const std::string& what,
                  const std::string& path_name) {
  if (static_cast<int>(names.size()) != expected) {
    std::ostringstream os;
    os << "path '" << path_name << "': " << expected << " " << what << " expected (the system's size), got "
       << names.size();
    throw InputError(os.str());
  }
}

}  // namespace

void Path::Validate() const {
  RequireNames(input_names, system.inputs(), "input names", name);
  RequireNames(output_names, system.outputs(), "output names", name);
  RequireNames(input_units, system.inputs(), "input units", name);
  RequireNames(output_units, system.outputs(), "output units", name);
  for (const auto* list : {&input_names, &output_names}) {
    std::set<std::string> seen;
    for (const auto& n : *list)
      if (!seen.insert(n).second)
        throw InputError("path '" + name + "': channel name '" + n + "' appears twice");
  }
}

int Path::OutputIndex(const std::string& signal) const {
  for (std::size_t i = 0; i < output_names.size(); ++i)
    if (output_names[i] == signal) return static_cast<int>(i);
  return -1;
}

Eigen::MatrixXcd FeedbackLoop::LoopGainAt(double f_hz) const { return LoopGainOf(plant_model->At(f_hz), f_hz); }

std::vector<Eigen::MatrixXcd> FeedbackLoop::LoopGains(const std::vector<double>& f_hz) const {
  std::vector<Eigen::MatrixXcd> l(f_hz.size());
  plant_model->ForEach(f_hz, [&](std::size_t k, const Eigen::MatrixXcd& g) { l[k] = LoopGainOf(g, f_hz[k]); });
  return l;
}

Eigen::MatrixXcd FeedbackLoop::LoopGainOf(const Eigen::MatrixXcd& g, double f_hz) const {
  return -static_cast<double>(sign) * (g * controller_model->At(f_hz));
}

int Path::States() const {
  if (unrealised_states > 0) return unrealised_states;
  return modal ? 2 * modal->modes() : system.states();
}

StateSpace Path::Rational() const {
  DEB_DEMAND(!KeptAsParts());
  return modal ? ModalStateSpace(*modal) : system;
}

FrequencyModel Path::Model() const {
  if (measured) return *measured;
  return modal ? FrequencyModel(modal) : FrequencyModel(system);
}

}  // namespace deb
