#include "deb/systems/lapack.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <new>
#include <sstream>
#include <string>
#include <vector>

// LAPACKE's own complex types would be C99 _Complex, which is not C++; the
// real routines used here do not take complex arguments.
#define lapack_complex_float std::complex<float>
#define lapack_complex_double std::complex<double>
#include <lapacke.h>
#include <cblas.h>

#include "deb/core/error.h"

namespace deb {
namespace {

// OpenBLAS's controls, looked up in the loaded libraries: null where the
// BLAS is another one.
struct OpenBlasControls {
  char* (*corename)() = nullptr;  // its kernels' name
  int (*parallel)() = nullptr;    // 0: its single-threaded build
  int (*threads)() = nullptr;
  void (*set_threads)(int) = nullptr;
};
const OpenBlasControls& OpenBlas() {
  static const OpenBlasControls c = [] {
    OpenBlasControls o;
    o.corename = reinterpret_cast<char* (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
    o.parallel = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_parallel"));
    o.threads = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    o.set_threads = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    return o;
  }();
  return c;
}

// OpenBLAS's single-threaded build (openblas_get_parallel() == 0) keeps its
// work buffers in a table it does not lock unless built with USE_LOCKING,
// which Debian's is not (it imports no mutex): two threads in it at once
// can share a buffer. Four threads calling dgees together on one 300 x 300
// matrix got Schur forms off by up to 34 (1 to 24 calls in 80,
// tests/systems/lapack_test.cpp), where each call alone gives the same form
// to the bit. Its threaded build locks (none of over 2000 such calls differed);
// other BLAS keep no such state. So every call deb makes into the BLAS or
// LAPACK takes this turn where the library is OpenBLAS's single-threaded
// build, or its threaded one running several threads per call (where calls
// at once would only compete for the cores): the exact variances and
// responses of paths analysed at once, and the products of worker threads.
std::unique_lock<std::mutex> BlasTurn() {
  static std::mutex turn;
  const OpenBlasControls& ob = OpenBlas();
  const bool needed = ob.parallel != nullptr && (ob.parallel() == 0 || (ob.threads != nullptr && ob.threads() > 1));
  return needed ? std::unique_lock<std::mutex>(turn) : std::unique_lock<std::mutex>();
}

// A square, finite, column-major A that LAPACK's int indices can address.
lapack_int RequireSquare(const Eigen::MatrixXd& a, const char* routine) {
  std::ostringstream os;
  if (a.rows() != a.cols()) {
    os << routine << ": the matrix is " << a.rows() << "x" << a.cols() << ", not square";
  } else if (a.rows() > std::numeric_limits<lapack_int>::max() / (a.rows() > 0 ? a.rows() : 1)) {
    os << routine << ": the matrix is too large for LAPACK (" << a.rows() << " rows)";
  } else if (!a.allFinite()) {
    os << routine << ": the matrix has an entry that is not finite";
  }
  if (!os.str().empty()) throw InputError(os.str());
  return static_cast<lapack_int>(a.rows());
}

// info < 0 names an illegal argument (a bug here); LAPACKE reports a failed
// workspace allocation as LAPACK_WORK_MEMORY_ERROR; info > 0 from the QR
// routines means that eigenvalues info+1 ... n did not converge.
void CheckEigenInfo(lapack_int info, const char* routine, lapack_int n) {
  if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR)
    throw std::bad_alloc();
  DEB_DEMAND(info >= 0);
  if (info > 0) {
    std::ostringstream os;
    os << routine << ": the QR iteration did not converge for the " << n << "x" << n
       << " matrix (LAPACK info " << info << "); its eigenvalues could not be computed";
    throw InputError(os.str());
  }
}

// lambda_k = wr_k + j wi_k. A zero part is returned as +0 (x + 0.0 turns -0
// into +0 and leaves every other value unchanged): a diagonal entry -0 of A
// (the damping of a rigid-body mode) must not be reported as a pole at -0.
Eigen::VectorXcd Pack(const Eigen::VectorXd& wr, const Eigen::VectorXd& wi) {
  Eigen::VectorXcd lambda(wr.size());
  for (Eigen::Index k = 0; k < wr.size(); ++k)
    lambda(k) = std::complex<double>(wr(k) + 0.0, wi(k) + 0.0);
  return lambda;
}

}  // namespace

RealSchurForm RealSchur(const Eigen::MatrixXd& a) {
  const lapack_int n = RequireSquare(a, "real Schur form (dgees)");
  RealSchurForm form{a, Eigen::MatrixXd(n, n), Eigen::VectorXcd(n)};
  if (n == 0) return form;
  Eigen::VectorXd wr(n), wi(n);
  lapack_int sdim = 0;
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info =
      LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', nullptr, n, form.t.data(), n, &sdim, wr.data(),
                    wi.data(), form.u.data(), n);
  CheckEigenInfo(info, "real Schur form (dgees)", n);
  form.eigenvalues = Pack(wr, wi);
  return form;
}

Eigen::VectorXcd RealEigenvalues(const Eigen::MatrixXd& a) {
  const lapack_int n = RequireSquare(a, "eigenvalues (dgees)");
  if (n == 0) return Eigen::VectorXcd(0);
  Eigen::MatrixXd t = a;
  Eigen::VectorXd wr(n), wi(n);
  lapack_int sdim = 0;
  double no_vectors = 0.0;
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info = LAPACKE_dgees(LAPACK_COL_MAJOR, 'N', 'N', nullptr, n, t.data(), n, &sdim, wr.data(),
                                        wi.data(), &no_vectors, 1);
  CheckEigenInfo(info, "eigenvalues (dgees)", n);
  return Pack(wr, wi);
}

namespace {

// Sides from which a Sylvester equation is solved by dtrsyl3.
constexpr lapack_int kBlockedSylvester = 64;

// T1 X + isgn X op(T2) = C, op(T2) = T2^T ('T') or T2 ('N').
SylvesterSolution SolveSylvester(const Eigen::MatrixXd& t1, const Eigen::MatrixXd& t2, const Eigen::MatrixXd& c,
                                 char trans2, lapack_int isgn) {
  const lapack_int n1 = RequireSquare(t1, "Sylvester equation (dtrsyl)");
  const lapack_int n2 = RequireSquare(t2, "Sylvester equation (dtrsyl)");
  DEB_DEMAND(c.rows() == n1 && c.cols() == n2);
  SylvesterSolution s{c};
  if (n1 == 0 || n2 == 0) return s;
  // LAPACKE refuses a NaN argument; the solution of a non-finite C is not finite.
  if (!c.allFinite()) {
    s.x.setConstant(std::numeric_limits<double>::quiet_NaN());
    return s;
  }
  double scale = 1.0;
  // dtrsyl3 (level 3) for large equations: dtrsyl's dot products make an
  // n x n solve O(n^3) at memory speed (a 2000-state loop: minutes).
  const bool blocked = std::min(n1, n2) >= kBlockedSylvester;
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info =
      blocked ? LAPACKE_dtrsyl3(LAPACK_COL_MAJOR, 'N', trans2, isgn, n1, n2, t1.data(), n1, t2.data(), n2,
                                s.x.data(), n1, &scale)
              : LAPACKE_dtrsyl(LAPACK_COL_MAJOR, 'N', trans2, isgn, n1, n2, t1.data(), n1, t2.data(), n2,
                               s.x.data(), n1, &scale);
  if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR)
    throw std::bad_alloc();
  DEB_DEMAND(info >= 0);
  s.near_singular = info > 0;
  if (scale != 1.0) s.x /= scale;
  return s;
}

}  // namespace

SylvesterSolution SolveQuasiTriangularSylvester(const Eigen::MatrixXd& t1,
                                                const Eigen::MatrixXd& t2,
                                                const Eigen::MatrixXd& c) {
  return SolveSylvester(t1, t2, c, 'T', 1);
}

SylvesterSolution SolveQuasiTriangularSylvesterMinus(const Eigen::MatrixXd& t1,
                                                     const Eigen::MatrixXd& t2,
                                                     const Eigen::MatrixXd& c) {
  return SolveSylvester(t1, t2, c, 'N', -1);
}

int ReorderRealSchur(RealSchurForm& form, const std::vector<bool>& lead) {
  const lapack_int n = static_cast<lapack_int>(form.t.rows());
  DEB_DEMAND(form.t.cols() == n && form.u.rows() == n && form.u.cols() == n &&
             lead.size() == static_cast<std::size_t>(n));
  if (n == 0) return 0;
  std::vector<lapack_logical> select(lead.begin(), lead.end());
  Eigen::MatrixXd t = form.t, u = form.u;
  Eigen::VectorXd wr(n), wi(n);
  lapack_int m = 0;
  double s = 0.0, sep = 0.0;
  // The _work form with its workspace here: LAPACKE_dtrsen's workspace query
  // writes through a null iwork for job 'N' in the reference LAPACKE of
  // Debian 12. For job 'N': lwork >= n, liwork >= 1.
  std::vector<double> work(static_cast<std::size_t>(n));
  lapack_int iwork = 0;
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info = LAPACKE_dtrsen_work(LAPACK_COL_MAJOR, 'N', 'V', select.data(), n, t.data(), n, u.data(),
                                              n, wr.data(), wi.data(), &m, &s, &sep, work.data(), n, &iwork, 1);
  if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR)
    throw std::bad_alloc();
  DEB_DEMAND(info >= 0);
  if (info > 0)
    throw InputError("reordering the real Schur form (dtrsen): two eigenvalues are too close to be swapped "
                     "(LAPACK info " + std::to_string(info) + ")");
  form.t = std::move(t);
  form.u = std::move(u);
  form.eigenvalues = Pack(wr, wi);
  return static_cast<int>(m);
}

SylvesterSolution SolveSchurCoupling(const Eigen::MatrixXd& t, int lo, int s, int e, const Eigen::MatrixXd& c,
                                     bool blocked) {
  const lapack_int n = static_cast<lapack_int>(t.rows());
  DEB_DEMAND(t.cols() == n && 0 <= lo && lo < s && s < e && e <= n && c.rows() == s - lo && c.cols() == e - s);
  SylvesterSolution out{c};
  if (!c.allFinite()) {
    out.x.setConstant(std::numeric_limits<double>::quiet_NaN());
    return out;
  }
  double scale = 1.0;
  const double* t1 = t.data() + static_cast<Eigen::Index>(lo) * n + lo;
  const double* t2 = t.data() + static_cast<Eigen::Index>(s) * n + s;
  // The _work form for dtrsyl: LAPACKE's NaN scan of the whole leading
  // block would cost as much as the solve (T comes from dgees: finite).
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info =
      blocked ? LAPACKE_dtrsyl3(LAPACK_COL_MAJOR, 'N', 'N', -1, s - lo, e - s, t1, n, t2, n, out.x.data(), s - lo,
                                &scale)
              : LAPACKE_dtrsyl_work(LAPACK_COL_MAJOR, 'N', 'N', -1, s - lo, e - s, t1, n, t2, n, out.x.data(),
                                    s - lo, &scale);
  if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR) throw std::bad_alloc();
  DEB_DEMAND(info >= 0);
  out.near_singular = info > 0;
  if (scale != 1.0) out.x /= scale;
  return out;
}

bool MoveRealSchurBlock(RealSchurForm& form, int& from, int& to) {
  const lapack_int n = static_cast<lapack_int>(form.t.rows());
  DEB_DEMAND(form.t.cols() == n && form.u.rows() == n && form.u.cols() == n && 0 <= from && from < n && 0 <= to &&
             to < n);
  lapack_int ifst = from + 1, ilst = to + 1;
  std::vector<double> work(static_cast<std::size_t>(n));
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info = LAPACKE_dtrexc_work(LAPACK_COL_MAJOR, 'V', n, form.t.data(), n, form.u.data(), n, &ifst,
                                              &ilst, work.data());
  DEB_DEMAND(info >= 0);
  // The eigenvalues from the diagonal blocks as they now stand.
  for (lapack_int i = 0; i < n;) {
    if (i + 1 < n && form.t(i + 1, i) != 0.0) {
      const double a = form.t(i, i), im = std::sqrt(std::abs(form.t(i, i + 1))) * std::sqrt(std::abs(form.t(i + 1, i)));
      form.eigenvalues(i) = std::complex<double>(a + 0.0, im);
      form.eigenvalues(i + 1) = std::complex<double>(a + 0.0, -im);
      i += 2;
    } else {
      form.eigenvalues(i) = std::complex<double>(form.t(i, i) + 0.0, 0.0);
      i += 1;
    }
  }
  // dtrexc leaves ilst on the first row of the block's position, where it
  // stopped if a swap failed.
  from = to = static_cast<int>(ilst) - 1;
  return info == 0;
}

double UnitUpperTriangularCondition(const Eigen::MatrixXd& y) {
  const lapack_int n = static_cast<lapack_int>(y.rows());
  DEB_DEMAND(y.cols() == n);
  if (n == 0) return 1.0;
  double rcond = 0.0;
  std::vector<double> work(3 * static_cast<std::size_t>(n));
  std::vector<lapack_int> iwork(static_cast<std::size_t>(n));
  const std::unique_lock<std::mutex> turn = BlasTurn();
  const lapack_int info =
      LAPACKE_dtrcon_work(LAPACK_COL_MAJOR, '1', 'U', 'U', n, y.data(), n, &rcond, work.data(), iwork.data());
  DEB_DEMAND(info == 0);
  return rcond > 0.0 ? 1.0 / rcond : std::numeric_limits<double>::infinity();
}

namespace {

// What OpenBLAS's kernels named `name` run (its names in 0.3.21 and since):
// AVX-512, AVX2 and FMA, or older instructions (also for unknown names).
enum class KernelWidth { kOlder, kAvx2, kAvx512 };
KernelWidth WidthOf(const std::string& name) {
  for (const char* avx512 : {"SkylakeX", "Cooperlake", "SapphireRapids"})
    if (name == avx512) return KernelWidth::kAvx512;
  for (const char* avx2 : {"Haswell", "Zen"})
    if (name == avx2) return KernelWidth::kAvx2;
  return KernelWidth::kOlder;
}

}  // namespace

std::string BlasKernel() {
  char* (*const name)() = OpenBlas().corename;
  const char* text = name ? name() : nullptr;
  return text ? text : "";
}

std::optional<std::string> BetterBlasKernel() {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return std::nullopt;
  const std::string now = BlasKernel();
  if (now.empty() || WidthOf(now) != KernelWidth::kOlder) return std::nullopt;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return std::nullopt;
}

bool BlasProductIsFaster() {
  static const bool faster = WidthOf(BlasKernel()) == KernelWidth::kAvx512;
  return faster;
}

void UseOneBlasThreadPerCall() {
  if (OpenBlas().set_threads != nullptr) OpenBlas().set_threads(1);
}

void BlasProduct(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b,
                 Eigen::Ref<Eigen::MatrixXd> out) {
  DEB_DEMAND(a.cols() == b.rows() && out.rows() == a.rows() && out.cols() == b.cols());
  constexpr Eigen::Index kMax = std::numeric_limits<int>::max();
  DEB_DEMAND(a.rows() <= kMax && a.cols() <= kMax && b.cols() <= kMax && a.outerStride() <= kMax &&
             b.outerStride() <= kMax && out.outerStride() <= kMax);
  if (out.size() == 0) return;
  if (a.cols() == 0) {
    out.setZero();
    return;
  }
  const std::unique_lock<std::mutex> turn = BlasTurn();
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, static_cast<int>(a.rows()), static_cast<int>(b.cols()),
              static_cast<int>(a.cols()), 1.0, a.data(), static_cast<int>(a.outerStride()), b.data(),
              static_cast<int>(b.outerStride()), 0.0, out.data(), static_cast<int>(out.outerStride()));
}

void BlasUnitUpperSolve(const Eigen::Ref<const Eigen::MatrixXd>& y, Eigen::Ref<Eigen::MatrixXd> x) {
  DEB_DEMAND(y.rows() == y.cols() && y.rows() == x.rows());
  constexpr Eigen::Index kMax = std::numeric_limits<int>::max();
  DEB_DEMAND(x.rows() <= kMax && x.cols() <= kMax && y.outerStride() <= kMax && x.outerStride() <= kMax);
  if (x.size() == 0) return;
  const std::unique_lock<std::mutex> turn = BlasTurn();
  cblas_dtrsm(CblasColMajor, CblasLeft, CblasUpper, CblasNoTrans, CblasUnit, static_cast<int>(x.rows()),
              static_cast<int>(x.cols()), 1.0, y.data(), static_cast<int>(y.outerStride()), x.data(),
              static_cast<int>(x.outerStride()));
}

}  // namespace deb
