// cpu_fast block kernels for the baseline instruction set (x86-64: SSE2, 4 floats per vector; others: whatever the
// target's default is). See ffd_fast_kernel_impl.h.
#if defined(__x86_64__) || defined(_M_X64)
#define FFD_ISA_NAME "sse"
#else
#define FFD_ISA_NAME "generic"
#endif
#define FFD_ISA_NS baseline
#define FFD_W 4
#define FFD_TABLE_FN kernels_baseline
#include "core/ffd/ffd_fast_kernel_impl.h"
