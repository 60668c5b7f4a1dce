#include "deb/systems/frequency_model.h"

#include <algorithm>
#include <optional>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/systems/coupled_realisation.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/modal_response.h"

namespace deb {

struct FrequencyModel::Node {
  enum class Kind { kRational, kMeasured, kIrrational, kModal, kSeries, kParallel, kFeedback, kSelect };
  Kind kind = Kind::kRational;
  int inputs = 0, outputs = 0;
  std::optional<StateSpace> rational;
  std::shared_ptr<const FrequencyResponse> response;  // of `rational`, reduced once
  std::optional<MeasuredResponse> measured;
  std::optional<IrrationalBlock> irrational;
  std::shared_ptr<const ModalModel> modal;
  std::shared_ptr<const ModalResponse> modal_response;  // of `modal`, every output row
  std::shared_ptr<const Node> a, b;  // series: first, second; feedback: plant, controller
  int sign = -1;
  std::vector<int> rows;  // kSelect

  Eigen::MatrixXcd At(double f_hz) const {
    switch (kind) {
      case Kind::kRational: return response->At(f_hz);
      case Kind::kMeasured: return measured->At(f_hz);
      case Kind::kIrrational: return Eigen::MatrixXcd::Constant(1, 1, irrational->At(f_hz));
      case Kind::kModal: return modal_response->At(f_hz);
      case Kind::kSeries: return b->At(f_hz) * a->At(f_hz);
      case Kind::kParallel: return a->At(f_hz) + b->At(f_hz);
      case Kind::kFeedback: return Close(a->At(f_hz), b->At(f_hz), f_hz);
      case Kind::kSelect: return Rows(a->At(f_hz));
    }
    DEB_DEMAND(false);
    return {};
  }

  // H at each of a block of frequencies: as At(), with a modal part's
  // responses computed together as matrix products (ModalResponse::ForEach)
  // instead of one frequency at a time.
  std::vector<Eigen::MatrixXcd> AtBlock(const std::vector<double>& f_hz) const {
    std::vector<Eigen::MatrixXcd> h;
    switch (kind) {
      case Kind::kModal:
        h.resize(f_hz.size());
        modal_response->ForEach(f_hz, [&](std::size_t k, const Eigen::MatrixXcd& x) { h[k] = x; }, 1);
        return h;
      case Kind::kSeries:
      case Kind::kParallel:
      case Kind::kFeedback: {
        h = a->AtBlock(f_hz);
        const std::vector<Eigen::MatrixXcd> y = b->AtBlock(f_hz);
        for (std::size_t k = 0; k < f_hz.size(); ++k) {
          if (kind == Kind::kSeries) h[k] = y[k] * h[k];
          else if (kind == Kind::kParallel) h[k] += y[k];
          else h[k] = Close(h[k], y[k], f_hz[k]);
        }
        return h;
      }
      case Kind::kSelect:
        h = a->AtBlock(f_hz);
        for (Eigen::MatrixXcd& x : h) x = Rows(x);
        return h;
      default:
        for (double f : f_hz) h.push_back(At(f));
        return h;
    }
  }

  // (I - sign G K)^-1 G at f_hz.
  Eigen::MatrixXcd Close(const Eigen::MatrixXcd& g, const Eigen::MatrixXcd& k, double f_hz) const {
    const Eigen::MatrixXcd loop = Eigen::MatrixXcd::Identity(g.rows(), g.rows()) - static_cast<double>(sign) * g * k;
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(loop);
    if (!(lu.rcond() > 1e-13)) {
      std::ostringstream os;
      os << "the feedback loop is singular at " << f_hz << " Hz: I - sign G K has reciprocal condition " << lu.rcond()
         << " there";
      throw InputError(os.str());
    }
    return lu.solve(g);
  }

  Eigen::MatrixXcd Rows(const Eigen::MatrixXcd& h) const {
    Eigen::MatrixXcd s(static_cast<Eigen::Index>(rows.size()), h.cols());
    for (std::size_t r = 0; r < rows.size(); ++r) s.row(static_cast<Eigen::Index>(r)) = h.row(rows[r]);
    return s;
  }

  void Collect(std::vector<StateSpace>* parts, std::vector<double>* f_hz, bool* loop_around_data,
               std::vector<IrrationalBlock>* blocks = nullptr,
               std::vector<std::shared_ptr<const ModalModel>>* modal_parts = nullptr) const {
    if (rational && parts) parts->push_back(*rational);
    if (modal && modal_parts) modal_parts->push_back(modal);
    if (irrational && blocks) blocks->push_back(*irrational);
    if (measured && f_hz) f_hz->insert(f_hz->end(), measured->f_hz().begin(), measured->f_hz().end());
    if (kind == Kind::kFeedback && loop_around_data && (a->HasData() || b->HasData())) *loop_around_data = true;
    if (a) a->Collect(parts, f_hz, loop_around_data, blocks, modal_parts);
    if (b) b->Collect(parts, f_hz, loop_around_data, blocks, modal_parts);
  }

  // Where every measured table whose extrapolation is an error is defined.
  std::optional<FrequencyInterval> DefinedRange() const {
    std::optional<FrequencyInterval> range;
    if (measured && measured->extrapolation() == Extrapolation::kError)
      range = FrequencyInterval{measured->f_hz().front(), measured->f_hz().back()};
    if (a) range = Intersect(range, a->DefinedRange());
    if (b) range = Intersect(range, b->DefinedRange());
    return range;
  }

  bool HasData() const { return measured || (a && a->HasData()) || (b && b->HasData()); }

  std::optional<CoupledRealisation> Coupled(std::string* why) const {
    switch (kind) {
      case Kind::kRational:
        if (rational->states() > kMaxCoupledBlock) {
          *why = "a rational part has " + std::to_string(rational->states()) + " states (more than " +
                 std::to_string(kMaxCoupledBlock) + " are not kept as one block)";
          return std::nullopt;
        }
        return CoupledOf(*rational);
      case Kind::kModal: return CoupledOf(*modal);
      case Kind::kMeasured: *why = "it holds measured data"; return std::nullopt;
      case Kind::kIrrational: *why = "it holds a delay or a sampled block"; return std::nullopt;
      case Kind::kSelect: {
        std::optional<CoupledRealisation> x = a->Coupled(why);
        if (!x) return x;
        return CoupledSelectOutputs(*x, rows);
      }
      case Kind::kSeries:
      case Kind::kParallel:
      case Kind::kFeedback: {
        std::optional<CoupledRealisation> x = a->Coupled(why);
        if (!x) return x;
        std::optional<CoupledRealisation> y = b->Coupled(why);
        if (!y) return y;
        if (kind == Kind::kSeries) return CoupledSeries(*x, *y);
        if (kind == Kind::kParallel) return CoupledParallel(*x, *y);
        return CoupledFeedback(*x, *y, sign);
      }
    }
    DEB_DEMAND(false);
    return std::nullopt;
  }
};

FrequencyModel::FrequencyModel(const StateSpace& rational) {
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kRational;
  n->inputs = rational.inputs();
  n->outputs = rational.outputs();
  n->rational = rational;
  n->response = std::make_shared<const FrequencyResponse>(rational);
  node_ = std::move(n);
}

FrequencyModel::FrequencyModel(MeasuredResponse measured) {
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kMeasured;
  n->inputs = measured.inputs();
  n->outputs = measured.outputs();
  n->measured = std::move(measured);
  node_ = std::move(n);
}

FrequencyModel::FrequencyModel(IrrationalBlock block) {
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kIrrational;
  n->inputs = 1;
  n->outputs = 1;
  n->irrational = std::move(block);
  node_ = std::move(n);
}

FrequencyModel::FrequencyModel(std::shared_ptr<const ModalModel> modal) {
  DEB_DEMAND(modal != nullptr);
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kModal;
  n->inputs = static_cast<int>(modal->phi_in.rows());
  n->outputs = static_cast<int>(modal->phi_out.rows());
  std::vector<int> rows(static_cast<std::size_t>(n->outputs));
  for (int r = 0; r < n->outputs; ++r) rows[static_cast<std::size_t>(r)] = r;
  n->modal_response = std::make_shared<const ModalResponse>(*modal, rows);
  n->modal = std::move(modal);
  node_ = std::move(n);
}

FrequencyModel FrequencyModel::Series(const FrequencyModel& first, const FrequencyModel& second) {
  if (second.inputs() != first.outputs())
    throw InputError("series: the second block has " + std::to_string(second.inputs()) + " input(s), the first " +
                     std::to_string(first.outputs()) + " output(s)");
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kSeries;
  n->inputs = first.inputs();
  n->outputs = second.outputs();
  n->a = first.node_;
  n->b = second.node_;
  return FrequencyModel(std::move(n));
}

FrequencyModel FrequencyModel::Parallel(const FrequencyModel& a, const FrequencyModel& b) {
  if (a.inputs() != b.inputs() || a.outputs() != b.outputs())
    throw InputError("parallel: the blocks must have the same numbers of inputs and outputs");
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kParallel;
  n->inputs = a.inputs();
  n->outputs = a.outputs();
  n->a = a.node_;
  n->b = b.node_;
  return FrequencyModel(std::move(n));
}

FrequencyModel FrequencyModel::Feedback(const FrequencyModel& plant, const FrequencyModel& controller, int sign) {
  if (sign != 1 && sign != -1) throw InputError("feedback: sign must be +1 or -1, got " + std::to_string(sign));
  if (controller.inputs() != plant.outputs() || controller.outputs() != plant.inputs())
    throw InputError("feedback: the controller must have " + std::to_string(plant.outputs()) + " input(s) and " +
                     std::to_string(plant.inputs()) + " output(s)");
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kFeedback;
  n->inputs = plant.inputs();
  n->outputs = plant.outputs();
  n->a = plant.node_;
  n->b = controller.node_;
  n->sign = sign;
  return FrequencyModel(std::move(n));
}

FrequencyModel FrequencyModel::SelectOutputs(const std::vector<int>& rows) const {
  for (int r : rows) DEB_DEMAND(r >= 0 && r < outputs());
  if (node_->kind == Node::Kind::kRational) return FrequencyModel(node_->rational->SelectOutputs(rows));
  if (node_->kind == Node::Kind::kMeasured) return FrequencyModel(node_->measured->SelectOutputs(rows));
  auto n = std::make_shared<Node>();
  n->kind = Node::Kind::kSelect;
  n->inputs = inputs();
  n->outputs = static_cast<int>(rows.size());
  n->a = node_;
  n->rows = rows;
  return FrequencyModel(std::move(n));
}

int FrequencyModel::inputs() const { return node_->inputs; }
int FrequencyModel::outputs() const { return node_->outputs; }

std::vector<StateSpace> FrequencyModel::RationalParts() const {
  std::vector<StateSpace> parts;
  node_->Collect(&parts, nullptr, nullptr);
  return parts;
}

std::vector<std::shared_ptr<const ModalModel>> FrequencyModel::ModalParts() const {
  std::vector<std::shared_ptr<const ModalModel>> parts;
  node_->Collect(nullptr, nullptr, nullptr, nullptr, &parts);
  return parts;
}

std::vector<double> FrequencyModel::DataFrequencies() const {
  std::vector<double> f;
  node_->Collect(nullptr, &f, nullptr);
  std::sort(f.begin(), f.end());
  f.erase(std::unique(f.begin(), f.end()), f.end());
  return f;
}

std::optional<FrequencyInterval> FrequencyModel::DefinedRangeHz() const { return node_->DefinedRange(); }

bool FrequencyModel::HasLoopAroundData() const {
  bool loop = false;
  node_->Collect(nullptr, nullptr, &loop);
  return loop;
}

bool FrequencyModel::HasData() const { return node_->HasData(); }

std::vector<IrrationalBlock> FrequencyModel::IrrationalBlocks() const {
  std::vector<IrrationalBlock> blocks;
  node_->Collect(nullptr, nullptr, nullptr, &blocks);
  return blocks;
}

std::optional<CoupledRealisation> FrequencyModel::Coupled(std::string* why) const { return node_->Coupled(why); }

Eigen::MatrixXcd FrequencyModel::At(double f_hz) const { return node_->At(f_hz); }

void FrequencyModel::ForEach(const std::vector<double>& f_hz, const Visitor& fn, int threads) const {
  // A modal model alone in blocks of frequencies (one matrix product each).
  if (node_->kind == Node::Kind::kModal) return node_->modal_response->ForEach(f_hz, fn, threads);
  // A diagram in fixed blocks of frequencies (so that the last digits of a
  // modal part's products do not depend on the thread count), its modal
  // parts evaluated a block at a time.
  ParallelForBlocks(
      f_hz.size(), 64,
      [&](std::size_t lo, std::size_t hi) {
        const std::vector<Eigen::MatrixXcd> h = node_->AtBlock(
            std::vector<double>(f_hz.begin() + static_cast<std::ptrdiff_t>(lo), f_hz.begin() + static_cast<std::ptrdiff_t>(hi)));
        for (std::size_t k = lo; k < hi; ++k) fn(k, h[k - lo]);
      },
      threads);
}

}  // namespace deb
