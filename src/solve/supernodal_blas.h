// The dense BLAS/LAPACK kernels the supernodal factorizations run on their
// panels (internal; Fortran interface of OpenBLAS, column-major), with the
// empty cases skipped: the reference interface rejects some zero sizes.
#pragma once

extern "C" {
void dgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* ta, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

namespace intrinsic::detail::blas {

inline void gemm(char ta, char tb, int m, int n, int k, double alpha, const double* a, int lda, const double* b,
                 int ldb, double beta, double* c, int ldc) {
  if (m > 0 && n > 0 && k > 0) dgemm_(&ta, &tb, &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc);
}

// C := alpha A A^T + beta C on C's lower triangle (A is n x k).
inline void syrk_lower(int n, int k, double alpha, const double* a, int lda, double beta, double* c, int ldc) {
  const char uplo = 'L', trans = 'N';
  if (n > 0 && k > 0) dsyrk_(&uplo, &trans, &n, &k, &alpha, a, &lda, &beta, c, &ldc);
}

inline void trsm(char side, char uplo, char ta, char diag, int m, int n, const double* a, int lda, double* b,
                 int ldb) {
  const double one = 1;
  if (m > 0 && n > 0) dtrsm_(&side, &uplo, &ta, &diag, &m, &n, &one, a, &lda, b, &ldb);
}

// Cholesky of the lower triangle of the n x n block a; false when it is not
// positive definite.
inline bool potrf_lower(int n, double* a, int lda) {
  const char uplo = 'L';
  int info = 0;
  if (n > 0) dpotrf_(&uplo, &n, a, &lda, &info);
  return info == 0;
}

}  // namespace intrinsic::detail::blas

// Complex (std::complex<double>) kernels for the Hermitian factorization
// L L^H of the natural map's complex form (complex_form.h): the same calls
// with the adjoint ('C') where the real code transposes.
#include <complex>

extern "C" {
void zgemm_(const char* ta, const char* tb, const int* m, const int* n, const int* k,
            const std::complex<double>* alpha, const std::complex<double>* a, const int* lda,
            const std::complex<double>* b, const int* ldb, const std::complex<double>* beta,
            std::complex<double>* c, const int* ldc);
void zherk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha,
            const std::complex<double>* a, const int* lda, const double* beta, std::complex<double>* c,
            const int* ldc);
void ztrsm_(const char* side, const char* uplo, const char* ta, const char* diag, const int* m, const int* n,
            const std::complex<double>* alpha, const std::complex<double>* a, const int* lda,
            std::complex<double>* b, const int* ldb);
void zpotrf_(const char* uplo, const int* n, std::complex<double>* a, const int* lda, int* info);
}

namespace intrinsic::detail::blas {

inline void gemm(char ta, char tb, int m, int n, int k, std::complex<double> alpha, const std::complex<double>* a,
                 int lda, const std::complex<double>* b, int ldb, std::complex<double> beta,
                 std::complex<double>* c, int ldc) {
  if (m > 0 && n > 0 && k > 0) zgemm_(&ta, &tb, &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc);
}

// C := alpha A A^H + beta C on C's lower triangle (A is n x k; alpha, beta real).
inline void herk_lower(int n, int k, double alpha, const std::complex<double>* a, int lda, double beta,
                       std::complex<double>* c, int ldc) {
  const char uplo = 'L', trans = 'N';
  if (n > 0 && k > 0) zherk_(&uplo, &trans, &n, &k, &alpha, a, &lda, &beta, c, &ldc);
}

inline void trsm(char side, char uplo, char ta, char diag, int m, int n, const std::complex<double>* a, int lda,
                 std::complex<double>* b, int ldb) {
  const std::complex<double> one = 1;
  if (m > 0 && n > 0) ztrsm_(&side, &uplo, &ta, &diag, &m, &n, &one, a, &lda, b, &ldb);
}

// Hermitian Cholesky of the lower triangle of the n x n block a; false when
// it is not positive definite.
inline bool potrf_lower(int n, std::complex<double>* a, int lda) {
  const char uplo = 'L';
  int info = 0;
  if (n > 0) zpotrf_(&uplo, &n, a, &lda, &info);
  return info == 0;
}

}  // namespace intrinsic::detail::blas
