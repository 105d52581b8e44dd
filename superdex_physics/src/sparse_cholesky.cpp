// CHOLMOD-backed sparse Cholesky (sparse_cholesky.h).

#include "sparse_cholesky.h"

#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <mutex>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct SparseCholesky::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  Eigen::SparseMatrix<double> H;  // double copy of the matrix being factored
};

namespace {

// Our systems are small to medium and the engine runs islands in parallel itself: a threaded
// BLAS or OpenMP team behind CHOLMOD would spin its threads against ours (and against other
// scenes stepped on other threads), so both are made single-threaded. OpenMP's thread count is
// a per-thread setting: it is made once in every thread that factors.
void use_serial_blas() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const char* name : {"openblas_set_num_threads", "goto_set_num_threads"})
      if (auto fn = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, name))) fn(1);
  });
  thread_local bool serial_openmp = false;
  if (!serial_openmp) {
    if (auto fn = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"))) fn(1);
    serial_openmp = true;
  }
}

}  // namespace

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {
  use_serial_blas();
  impl_->llt.cholmod().print = 0;  // failures are reported through factorize()
}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<real>& H) {
  use_serial_blas();
  impl_->H = H.cast<double>();
  impl_->llt.analyzePattern(impl_->H);
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<real>& H) {
  use_serial_blas();
  // the analysed structure: only the values change (no reallocation)
  if (impl_->H.nonZeros() == H.nonZeros() && impl_->H.rows() == H.rows() && H.isCompressed())
    Eigen::Map<Eigen::VectorXd>(impl_->H.valuePtr(), H.nonZeros()) =
        Eigen::Map<const VecX>(H.valuePtr(), H.nonZeros()).cast<double>();
  else
    impl_->H = H.cast<double>();
  impl_->llt.factorize(impl_->H);
  return impl_->llt.info() == Eigen::Success;
}

bool SparseCholesky::compute(const Eigen::SparseMatrix<real>& H) {
  analyze(H);
  return factorize(H);
}

VecX SparseCholesky::solve(const VecX& b) const {
  const Eigen::VectorXd x = impl_->llt.solve(b.cast<double>());
  return x.cast<real>();
}

MatX SparseCholesky::solve(const MatX& b) const {
  const Eigen::MatrixXd x = impl_->llt.solve(b.cast<double>());
  return x.cast<real>();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
