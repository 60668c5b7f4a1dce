#include "deb/signal/fft.h"

#include <fftw3.h>

#include <mutex>
#include <new>
#include <string>

#include "deb/core/error.h"

namespace deb {
namespace {

// FFTW's planner (and plan destruction) touch global state.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

struct RealFft::Plan {
  fftw_plan plan = nullptr;
};

RealFft::Buffer::Buffer(int size, int bins) {
  // fftw_malloc gives every buffer the alignment the plan was made with, which
  // the new-array execute interface requires.
  input_ = static_cast<double*>(fftw_malloc(sizeof(double) * static_cast<std::size_t>(size)));
  output_ = reinterpret_cast<std::complex<double>*>(
      fftw_malloc(sizeof(fftw_complex) * static_cast<std::size_t>(bins)));
  if (!input_ || !output_) {
    fftw_free(input_);
    fftw_free(output_);
    throw std::bad_alloc();
  }
}

RealFft::Buffer::Buffer(Buffer&& other) noexcept : input_(other.input_), output_(other.output_) {
  other.input_ = nullptr;
  other.output_ = nullptr;
}

RealFft::Buffer& RealFft::Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    fftw_free(input_);
    fftw_free(output_);
    input_ = other.input_;
    output_ = other.output_;
    other.input_ = nullptr;
    other.output_ = nullptr;
  }
  return *this;
}

RealFft::Buffer::~Buffer() {
  fftw_free(input_);
  fftw_free(output_);
}

RealFft::RealFft(int size) : size_(size), plan_(std::make_unique<Plan>()) {
  if (size < 1) throw InputError("FFT length " + std::to_string(size) + " is invalid; it must be >= 1");
  Buffer scratch = MakeBuffer();
  std::lock_guard<std::mutex> lock(PlannerMutex());
  plan_->plan = fftw_plan_dft_r2c_1d(size, scratch.input(),
                                     reinterpret_cast<fftw_complex*>(const_cast<std::complex<double>*>(scratch.output())),
                                     FFTW_ESTIMATE);
  DEB_DEMAND(plan_->plan != nullptr);
}

RealFft::~RealFft() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  fftw_destroy_plan(plan_->plan);
}

void RealFft::Execute(Buffer& buffer) const {
  // std::complex<double> is layout-compatible with fftw_complex (double[2]).
  fftw_execute_dft_r2c(plan_->plan, buffer.input_, reinterpret_cast<fftw_complex*>(buffer.output_));
}

}  // namespace deb
