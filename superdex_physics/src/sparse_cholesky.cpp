// CHOLMOD-backed sparse Cholesky (sparse_cholesky.h).

#include "sparse_cholesky.h"

#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <initializer_list>
#include <mutex>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct SparseCholesky::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  Eigen::SparseMatrix<double> H;  // double copy of the matrix being factored
};

namespace {

// A function of a library that CHOLMOD loaded: searched in the global scope, then in the library
// itself, which a Python extension module's dependencies are not part of (they are loaded with
// RTLD_LOCAL); null when absent.
void* library_function(std::initializer_list<const char*> libraries, const char* name) {
  if (void* fn = dlsym(RTLD_DEFAULT, name)) return fn;
  for (const char* library : libraries)
    if (void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD)) {
      void* fn = dlsym(handle, name);
      dlclose(handle);  // only drops the reference RTLD_NOLOAD took
      if (fn) return fn;
    }
  return nullptr;
}

// Our systems are small to medium and the engine runs islands in parallel itself: a threaded
// BLAS or OpenMP team behind CHOLMOD would spin its threads against ours (and against other
// scenes stepped on other threads), so both are made single-threaded.
// CHOLMOD's supernodal factorization opens its OpenMP regions with a team size fixed when it was
// built (num_threads(4), which OMP_NUM_THREADS and omp_set_num_threads do not override): waking
// and joining that team cost more than the factorization of a soft prop of 4k tetrahedra. No
// OpenMP region in the process may be active (max-active-levels 0, a process-wide setting), so
// every region runs on the thread that opens it.
void use_serial_blas() {
  static std::once_flag once;
  std::call_once(once, [] {
    using SetInt = void (*)(int);
    for (const char* name : {"openblas_set_num_threads", "goto_set_num_threads"})
      if (auto fn = reinterpret_cast<SetInt>(library_function({"libopenblas.so.0", "libblas.so.3"}, name))) fn(1);
    if (auto fn = reinterpret_cast<SetInt>(library_function({"libgomp.so.1", "libomp.so.5", "libomp.so"}, "omp_set_max_active_levels"))) fn(0);
  });
}

}  // namespace

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {
  // process-wide and once: every factorization is of a constructed object
  use_serial_blas();
  impl_->llt.cholmod().print = 0;  // failures are reported through factorize()
  // the fill-reducing ordering with the sparsest factor of AMD's and METIS's (CHOLMOD's default
  // tries METIS only when AMD's factor is very dense): nested dissection suits the 3-D meshes of
  // soft bodies, and the analysis runs once per pattern
  impl_->llt.cholmod().nmethods = 3;
}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<real>& H) {
  impl_->H = H.cast<double>();
  impl_->llt.analyzePattern(impl_->H);
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<real>& H) {
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
