#include "preproc/solvers/single_threaded_blas.h"

#include <dlfcn.h>

namespace ffriga {

SingleThreadedBlas::SingleThreadedBlas() {
  set_ = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  auto get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  if (set_ && get) {
    previous_ = get();
    set_(1);
  }
}

SingleThreadedBlas::~SingleThreadedBlas() {
  if (set_ && previous_ > 0) set_(previous_);
}

}  // namespace ffriga
