#include "deb/signal/welch.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/signal/chi_square.h"
#include "deb/signal/fft.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

// How a series of n samples is cut into segments.
struct Segmentation {
  int length = 0;   // L
  int overlap = 0;  // samples shared by neighbours
  int step = 0;     // L - overlap
  int count = 0;    // K
};

int SegmentCount(Eigen::Index n, int length, int step) {
  return n < length ? 0 : 1 + static_cast<int>((n - length) / step);
}

Segmentation Segment(Eigen::Index n, int length, double overlap) {
  Segmentation s;
  s.length = length;
  s.overlap = std::min(length - 1, static_cast<int>(std::floor(overlap * length)));
  s.step = length - s.overlap;
  s.count = SegmentCount(n, length, s.step);
  return s;
}

Segmentation Plan(Eigen::Index n, const WelchOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError("Welch options: " + error);
  const Segmentation s = Segment(n, SegmentLengthFor(n, options), options.overlap);
  DEB_DEMAND(s.count >= 1);
  return s;
}

// out_n = w_n (x_n - trend_n) for one segment.
void Prepare(const double* x, int length, Detrend detrend, const std::vector<double>& w, double* out) {
  double mean = 0.0, slope = 0.0;
  const double mid = 0.5 * (length - 1);
  if (detrend != Detrend::kNone) {
    for (int n = 0; n < length; ++n) mean += x[n];
    mean /= length;
  }
  if (detrend == Detrend::kLinear && length > 1) {
    // Least squares a + b t with t = n - mid centred, so a is the mean;
    // sum t^2 = L (L^2 - 1) / 12.
    double st = 0.0;
    for (int n = 0; n < length; ++n) st += (n - mid) * x[n];
    slope = st / (static_cast<double>(length) * (static_cast<double>(length) * length - 1.0) / 12.0);
  }
  for (int n = 0; n < length; ++n) out[n] = w[static_cast<std::size_t>(n)] * (x[n] - mean - slope * (n - mid));
}

// Expected median of k unit exponentials (see welch.h).
double MedianBias(int k) {
  const int odd = k % 2 == 1 ? k : k - 1;
  double b = 0.0;
  for (int n = 1; n <= odd; ++n) b += (n % 2 == 1 ? 1.0 : -1.0) / n;
  return b;
}

// Median of v (modified), the two middle values averaged for an even count.
double Median(std::vector<double>& v) {
  const std::size_t half = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(half), v.end());
  const double upper = v[half];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(half)));
}

// c_k / (fs S2): the one-sided density scale of bin k.
std::vector<double> BinScales(int length, double rate_hz, double sum_squares) {
  const int bins = length / 2 + 1;
  std::vector<double> scale(static_cast<std::size_t>(bins), 2.0 / (rate_hz * sum_squares));
  scale[0] = 1.0 / (rate_hz * sum_squares);
  if (length % 2 == 0) scale.back() = 1.0 / (rate_hz * sum_squares);
  return scale;
}

std::vector<double> Frequencies(int length, double rate_hz) {
  std::vector<double> f(static_cast<std::size_t>(length / 2 + 1));
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = static_cast<double>(k) * rate_hz / length;
  return f;
}

WelchProvenance Provenance(const Segmentation& s, const std::vector<double>& window, double rate_hz,
                           const WelchOptions& options) {
  WelchProvenance p;
  p.window = options.window;
  p.segment_length = s.length;
  p.overlap_samples = s.overlap;
  p.segments = s.count;
  p.detrend = options.detrend;
  p.averaging = options.averaging;
  p.rate_hz = rate_hz;
  p.resolution_hz = rate_hz / s.length;
  p.enbw_hz = EnbwBins(window) * rate_hz / s.length;
  p.degrees_of_freedom = WelchDegreesOfFreedom(window, s.step, s.count, options.averaging);
  p.confidence = options.confidence;
  const double alpha = 1.0 - options.confidence;
  p.lower_factor = p.degrees_of_freedom / ChiSquareQuantile(1.0 - 0.5 * alpha, p.degrees_of_freedom);
  p.upper_factor = p.degrees_of_freedom / ChiSquareQuantile(0.5 * alpha, p.degrees_of_freedom);
  return p;
}

// Samples of FFT work per job: a job takes this many samples' worth of
// segments (at least one), which keeps each job well above the cost of
// handing it to a thread (parallel.h). It depends on the segment length
// only, so the jobs and the order of the sums are the same for any thread
// count.
constexpr Eigen::Index kJobSamples = Eigen::Index{1} << 16;

int SegmentsPerJob(const Segmentation& s, int channels_per_segment) {
  return static_cast<int>(std::max<Eigen::Index>(1, kJobSamples / (Eigen::Index{s.length} * channels_per_segment)));
}

// Objects reused from one job to the next: a fresh FFT buffer or partial
// sum per job would be fresh memory each time, and first touches of pages
// (a fault each, tens of microseconds on a virtual machine) cost more than
// the FFTs of large segments. Holds about as many objects as threads ran.
template <typename T>
class Scratch {
 public:
  template <typename Make>
  T Take(Make&& make) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        T t = std::move(free_.back());
        free_.pop_back();
        return t;
      }
    }
    return make();
  }
  void Give(T t) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(t));
  }

 private:
  std::mutex mutex_;
  std::vector<T> free_;
};

// Adds per-job partial sums in job order, whichever thread finished first,
// so that the total is bitwise the same for any thread count. A partial is
// kept only until the jobs before it have been added.
template <typename Matrix>
class OrderedSum {
 public:
  OrderedSum(std::function<void(std::size_t, const Matrix&)> add, Scratch<Matrix>* spare)
      : add_(std::move(add)), spare_(spare) {}
  // Added partials go back to *spare.
  void Add(std::size_t job, Matrix partial) {
    const std::lock_guard<std::mutex> lock(mutex_);
    pending_.emplace(job, std::move(partial));
    for (auto it = pending_.begin(); it != pending_.end() && it->first == next_; it = pending_.erase(it), ++next_) {
      add_(it->first, it->second);
      spare_->Give(std::move(it->second));
    }
  }

 private:
  std::function<void(std::size_t, const Matrix&)> add_;
  Scratch<Matrix>* spare_;
  std::mutex mutex_;
  std::size_t next_ = 0;
  std::map<std::size_t, Matrix> pending_;
};

}  // namespace

bool WelchOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (segment_length != 0 && segment_length < kMinSegmentLength)
    return fail("segment_length " + std::to_string(segment_length) + " is invalid; a segment needs at least " +
                std::to_string(kMinSegmentLength) + " samples (8 bins above 0 Hz), or 0: automatic");
  if (!(overlap >= 0.0 && overlap < 1.0))
    return fail("overlap " + NumberText(overlap) + " is invalid; it is a fraction of a segment in [0, 1)");
  if (!(confidence > 0.0 && confidence < 1.0))
    return fail("confidence " + NumberText(confidence) + " is invalid; it must be in (0, 1), e.g. 0.95");
  // The bounds are the chi-square quantiles at (1 -+ confidence) / 2, which
  // must stay below 1 in double precision.
  if (!(1.0 - 0.5 * (1.0 - confidence) < 1.0))
    return fail("confidence " + NumberText(confidence) + " is too close to 1: (1 + confidence) / 2 rounds to 1, "
                "where the chi-square quantile is infinite; use e.g. 0.999");
  return true;
}

int SegmentLengthFor(Eigen::Index samples, const WelchOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError("Welch options: " + error);
  if (options.segment_length > 0) {
    if (samples < options.segment_length)
      throw InputError("too few samples: " + std::to_string(samples) + " samples are fewer than one segment of " +
                       std::to_string(options.segment_length) +
                       " samples; use a shorter segment_length or a longer recording");
    return options.segment_length;
  }
  for (int length = 1 << 30; length >= WelchOptions::kMinSegmentLength; length /= 2) {
    const Segmentation s = Segment(samples, length, options.overlap);
    if (s.count >= 8) return length;
  }
  if (samples >= WelchOptions::kMinSegmentLength) return WelchOptions::kMinSegmentLength;  // fewer averages
  throw InputError("too few samples: " + std::to_string(samples) + " samples are fewer than one segment of " +
                   std::to_string(WelchOptions::kMinSegmentLength) +
                   " (the shortest, 8 bins above 0 Hz); record longer");
}

double WelchDegreesOfFreedom(const std::vector<double>& window, int step, int segments, Averaging averaging) {
  DEB_DEMAND(step >= 1 && segments >= 1);
  const WindowSums sums = SumsOf(window);
  const int length = static_cast<int>(window.size());
  double correlation = 0.0;
  for (int m = 1; m < segments && m * step < length; ++m) {
    const int shift = m * step;
    double r = 0.0;
    for (int n = 0; n + shift < length; ++n)
      r += window[static_cast<std::size_t>(n)] * window[static_cast<std::size_t>(n + shift)];
    r /= sums.sum_squares;
    correlation += (1.0 - static_cast<double>(m) / segments) * r * r;
  }
  const double nu = 2.0 * segments / (1.0 + 2.0 * correlation);
  constexpr double kLn2 = 0.69314718055994530942;
  return averaging == Averaging::kMedian ? nu * kLn2 * kLn2 : nu;
}

PsdEstimate WelchPsd(const TimeSeries& series, const WelchOptions& options) {
  const Segmentation s = Plan(series.size(), options);
  const std::vector<double> window = MakeWindow(options.window, s.length);
  const RealFft fft(s.length);
  const int bins = fft.bins();
  const int channels = series.channels();
  const bool median = options.averaging == Averaging::kMedian;
  std::vector<Eigen::MatrixXd> periodograms;  // median: per channel, bins x K
  if (median) periodograms.assign(static_cast<std::size_t>(channels), Eigen::MatrixXd(bins, s.count));
  // One job per (channel, group of segments), channel-major; each
  // segment's FFT is work of its job.
  const int per_job = SegmentsPerJob(s, 1);
  const int groups = (s.count + per_job - 1) / per_job;
  Eigen::MatrixXd total;
  if (!median) total = Eigen::MatrixXd::Zero(bins, channels);
  Scratch<RealFft::Buffer> buffers;
  Scratch<Eigen::VectorXd> partials;
  OrderedSum<Eigen::VectorXd> sums(
      [&](std::size_t job, const Eigen::VectorXd& part) { total.col(static_cast<Eigen::Index>(job) / groups) += part; },
      &partials);
  ParallelForEach(
      static_cast<std::size_t>(channels) * static_cast<std::size_t>(groups),
      [&](std::size_t job) {
        const int c = static_cast<int>(job / static_cast<std::size_t>(groups));
        const int first = static_cast<int>(job % static_cast<std::size_t>(groups)) * per_job;
        RealFft::Buffer buffer = buffers.Take([&] { return fft.MakeBuffer(); });
        Eigen::VectorXd local;
        if (!median) {
          local = partials.Take([&] { return Eigen::VectorXd(bins); });
          local.setZero();
        }
        for (int k = first; k < std::min(s.count, first + per_job); ++k) {
          Prepare(series.samples().col(c).data() + static_cast<std::ptrdiff_t>(k) * s.step, s.length,
                  options.detrend, window, buffer.input());
          fft.Execute(buffer);
          const std::complex<double>* x = buffer.output();
          if (median) {
            double* target = periodograms[static_cast<std::size_t>(c)].col(k).data();
            for (int b = 0; b < bins; ++b) target[b] = std::norm(x[b]);
          } else {
            for (int b = 0; b < bins; ++b) local[b] += std::norm(x[b]);
          }
        }
        buffers.Give(std::move(buffer));
        if (!median) sums.Add(job, std::move(local));
      },
      options.threads);

  PsdEstimate e;
  e.f_hz = Frequencies(s.length, series.rate_hz());
  const std::vector<double> scale = BinScales(s.length, series.rate_hz(), SumsOf(window).sum_squares);
  if (median) {
    e.psd.resize(bins, channels);
    const double bias = MedianBias(s.count);
    // Blocks of kChunk bins: copying a block reads each segment's column
    // contiguously instead of striding across all segments bin by bin.
    constexpr int kChunk = 64;
    const int chunks = (bins + kChunk - 1) / kChunk;
    ParallelFor(
        static_cast<std::size_t>(chunks) * static_cast<std::size_t>(channels),
        [&](std::size_t begin, std::size_t end) {
          Eigen::MatrixXd block(s.count, kChunk);
          std::vector<double> values(static_cast<std::size_t>(s.count));
          for (std::size_t item = begin; item < end; ++item) {
            const int c = static_cast<int>(item / static_cast<std::size_t>(chunks));
            const int first = static_cast<int>(item % static_cast<std::size_t>(chunks)) * kChunk;
            const int width = std::min(kChunk, bins - first);
            const Eigen::MatrixXd& p = periodograms[static_cast<std::size_t>(c)];
            block.leftCols(width) = p.middleRows(first, width).transpose();
            for (int b = 0; b < width; ++b) {
              for (int k = 0; k < s.count; ++k) values[static_cast<std::size_t>(k)] = block(k, b);
              e.psd(first + b, c) = scale[static_cast<std::size_t>(first + b)] * Median(values) / bias;
            }
          }
        },
        options.threads);
  } else {
    e.psd = total / static_cast<double>(s.count);
    for (int b = 0; b < bins; ++b) e.psd.row(b) *= scale[static_cast<std::size_t>(b)];
  }
  e.channel_names = series.channel_names();
  e.unit = series.unit();
  e.provenance = Provenance(s, window, series.rate_hz(), options);
  return e;
}

CsdEstimate WelchCsd(const TimeSeries& series, const WelchOptions& options) {
  const Segmentation s = Plan(series.size(), options);
  const std::vector<double> window = MakeWindow(options.window, s.length);
  const RealFft fft(s.length);
  const int bins = fft.bins();
  const int c_count = series.channels();
  const bool median = options.averaging == Averaging::kMedian;
  // Upper-triangle pairs (i <= j), column i + C j of the result.
  std::vector<std::pair<int, int>> pairs;
  for (int j = 0; j < c_count; ++j)
    for (int i = 0; i <= j; ++i) pairs.emplace_back(i, j);
  std::vector<Eigen::MatrixXcd> products;  // median: per pair, bins x K
  if (median) products.assign(pairs.size(), Eigen::MatrixXcd(bins, s.count));
  // One job per group of segments (a segment's FFTs of every channel, then
  // the products of every pair), partial sums per pair.
  const int per_job = SegmentsPerJob(s, c_count);
  const int groups = (s.count + per_job - 1) / per_job;
  Eigen::MatrixXcd total;
  if (!median) total = Eigen::MatrixXcd::Zero(bins, static_cast<Eigen::Index>(pairs.size()));
  Scratch<RealFft::Buffer> buffers;
  Scratch<Eigen::MatrixXcd> partials, transforms;
  OrderedSum<Eigen::MatrixXcd> sums([&](std::size_t, const Eigen::MatrixXcd& part) { total += part; }, &partials);
  ParallelForEach(
      static_cast<std::size_t>(groups),
      [&](std::size_t job) {
        const int first = static_cast<int>(job) * per_job;
        RealFft::Buffer buffer = buffers.Take([&] { return fft.MakeBuffer(); });
        Eigen::MatrixXcd x = transforms.Take([&] { return Eigen::MatrixXcd(bins, c_count); });
        Eigen::MatrixXcd local;
        if (!median) {
          local = partials.Take([&] { return Eigen::MatrixXcd(bins, static_cast<Eigen::Index>(pairs.size())); });
          local.setZero();
        }
        for (int k = first; k < std::min(s.count, first + per_job); ++k) {
          for (int c = 0; c < c_count; ++c) {
            Prepare(series.samples().col(c).data() + static_cast<std::ptrdiff_t>(k) * s.step, s.length,
                    options.detrend, window, buffer.input());
            fft.Execute(buffer);
            x.col(c) = Eigen::Map<const Eigen::VectorXcd>(buffer.output(), bins);
          }
          for (std::size_t p = 0; p < pairs.size(); ++p) {
            const int i = pairs[p].first, j = pairs[p].second;
            // conj on the first channel: S_ij = conj(X_i) X_j.
            if (median) {
              products[p].col(k) = x.col(i).conjugate().cwiseProduct(x.col(j));
            } else {
              local.col(static_cast<Eigen::Index>(p)) += x.col(i).conjugate().cwiseProduct(x.col(j));
            }
          }
        }
        buffers.Give(std::move(buffer));
        transforms.Give(std::move(x));
        if (!median) sums.Add(job, std::move(local));
      },
      options.threads);

  CsdEstimate e;
  e.f_hz = Frequencies(s.length, series.rate_hz());
  e.channels = c_count;
  const std::vector<double> scale = BinScales(s.length, series.rate_hz(), SumsOf(window).sum_squares);
  if (median) {
    e.csd = Eigen::MatrixXcd::Zero(bins, c_count * c_count);
    const double bias = MedianBias(s.count);
    ParallelFor(
        pairs.size() * static_cast<std::size_t>(bins),
        [&](std::size_t begin, std::size_t end) {
          std::vector<double> re(static_cast<std::size_t>(s.count)), im(re.size());
          for (std::size_t item = begin; item < end; ++item) {
            const std::size_t p = item / static_cast<std::size_t>(bins);
            const int b = static_cast<int>(item % static_cast<std::size_t>(bins));
            for (int k = 0; k < s.count; ++k) {
              re[static_cast<std::size_t>(k)] = products[p](b, k).real();
              im[static_cast<std::size_t>(k)] = products[p](b, k).imag();
            }
            const auto [i, j] = pairs[p];
            const double imag = i == j ? 0.0 : Median(im);
            e.csd(b, i + c_count * j) = scale[static_cast<std::size_t>(b)] / bias * std::complex<double>(Median(re), imag);
          }
        },
        options.threads);
  } else {
    e.csd = Eigen::MatrixXcd::Zero(bins, c_count * c_count);
    for (std::size_t p = 0; p < pairs.size(); ++p)
      e.csd.col(pairs[p].first + c_count * pairs[p].second) =
          total.col(static_cast<Eigen::Index>(p)) / static_cast<double>(s.count);
    for (int b = 0; b < bins; ++b) e.csd.row(b) *= scale[static_cast<std::size_t>(b)];
  }
  for (const auto& [i, j] : pairs) {
    if (i == j) {
      e.csd.col(i + c_count * i) = e.csd.col(i + c_count * i).real().cast<std::complex<double>>();
    } else {
      e.csd.col(j + c_count * i) = e.csd.col(i + c_count * j).conjugate();
    }
  }
  e.channel_names = series.channel_names();
  e.unit = series.unit();
  e.provenance = Provenance(s, window, series.rate_hz(), options);
  return e;
}

}  // namespace deb
