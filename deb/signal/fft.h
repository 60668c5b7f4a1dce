// Internal: not part of the public API.
// Real-to-complex discrete Fourier transforms for spectral estimation. This is
// the only code in deb that talks to FFTW (STYLE rule 3): callers see std and
// Eigen types only.
//
// Convention: X_k = sum_{n=0}^{N-1} x_n exp(-j 2 pi k n / N), k = 0 .. N/2
// (the non-negative frequencies; the others are conj(X_{N-k}) for real x).
// Unnormalised, as FFTW computes it.
//
// Threads: FFTW's planner is not thread-safe, so plan creation and destruction
// are serialised by a mutex; executing one plan on different arrays from
// several threads at once is safe (FFTW's new-array execute interface), as
// long as each thread uses its own Buffer.
#pragma once

#include <complex>
#include <memory>

namespace deb {

class RealFft {
 public:
  // Scratch arrays aligned as FFTW needs them; one per thread.
  class Buffer {
   public:
    Buffer(Buffer&&) noexcept;
    Buffer& operator=(Buffer&&) noexcept;
    ~Buffer();
    // size() real inputs; the transform may overwrite them.
    double* input() { return input_; }
    // bins() complex outputs.
    const std::complex<double>* output() const { return output_; }

   private:
    friend class RealFft;
    Buffer(int size, int bins);
    double* input_ = nullptr;
    std::complex<double>* output_ = nullptr;
  };

  // Plans a transform of length size >= 1 (FFTW_ESTIMATE: no timing runs, so
  // results do not depend on the machine's load).
  // @throws InputError if size < 1.
  explicit RealFft(int size);
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  int size() const { return size_; }
  // N/2 + 1 non-negative frequency bins.
  int bins() const { return size_ / 2 + 1; }

  Buffer MakeBuffer() const { return Buffer(size_, bins()); }

  // buffer.output() = DFT of buffer.input(). Thread-safe for distinct buffers.
  void Execute(Buffer& buffer) const;

 private:
  struct Plan;
  int size_;
  std::unique_ptr<Plan> plan_;
};

}  // namespace deb
