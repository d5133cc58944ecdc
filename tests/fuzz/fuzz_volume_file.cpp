// libFuzzer target: one volume reader, the code that opens CT/MRI files from anywhere. The extension is fixed per
// target (TRISPLINE_FUZZ_EXT: ".nii", ".nii.gz", ".inv3", ".dcm"); the input is written to a file of that name in a
// folder of its own and loaded with load_volume under a 256 MiB memory budget (below libFuzzer's 2 GiB malloc limit,
// so a header claiming a large volume is refused by the budget, as a user's file over the default 4 GiB would be).
// The contract under test: a file loads whole — a volume that passes scalar_volume_error, with source set — or the
// reader throws VolumeLoadError. A lone .dcm is a series of one slice, which load_volume refuses after the element
// walk, GDCM's scan and the header checks; the slice is then also decoded on its own (load_dicom_slice, the path
// every slice of a series takes). Any other exception, a signal, a sanitizer finding or a volume that breaks the
// contract aborts, which libFuzzer reports as a crash.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/volume/volume_io.h"
#include "core/volume/volume_io_formats.h"
#include "tests/fuzz/fuzz_input_file.h"

#ifndef TRISPLINE_FUZZ_EXT
#error "define TRISPLINE_FUZZ_EXT, e.g. \".nii\""
#endif

using namespace trispline;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = fuzz::write_input_file("trispline_fuzz_volume", TRISPLINE_FUZZ_EXT, data, size);
  if (file.empty()) return 0;
  core::VolumeLoadOptions options;
  options.memory_budget_bytes = std::uint64_t{256} << 20;
  try {
    const core::ScalarVolume v = core::load_volume(file, options);
    const std::string why = core::scalar_volume_error(v);
    if (!why.empty() || v.source != file.string()) {
      std::fprintf(stderr, "load_volume returned a volume that breaks its contract: %s\n", why.c_str());
      std::abort();
    }
    if (v.voxel_count() * 4 > options.memory_budget_bytes) {
      std::fprintf(stderr, "load_volume returned %zu samples, over the memory budget\n", v.voxel_count());
      std::abort();
    }
  } catch (const core::VolumeLoadError&) {
  }
  if (std::string(TRISPLINE_FUZZ_EXT) == ".dcm") {
    try {
      const std::vector<float> slice = core::volume_io::load_dicom_slice(file, options);
      if (slice.empty() || slice.size() * 4 > options.memory_budget_bytes) {
        std::fprintf(stderr, "load_dicom_slice returned %zu samples\n", slice.size());
        std::abort();
      }
    } catch (const core::VolumeLoadError&) {
    }
  }
  return 0;
}
