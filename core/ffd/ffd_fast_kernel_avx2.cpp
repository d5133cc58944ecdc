// cpu_fast block kernels for x86-64-v3 (AVX2 + FMA, 8 floats per vector), compiled with -march=x86-64-v3 by
// core/ffd/CMakeLists.txt and chosen at run time (ffd_fast_dispatch.cpp). See ffd_fast_kernel_impl.h.
#include "core/ffd/ffd_fast_kernel.h"

#if defined(__AVX2__) && defined(__FMA__)
#define FFD_ISA_NAME "avx2"
#define FFD_ISA_NS avx2
#define FFD_W 8
#define FFD_TABLE_FN kernels_avx2
#include "core/ffd/ffd_fast_kernel_impl.h"
#else
const trispline::core::ffd_fast_detail::KernelTable* trispline::core::ffd_fast_detail::kernels_avx2() {
  return nullptr;
}
#endif
