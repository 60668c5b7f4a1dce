// Internal: not part of the public API.
// The real Schur form and quasi-triangular Sylvester equations through LAPACK
// (its C interface LAPACKE), for the exact-variance (Lyapunov) solver. This is
// the only code in deb that talks to LAPACK: callers see Eigen types only.
// Every LAPACK status is checked: an illegal argument is a programming error
// (DEB_DEMAND), a QR iteration that does not converge throws, and no result
// is returned that LAPACK did not vouch for.
//
// Why LAPACK here: dgees and dtrsyl keep the Bartels-Stewart solver and the
// block-diagonal form (real_block_diagonal.h) in real arithmetic, conjugate
// pairs together in 2x2 blocks, where Eigen has only ComplexSchur (complex
// QR iterations) and no Sylvester solver. deb is linked against the system's
// LAPACK and BLAS; tools/install-deps installs OpenBLAS's threaded build
// (libopenblas0-pthread), which provides both: dgees on a 2000 x 2000
// matrix took 3.6 s against about 30 s with the reference BLAS and 26 s with
// Eigen's RealSchur. The command line runs it at one thread per call
// (UseOneBlasThreadPerCall), because deb runs its own threads across paths
// and frequencies (at its default thread count, sharing 2 cores with them,
// it took 15 s); its threaded build, unlike its single-threaded one, may be
// called from those threads at once. Eigenvalues alone stay with Eigen's
// EigenSolver.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

namespace deb {

// A = U T U^T with U orthogonal and T quasi upper triangular (real Schur
// form, dgees, no reordering): 1x1 blocks for real eigenvalues, standardised
// 2x2 blocks [a b; c a] with b c < 0 for the pairs a +- j sqrt(-b c).
struct RealSchurForm {
  Eigen::MatrixXd t;
  Eigen::MatrixXd u;
  // The eigenvalues in the order of T's diagonal: real ones with imaginary
  // part 0 exactly, a pair's 2x2 block as exact conjugates, the +j member
  // first.
  Eigen::VectorXcd eigenvalues;
};

// @throws InputError if A is not square or not finite, or if the QR
//         iteration does not converge.
RealSchurForm RealSchur(const Eigen::MatrixXd& a);

// The eigenvalues alone (dgees without Schur vectors), as RealSchur's.
// @throws as RealSchur.
Eigen::VectorXcd RealEigenvalues(const Eigen::MatrixXd& a);

// X with T1 X + X T2^T = C, T1 (n1 x n1) and T2 (n2 x n2) in real Schur form,
// C n1 x n2 (dtrsyl). dtrsyl returns X scaled by a factor <= 1 chosen to
// avoid overflow; the scale is divided out, so an X too large for double has
// infinite entries, and a C with an entry that is not finite gives X = NaN.
// `near_singular` is set when dtrsyl met a pivot below eps max(|T1|, |T2|)
// and replaced it by that bound (LAPACK's INFO = 1): T1 and -T2 may have
// nearly common eigenvalues, or a non-normal T (large off-diagonal entries)
// only makes the bound large. The perturbation is of the size of the
// rounding, so X is then to be judged by its residual, not discarded.
struct SylvesterSolution {
  Eigen::MatrixXd x;
  bool near_singular = false;
};

SylvesterSolution SolveQuasiTriangularSylvester(const Eigen::MatrixXd& t1,
                                                const Eigen::MatrixXd& t2,
                                                const Eigen::MatrixXd& c);

// X with T1 X - X T2 = C (dtrsyl, no transposes), as above otherwise: the
// equation that decouples the blocks of a block upper triangular T.
SylvesterSolution SolveQuasiTriangularSylvesterMinus(const Eigen::MatrixXd& t1,
                                                     const Eigen::MatrixXd& t2,
                                                     const Eigen::MatrixXd& c);

// X with T(lo:s, lo:s) X - X T(s:e, s:e) = C for one real Schur form T,
// 0 <= lo < s < e <= n, none inside a 2x2 block, C (s - lo) x (e - s)
// (dtrsyl on T's own storage, no copies; `blocked`: dtrsyl3, LAPACK's
// level-3 version, for wide C): the coupling that block-diagonalisation
// removes (real_block_diagonal.h). Scale and INFO = 1 as above.
SylvesterSolution SolveSchurCoupling(const Eigen::MatrixXd& t, int lo, int s, int e, const Eigen::MatrixXd& c,
                                     bool blocked = false);

// Moves the diagonal block of a real Schur form that starts at row `from`
// to start at row `to` by adjacent swaps (dtrexc), updating T, U and the
// eigenvalues. Returns false if two blocks were too close to swap (LAPACK
// info 1): the swaps made so far stand (the form is still a valid Schur
// form), and `from` is where the block now starts. `to` is adjusted as
// dtrexc adjusts it (onto the first row of a 2x2 block).
bool MoveRealSchurBlock(RealSchurForm& form, int& from, int& to);

// The 1-norm condition number of a unit upper triangular matrix, estimated
// (dtrcon, O(n^2)); infinite if it is numerically singular.
double UnitUpperTriangularCondition(const Eigen::MatrixXd& y);

// Reorders a real Schur form (dtrsen) so that the eigenvalues with
// lead[k] set (k in the order of form.eigenvalues; a pair's two members
// alike) come first on T's diagonal; U and the eigenvalues follow. Returns
// how many lead.
// @throws InputError if LAPACK could not swap two blocks (eigenvalues too
//         close: info 1); the form is then unchanged.
int ReorderRealSchur(RealSchurForm& form, const std::vector<bool>& lead);

// The kernels of the BLAS under LAPACK. OpenBLAS picks them by the
// processor's model number when it is loaded; 0.3.21 (Debian 12) does not
// know the newest processors and falls back to its oldest, SSE3 kernels on
// them ("Prescott", on a Xeon of model 207 with AVX-512): dgees on 2000
// states then took 6.9 s instead of 3.6 s with its AVX-512 kernels
// ("SkylakeX"), and the whole dense 1000-mode budget 9.5 s instead of 7.1 s.
//
// BlasKernel: the kernels in use, as OpenBLAS names them ("SkylakeX"), or
// empty when the BLAS is not OpenBLAS (asked at run time: deb links whatever
// BLAS the system provides).
std::string BlasKernel();
// The kernels OpenBLAS should be told to use (its OPENBLAS_CORETYPE, read
// only when it is loaded): "SkylakeX" where the processor runs AVX-512 (F,
// CD, BW, DQ, VL), else "Haswell" where it runs AVX2 and FMA, when OpenBLAS
// picked kernels older than both. nullopt when the BLAS is not OpenBLAS,
// OPENBLAS_CORETYPE is set already (the user's choice, or deb's own after a
// restart), or OpenBLAS's choice stands.
std::optional<std::string> BetterBlasKernel();

// Whether the BLAS's matrix product beats Eigen's as deb compiles it: true
// for OpenBLAS's AVX-512 kernels (SkylakeX and later: dgemm of 2000 x 2000
// by 2000 x 128 at 59 GFlop/s, Eigen's AVX2 product 30), false otherwise
// (Haswell's: 30, as Eigen; Prescott's: 9.5). Decided once per process.
bool BlasProductIsFaster();
// One thread per call of OpenBLAS (openblas_set_num_threads(1); nothing for
// another BLAS). deb runs its own threads, across frequencies and paths, and
// calls the BLAS and LAPACK from each of them. With one thread per call,
// OpenBLAS's threaded build (which locks) runs calls from several threads
// at once, each on its core; its single-threaded build (which does not
// lock), and its threaded one at several threads per call, have the calls
// take turns (lapack.cpp, BlasTurn). The command line calls this at start;
// the Python module does not (numpy shares the library and its threads).
void UseOneBlasThreadPerCall();
// out = a * b through the BLAS's dgemm (column-major blocks of matrices, as
// Eigen keeps them). Calls from several threads take turns where the BLAS is
// not safe to call at once (UseOneBlasThreadPerCall); so do
// BlasUnitUpperSolve and the LAPACK calls above. @pre a.cols() == b.rows(), out is a.rows() x b.cols()
// (DEB_DEMAND), and the sizes fit the BLAS's int.
void BlasProduct(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b,
                 Eigen::Ref<Eigen::MatrixXd> out);
// x := Y^-1 x for the unit upper triangular part of Y (its diagonal and
// lower part are not read), through the BLAS's dtrsm. @pre Y square with
// as many rows as x (DEB_DEMAND), sizes that fit the BLAS's int.
void BlasUnitUpperSolve(const Eigen::Ref<const Eigen::MatrixXd>& y, Eigen::Ref<Eigen::MatrixXd> x);

}  // namespace deb
