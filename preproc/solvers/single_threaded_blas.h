// While an object of this class is in scope, a multithreaded OpenBLAS, if it is the BLAS in
// use, runs on one thread; other BLAS libraries are left alone (the symbols are looked up at
// run time). Two reasons:
//   * reproducibility: OpenBLAS's threaded factorisations (dpotrf, dsyrk inside CHOLMOD's
//     supernodal Cholesky) split their work by the thread count, so the last bits of the
//     factor, and through the eigen solver the signs and mixtures of degenerate modes,
//     changed with OPENBLAS_NUM_THREADS (measured on the rod: mode shapes differed by
//     their full size). The project parallelises its own loops in fixed-size pieces instead.
//   * speed: ARPACK applies the operator one vector at a time; CHOLMOD's single-RHS solves
//     are BLAS-2 calls too small to share between threads, and a multithreaded OpenBLAS
//     spent more time synchronising than computing (measured 3x slower on 2 cores).
#pragma once

namespace ffriga {

class SingleThreadedBlas {
 public:
  SingleThreadedBlas();
  ~SingleThreadedBlas();
  SingleThreadedBlas(const SingleThreadedBlas&) = delete;
  SingleThreadedBlas& operator=(const SingleThreadedBlas&) = delete;

 private:
  void (*set_)(int) = nullptr;
  int previous_ = 0;
};

}  // namespace ffriga
