#include "deb/budget/path_composition.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "deb/core/at_key_path.h"
#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/suggest.h"
#include "deb/systems/interconnect.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

[[noreturn]] void Fail(const std::string& key_path, const std::string& message) {
  throw InputError(key_path, message);
}

// Gain matrix diag(scale_k) turning signals in `from` units into `to` units.
// @throws at `key_path` if a pair differs by more than a scale.
Eigen::MatrixXd ScaleBetween(const std::string& key_path, const std::vector<std::string>& from,
                             const std::vector<std::string>& to, const std::string& what) {
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(to.size(), from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    const UnitConversion c = AtKeyPath(key_path, [&] { return ConvertUnit(from[k], to[k]); });
    if (!c.IsPureScale())
      Fail(key_path, what + ": channel " + std::to_string(k + 1) + " carries '" + from[k] + "' into '" + to[k] +
                         "', which differ by a time derivative; insert the derivative explicitly");
    g(k, k) = c.scale;
  }
  return g;
}

// Sets p's transfer to the combination of a and b: in state space when both
// are rational (poles and Lyapunov variances stay available); as a diagram
// evaluated per frequency when a part holds measured data, delays, sampled
// blocks or modes (path.h), with as `system` the combination of the parts'
// realisations where there are no measured data (Path::SystemApproximates),
// or a zero gain of the result's size: with measured data, and for a
// diagram of more than limits::kMaxDenseStates states, which is kept as its
// parts (Path::KeptAsParts). p may be a or b.
// @throws InputError for a diagram kept as parts of more than
//   limits::kMaxCoupledStates states.
template <typename StateSpaceOp, typename ModelOp>
void Combine(Path* p, const Path& a, const Path& b, StateSpaceOp rational, ModelOp diagram) {
  std::shared_ptr<const FrequencyModel> model;
  if (a.measured || b.measured || a.modal || b.modal)
    model = std::make_shared<const FrequencyModel>(diagram(a.Model(), b.Model()));
  const int states = a.States() + b.States();
  const bool kept = model && !model->HasData() && (a.KeptAsParts() || b.KeptAsParts() || states > limits::kMaxDenseStates);
  if (kept && states > limits::kMaxCoupledStates)
    throw InputError("the combination has " + std::to_string(states) + " states (2 per mode), more than the " +
                     std::to_string(limits::kMaxCoupledStates) + " deb keeps as coupled parts");
  StateSpace system = model && (model->HasData() || kept)
                          ? StateSpace::Gain(Eigen::MatrixXd::Zero(model->outputs(), model->inputs()))
                          : rational(a.Rational(), b.Rational());
  p->modal.reset();  // a combination is realised in state space (path.h)
  p->system = std::move(system);
  p->measured = std::move(model);
  p->unrealised_states = kept ? states : 0;
}

// p's transfer = b after a (H = H_b H_a).
void SeriesInto(Path* p, const Path& a, const Path& b) {
  Combine(p, a, b, [](const StateSpace& x, const StateSpace& y) { return Series(x, y); },
          [](const FrequencyModel& x, const FrequencyModel& y) { return FrequencyModel::Series(x, y); });
}

// A path of the gain g (no states) for scaling between parts.
Path GainPath(const Eigen::MatrixXd& g) {
  Path p;
  p.system = StateSpace::Gain(g);
  return p;
}

// g_in, then part, then g_out.
Path Scaled(const Eigen::MatrixXd& g_in, const Path& part, const Eigen::MatrixXd& g_out) {
  Path p = part;
  SeriesInto(&p, GainPath(g_in), part);
  SeriesInto(&p, p, GainPath(g_out));
  return p;
}

// A part of a composition, checked to be there.
const Path& PartPath(const PathPart& part) {
  DEB_DEMAND(part.path != nullptr);
  return *part.path;
}

// The transfer and channels of `acc` under the caller's name.
Path Composed(const Path& acc) {
  Path p;
  p.system = acc.system;
  p.measured = acc.measured;
  p.unrealised_states = acc.unrealised_states;
  p.input_units = acc.input_units;
  p.output_units = acc.output_units;
  p.input_names = acc.input_names;
  p.output_names = acc.output_names;
  p.loops = acc.loops;
  return p;
}

// `to` keeps its loops and gains those of `from`.
void AddLoops(Path* to, const Path& from) { to->loops.insert(to->loops.end(), from.loops.begin(), from.loops.end()); }

void RequireTwo(const std::vector<PathPart>& parts) {
  if (parts.size() < 2) throw InputError("list at least two paths");
}

}  // namespace

Path SeriesOfPaths(const std::vector<PathPart>& parts) {
  RequireTwo(parts);
  Path acc = PartPath(parts[0]);
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const Path& next = PartPath(parts[i]);
    if (next.system.inputs() != acc.system.outputs())
      Fail(parts[i].key_path, "path '" + next.name + "' has " + std::to_string(next.system.inputs()) +
                                  " input(s) but follows " + std::to_string(acc.system.outputs()) + " output(s)");
    const Eigen::MatrixXd g = ScaleBetween(parts[i].key_path, acc.output_units, next.input_units, "series");
    Path scaled = acc;
    SeriesInto(&scaled, acc, GainPath(g));
    SeriesInto(&acc, scaled, next);
    AddLoops(&acc, next);
    acc.output_names = next.output_names;
    acc.output_units = next.output_units;
  }
  return Composed(acc);
}

Path ParallelOfPaths(const std::vector<PathPart>& parts) {
  RequireTwo(parts);
  Path acc = PartPath(parts[0]);
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const Path& next = PartPath(parts[i]);
    if (next.system.inputs() != acc.system.inputs() || next.system.outputs() != acc.system.outputs())
      Fail(parts[i].key_path, "parallel paths must have the same numbers of inputs and outputs");
    const Eigen::MatrixXd gi = ScaleBetween(parts[i].key_path, acc.input_units, next.input_units, "parallel inputs");
    const Eigen::MatrixXd go =
        ScaleBetween(parts[i].key_path, next.output_units, acc.output_units, "parallel outputs");
    const Path other = Scaled(gi, next, go);
    const Path before = acc;
    Combine(&acc, before, other, [](const StateSpace& x, const StateSpace& y) { return Parallel(x, y); },
            [](const FrequencyModel& x, const FrequencyModel& y) { return FrequencyModel::Parallel(x, y); });
    AddLoops(&acc, next);
  }
  return Composed(acc);
}

Path SelectPathInputs(const Path& path, const std::vector<std::string>& inputs) {
  if (inputs.empty()) throw InputError("inputs: name at least one input of path '" + path.name + "'");
  std::vector<int> columns;
  for (const std::string& name : inputs) {
    const auto at = std::find(path.input_names.begin(), path.input_names.end(), name);
    if (at == path.input_names.end()) {
      std::string all;
      for (const std::string& n : path.input_names) all += (all.empty() ? "" : ", ") + n;
      throw InputError("path '" + path.name + "' has no input '" + name + "'" + DidYouMean(name, path.input_names) +
                       " (its inputs: " + all + ")");
    }
    const int column = static_cast<int>(at - path.input_names.begin());
    if (std::find(columns.begin(), columns.end(), column) != columns.end())
      throw InputError("input '" + name + "' is named twice; each input takes one channel");
    columns.push_back(column);
  }
  Path p = path;
  p.input_names.clear();
  p.input_units.clear();
  for (int j : columns) {
    p.input_names.push_back(path.input_names[j]);
    p.input_units.push_back(path.input_units[j]);
  }
  const int k = static_cast<int>(columns.size());
  if (path.IsModal()) {
    auto modal = std::make_shared<ModalModel>(*path.modal);
    modal->phi_in = path.modal->phi_in(columns, Eigen::all);
    std::vector<std::string> dofs;
    for (int j : columns) dofs.push_back(path.modal->input_names[j]);
    modal->input_names = dofs;
    if (modal->residual.size() > 0) modal->residual = path.modal->residual(Eigen::all, columns);
    p.modal = std::move(modal);
    p.system = StateSpace::Gain(Eigen::MatrixXd::Zero(path.system.outputs(), k));
    return p;
  }
  if (path.measured) {
    Eigen::MatrixXd selector = Eigen::MatrixXd::Zero(path.system.inputs(), k);
    for (int i = 0; i < k; ++i) selector(columns[i], i) = 1.0;
    p.measured = std::make_shared<const FrequencyModel>(
        FrequencyModel::Series(FrequencyModel(StateSpace::Gain(selector)), *path.measured));
    if (path.HasMeasuredData() || path.KeptAsParts()) {
      p.system = StateSpace::Gain(Eigen::MatrixXd::Zero(path.system.outputs(), k));
      return p;
    }
  }
  p.system = path.system.SelectInputs(columns);
  return p;
}

Path AddCombinedOutput(const Path& path, const std::string& name, const std::vector<SignalTerm>& terms) {
  if (terms.empty()) throw InputError("a combination needs at least one term (signal: weight)");
  if (path.OutputIndex(name) >= 0)
    throw InputError("path '" + path.name + "' already has a signal '" + name + "': name the combined output otherwise");
  const int p = path.system.outputs();
  Eigen::RowVectorXd weights = Eigen::RowVectorXd::Zero(p);
  std::string unit;
  for (const SignalTerm& t : terms) {
    const int row = path.OutputIndex(t.signal);
    if (row < 0)
      throw InputError("." + t.signal, "path '" + path.name + "' has no signal '" + t.signal + "'" +
                                           DidYouMean(t.signal, path.output_names));
    if (!std::isfinite(t.weight)) throw InputError("." + t.signal, "the weight is not finite");
    const std::string term_unit = UnitProduct(t.unit, path.output_units[row]);
    if (unit.empty()) unit = term_unit;
    const UnitConversion c = AtKeyPath("." + t.signal, [&] { return ConvertUnit(term_unit, unit); });
    if (!c.IsPureScale())
      throw InputError("." + t.signal, "the term " + t.signal + " is in " + term_unit + ", the combination in " + unit +
                                           " (its first term's unit): they differ by a time derivative; every term "
                                           "must be the same quantity");
    weights(row) += t.weight * c.scale;
  }
  Path q = path;
  q.output_names.push_back(name);
  q.output_units.push_back(unit);
  const int m = path.system.inputs();
  if (path.IsModal()) {
    auto modal = std::make_shared<ModalModel>(*path.modal);
    modal->phi_out.conservativeResize(p + 1, Eigen::NoChange);
    modal->phi_out.row(p) = weights * path.modal->phi_out;
    modal->output_names.push_back(name);
    if (modal->residual.size() > 0) {
      modal->residual.conservativeResize(p + 1, Eigen::NoChange);
      modal->residual.row(p) = weights * path.modal->residual;
    }
    q.modal = std::move(modal);
    q.system = StateSpace::Gain(Eigen::MatrixXd::Zero(p + 1, m));
    return q;
  }
  if (path.measured) {
    Eigen::MatrixXd stack(p + 1, p);
    stack.topRows(p).setIdentity();
    stack.row(p) = weights;
    q.measured = std::make_shared<const FrequencyModel>(
        FrequencyModel::Series(*path.measured, FrequencyModel(StateSpace::Gain(stack))));
    if (path.HasMeasuredData() || path.KeptAsParts()) {
      q.system = StateSpace::Gain(Eigen::MatrixXd::Zero(p + 1, m));
      return q;
    }
  }
  Eigen::MatrixXd c(p + 1, path.system.states()), d(p + 1, m);
  c.topRows(p) = path.system.C();
  c.row(p) = weights * path.system.C();
  d.topRows(p) = path.system.D();
  d.row(p) = weights * path.system.D();
  q.system = StateSpace(path.system.A(), path.system.B(), c, d);
  return q;
}

void CheckFeedbackSign(int sign) {
  if (sign != 1 && sign != -1)
    throw InputError("sign must be -1 (negative feedback) or +1, got " + std::to_string(sign));
}

Path FeedbackOfPaths(const PathPart& plant_part, const PathPart& controller_part, int sign) {
  CheckFeedbackSign(sign);
  const Path& plant = PartPath(plant_part);
  const Path& ctrl = PartPath(controller_part);
  const std::string& at = controller_part.key_path;
  if (ctrl.system.inputs() != plant.system.outputs() || ctrl.system.outputs() != plant.system.inputs())
    Fail(at, "controller '" + ctrl.name + "' must have " + std::to_string(plant.system.outputs()) + " input(s) and " +
                 std::to_string(plant.system.inputs()) + " output(s) to close a loop around '" + plant.name + "'");
  const Eigen::MatrixXd gi = ScaleBetween(at, plant.output_units, ctrl.input_units, "feedback");
  const Eigen::MatrixXd go = ScaleBetween(at, ctrl.output_units, plant.input_units, "feedback");
  const Path k = Scaled(gi, ctrl, go);
  Path p;
  Combine(&p, plant, k, [&](const StateSpace& g, const StateSpace& c) { return Feedback(g, c, sign); },
          [&](const FrequencyModel& g, const FrequencyModel& c) { return FrequencyModel::Feedback(g, c, sign); });
  p.input_units = plant.input_units;
  p.output_units = plant.output_units;
  p.input_names = plant.input_names;
  p.output_names = plant.output_names;
  p.loops = plant.loops;
  AddLoops(&p, ctrl);
  FeedbackLoop loop;
  loop.plant = plant.name;
  loop.controller = ctrl.name;
  loop.sign = sign;
  loop.plant_model = std::make_shared<const FrequencyModel>(plant.Model());
  loop.controller_model = std::make_shared<const FrequencyModel>(k.Model());
  p.loops.push_back(std::move(loop));
  return p;
}

}  // namespace deb
