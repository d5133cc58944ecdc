// cpu_fast block kernels for x86-64-v4 (AVX-512 F/BW/DQ/VL/CD, 16 floats per vector), compiled with
// -march=x86-64-v4 by core/ffd/CMakeLists.txt and chosen at run time (ffd_fast_dispatch.cpp).
// See ffd_fast_kernel_impl.h.
#include "core/ffd/ffd_fast_kernel.h"

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__) && defined(__AVX512DQ__)
#define FFD_ISA_NAME "avx512"
#define FFD_ISA_NS avx512
#define FFD_W 16
#define FFD_TABLE_FN kernels_avx512
#include "core/ffd/ffd_fast_kernel_impl.h"
#else
const trispline::core::ffd_fast_detail::KernelTable* trispline::core::ffd_fast_detail::kernels_avx512() {
  return nullptr;
}
#endif
