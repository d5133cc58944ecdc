// libFuzzer target: the singleton table's disk-cache reader (core/volume/singletons.h read_singleton_cache), the code
// that reads a file anyone with access to the cache folder may have written. The input is the cache file; its key is
// taken from the input's header (so the key check does not stop every input) and its CRC-32 is recomputed when the
// input holds a whole header (so mutations reach the count, budget and value checks and the filing of bins, not only
// the CRC). The reader runs under a 64 MiB budget. The contract: false, or a table whose every query answers cells
// that exist and hold the level (the bins are filed from the singletons, never read). Any other exception, a signal,
// a sanitizer finding or a broken answer aborts.
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/volume/singletons.h"
#include "tests/fuzz/fuzz_input_file.h"

using namespace trispline;

namespace {

constexpr std::size_t kHead = 48, kKeyOffset = 8, kCrcOffset = 36;

void check_query(const core::SingletonTable& t, double iso) {
  for (const std::uint32_t cell : t.cells_holding(iso)) {
    if (cell >= t.cell_count()) {
      std::fprintf(stderr, "cells_holding(%g) answered cell %u of %zu\n", iso, cell, t.cell_count());
      std::abort();
    }
    const core::Singleton& s = t.singletons()[cell];
    if (!(s.lo <= iso && iso <= s.hi)) {
      std::fprintf(stderr, "cells_holding(%g) answered cell %u of range [%g, %g]\n", iso, cell, s.lo, s.hi);
      std::abort();
    }
  }
  t.cells_holding(iso, glm::dvec3(0.0, 0.0, 1.0), 0.2, core::SingletonTable::CellOrder::by_bin);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  std::uint64_t key = 0;
  if (bytes.size() >= kHead) {
    std::memcpy(&key, bytes.data() + kKeyOffset, sizeof(key));
    std::memset(bytes.data() + kCrcOffset, 0, 4);
    const auto crc = static_cast<std::uint32_t>(crc32_z(crc32_z(0L, Z_NULL, 0), bytes.data(), bytes.size()));
    std::memcpy(bytes.data() + kCrcOffset, &crc, 4);
  }
  const std::filesystem::path file =
      fuzz::write_input_file("trispline_fuzz_singleton_cache", ".singletons", bytes.data(), bytes.size());
  if (file.empty()) return 0;
  core::SingletonTable table;
  if (!core::read_singleton_cache(file, key, table, std::uint64_t{64} << 20)) return 0;
  for (const double iso : {table.range_min(), 0.5 * (table.range_min() + table.range_max()), table.range_max()})
    check_query(table, iso);
  return 0;
}
