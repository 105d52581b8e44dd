// CHOLMOD-backed sparse Cholesky (sparse_cholesky.h).

#include "linalg/sparse_cholesky.h"

#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <mutex>
#include <utility>
#include <vector>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// CHOLMOD's supernodal Cholesky with access to its factor (the ordering it chose).
class SupernodalLlt : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
 public:
  const cholmod_factor* factor() const { return m_cholmodFactor; }
};

// The factorization is of S = P H P^T, kept as its lower triangle in the order CHOLMOD's
// analysis chose (fill-reducing, then postordered), and analysed again with the natural ordering:
// CHOLMOD then factors S as it is stored, where with its own ordering every factorization first
// built the permuted transpose of H (cholmod_transpose_sym, some 6 % of a soft step).
struct SparseCholesky::Impl {
  SupernodalLlt llt;
  Eigen::SparseMatrix<double> S;  // lower triangle of P H P^T
  std::vector<int> source;        // S.valuePtr()[k] = H.valuePtr()[source[k]]
  std::vector<int> perm;          // row k of S is row perm[k] of H
  Eigen::Index rows = -1, nonzeros = -1;  // H's analysed structure
  bool factored = false;          // llt holds the factor of S's values
  int factorizations = 0;         // numeric factorizations done
  std::vector<double> next;       // the values of the matrix being factored, in S's order
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
}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<real>& H) {
  Impl& m = *impl_;
  const int n = static_cast<int>(H.rows());
  Eigen::SparseMatrix<real> Hc = H;
  Hc.makeCompressed();
  // the fill-reducing ordering with the sparsest factor of AMD's and METIS's (CHOLMOD's default
  // tries METIS only when AMD's factor is very dense): nested dissection suits the 3-D meshes of
  // soft bodies, and the analysis runs once per pattern
  cholmod_common& c = m.llt.cholmod();
  c.nmethods = 3;
  c.method[0].ordering = CHOLMOD_GIVEN;  // CHOLMOD's default: AMD and METIS are methods 1 and 2
  c.postorder = 1;
  m.llt.analyzePattern(Hc.cast<double>());
  const cholmod_factor* L = m.llt.factor();
  m.perm.resize(n);
  const auto* P = static_cast<const int*>(L->Perm);
  for (int k = 0; k < n; ++k) m.perm[k] = P ? P[k] : k;
  // S = P H P^T, lower triangle, each column's rows ascending, with the source of each value
  std::vector<int> inverse(n);
  for (int k = 0; k < n; ++k) inverse[m.perm[k]] = k;
  std::vector<std::vector<std::pair<int, int>>> columns(n);  // per column of S: (row, index into H's values)
  for (int col = 0; col < n; ++col)
    for (int idx = Hc.outerIndexPtr()[col]; idx < Hc.outerIndexPtr()[col + 1]; ++idx) {
      const int i = inverse[Hc.innerIndexPtr()[idx]], j = inverse[col];
      if (i >= j) columns[j].emplace_back(i, idx);
    }
  m.S.resize(n, n);
  m.S.resizeNonZeros(0);
  m.source.clear();
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < n; ++j) {
    std::sort(columns[j].begin(), columns[j].end());
    for (const auto& [i, idx] : columns[j]) {
      entries.emplace_back(i, j, 0.0);
      m.source.push_back(idx);
    }
  }
  m.S.setFromTriplets(entries.begin(), entries.end());
  m.S.makeCompressed();
  // S is already in the chosen order: analysed as it is (no ordering, no postorder)
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_NATURAL;
  c.postorder = 0;
  m.llt.analyzePattern(m.S);
  m.factored = false;
  m.rows = n;
  m.nonzeros = Hc.nonZeros();
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<real>& H) {
  Impl& m = *impl_;
  if (!(H.isCompressed() && H.rows() == m.rows && H.nonZeros() == m.nonzeros)) analyze(H);
  // the analysed structure: only the values change (no reallocation)
  const real* values = H.valuePtr();
  m.next.resize(m.source.size());
  for (size_t k = 0; k < m.source.size(); ++k) m.next[k] = values[m.source[k]];
  // the same values, bit for bit, as the factor holds (a Newton iteration in which no element
  // Hessian and no contact changed): that factor is this matrix's
  const size_t bytes = m.next.size() * sizeof(double);
  if (m.factored && std::memcmp(m.next.data(), m.S.valuePtr(), bytes) == 0) return true;
  std::memcpy(m.S.valuePtr(), m.next.data(), bytes);
  m.llt.factorize(m.S);
  ++m.factorizations;
  m.factored = m.llt.info() == Eigen::Success;
  return m.factored;
}

int SparseCholesky::factorizations() const { return impl_->factorizations; }

bool SparseCholesky::compute(const Eigen::SparseMatrix<real>& H) {
  analyze(H);
  return factorize(H);
}

VecX SparseCholesky::solve(const VecX& b) const {
  Eigen::MatrixXd x = b.cast<double>();
  solve_in_place(x);
  return x.col(0).cast<real>();
}

MatX SparseCholesky::solve(const MatX& b) const {
  Eigen::MatrixXd x = b.cast<double>();
  solve_in_place(x);
  return x.cast<real>();
}

void SparseCholesky::solve_in_place(Eigen::MatrixXd& b) const {
  const Impl& m = *impl_;
  const int n = static_cast<int>(m.perm.size());
  // permuted column by column (b is column-major)
  Eigen::MatrixXd bp(n, b.cols());
  for (Eigen::Index j = 0; j < b.cols(); ++j)
    for (int k = 0; k < n; ++k) bp(k, j) = b(m.perm[k], j);
  const Eigen::MatrixXd xp = m.llt.solve(bp);
  for (Eigen::Index j = 0; j < b.cols(); ++j)
    for (int k = 0; k < n; ++k) b(m.perm[k], j) = xp(k, j);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
