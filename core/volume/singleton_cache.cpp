// The singleton table's on-disk cache (singletons.h): bounded (a size limit, least recently used evicted first, 0 =
// off) and verified (header counts against the file size and the memory budget before allocating, CRC-32 of the whole
// file through zlib, value checks, a rebuild of a sample of cells); a bad entry is rebuilt and replaced, never used.
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/volume/singletons.h"

namespace trispline::core {

std::uint64_t singleton_cache_key(const VolumeSpline& spline) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  const std::int32_t head[6] = {spline.dims()[0],
                                spline.dims()[1],
                                spline.dims()[2],
                                spline.order(),
                                spline.interpolating() ? 1 : 0,
                                2 /* bound_cell version */};
  mix(head, sizeof(head));
  mix(spline.control_points().data(), spline.control_points().size() * sizeof(float));
  return h;
}

std::filesystem::path singleton_cache_dir() {
  if (const char* d = std::getenv("TRISPLINE_CACHE_DIR"); d && *d) return std::filesystem::path(d);
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::filesystem::path(d) / "trispline" / "volumes";
  if (const char* d = std::getenv("HOME"); d && *d)
    return std::filesystem::path(d) / ".cache" / "trispline" / "volumes";
  return std::filesystem::temp_directory_path() / "trispline-cache" / "volumes";
}

std::uint64_t singleton_cache_limit_bytes() {
  constexpr std::uint64_t kMaxMiB = 1ull << 20;  // 1 TiB
  const char* v = std::getenv("TRISPLINE_CACHE_MAX_MB");
  if (!v || !*v || std::strlen(v) > 7) return kSingletonCacheDefaultMiB << 20;
  std::uint64_t mib = 0;
  for (const char* c = v; *c; ++c) {
    if (*c < '0' || *c > '9') return kSingletonCacheDefaultMiB << 20;
    mib = mib * 10 + static_cast<std::uint64_t>(*c - '0');
  }
  return mib > kMaxMiB ? kSingletonCacheDefaultMiB << 20 : mib << 20;
}

namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'T', 'S', 'P', 'L', 'S', 'N', 'G', '2'};
constexpr char kSuffix[] = ".singletons";

// The file's header: 48 bytes, no padding (host byte order: a cache is local to its machine).
struct CacheHead {
  char magic[8];
  std::uint64_t key;
  std::int32_t cells[3];
  std::int32_t rows, columns;
  std::uint32_t crc;  // CRC-32 (zlib) of the header with this field 0, then the singletons
  std::uint64_t singletons;
};
static_assert(sizeof(CacheHead) == 48, "the cache header has no padding");
static_assert(sizeof(Singleton) == 24, "a singleton is six floats");

std::uint32_t file_crc(CacheHead head, const Singleton* singletons, std::uint64_t count) {
  head.crc = 0;
  uLong crc = crc32_z(0L, Z_NULL, 0);
  crc = crc32_z(crc, reinterpret_cast<const Bytef*>(&head), sizeof(head));
  crc = crc32_z(crc, reinterpret_cast<const Bytef*>(singletons), static_cast<z_size_t>(count * sizeof(Singleton)));
  return static_cast<std::uint32_t>(crc);
}

bool is_hex16(const std::string& s) {
  return s.size() >= 16 && std::all_of(s.begin(), s.begin() + 16,
                                       [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// A cache entry "<16 hex>.singletons" or a write's temporary "<16 hex>.singletons.<pid>.tmp".
bool is_cache_file_name(const std::string& name) {
  if (!is_hex16(name) || name.compare(16, sizeof(kSuffix) - 1, kSuffix) != 0) return false;
  const std::string rest = name.substr(16 + sizeof(kSuffix) - 1);
  return rest.empty() || (rest.size() > 5 && rest.front() == '.' && rest.compare(rest.size() - 4, 4, ".tmp") == 0);
}

std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, bool& overflow) {
  std::uint64_t r = 0;
  overflow = overflow || __builtin_mul_overflow(a, b, &r);
  return r;
}

// Plausible values of a built singleton: finite, lo ≤ hi, the cone's sine in [0, 1], an axis of length 1 or 0.
bool plausible(const Singleton& s) {
  if (!std::isfinite(s.lo) || !std::isfinite(s.hi) || !(s.lo <= s.hi)) return false;
  if (!(s.sin_half >= 0.0f && s.sin_half <= 1.0f)) return false;
  const double len2 = double(s.axis[0]) * s.axis[0] + double(s.axis[1]) * s.axis[1] + double(s.axis[2]) * s.axis[2];
  return len2 == 0.0 || std::abs(len2 - 1.0) < 1e-4;
}

}  // namespace

std::uint64_t singleton_cache_file_bytes(const SingletonTable& table) {
  return sizeof(CacheHead) + table.cell_count() * sizeof(Singleton);
}

std::uint64_t evict_singleton_cache(const fs::path& dir, std::uint64_t limit_bytes) {
  struct Entry {
    fs::file_time_type used;
    std::string name;
    std::uint64_t bytes;
  };
  std::vector<Entry> entries;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code e;
    if (!is_cache_file_name(name) || !fs::is_regular_file(it->symlink_status(e))) continue;
    const std::uintmax_t bytes = fs::file_size(it->path(), e);
    if (e) continue;
    const fs::file_time_type used = fs::last_write_time(it->path(), e);
    entries.push_back({e ? fs::file_time_type::min() : used, name, bytes});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used != b.used ? a.used < b.used : a.name < b.name; });
  std::uint64_t total = 0;
  for (const Entry& e : entries) total += e.bytes;
  for (const Entry& e : entries) {
    if (total <= limit_bytes) break;
    std::error_code e2;
    if (fs::remove(dir / e.name, e2) && !e2) total -= e.bytes;
  }
  return total;
}

void write_singleton_cache(const SingletonTable& t, const fs::path& path, std::uint64_t key) {
  CacheHead h;
  std::memset(&h, 0, sizeof(h));
  std::memcpy(h.magic, kMagic, 8);
  h.key = key;
  for (int a = 0; a < 3; ++a) h.cells[a] = t.cells()[a];
  h.rows = t.rows();
  h.columns = t.columns();
  h.singletons = t.cell_count();
  h.crc = file_crc(h, t.singletons().data(), t.cell_count());
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  const fs::path tmp = path.string() + "." + std::to_string(::getpid()) + ".tmp";
  const auto fail = [&tmp]() {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write the singleton cache " + tmp.string());
  };
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) fail();
    f.write(reinterpret_cast<const char*>(&h), sizeof(h));
    f.write(reinterpret_cast<const char*>(t.singletons().data()),
            static_cast<std::streamsize>(t.cell_count() * sizeof(Singleton)));
    f.flush();
    if (!f) fail();
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) fail();
}

bool read_singleton_cache(const fs::path& path, std::uint64_t key, SingletonTable& out,
                          std::uint64_t memory_budget_bytes) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec))) return false;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size < sizeof(CacheHead)) return false;
  std::ifstream f(path, std::ios::binary);
  CacheHead h{};
  if (!f.read(reinterpret_cast<char*>(&h), sizeof(h)) || std::memcmp(h.magic, kMagic, 8) != 0 || h.key != key)
    return false;
  if (h.rows < 1 || h.rows > kSingletonTableMaxRows || h.columns < 1 || h.columns > kSingletonTableMaxColumns)
    return false;
  // Counts from the header, checked against the file size and the budget before anything is allocated.
  bool overflow = false;
  std::uint64_t cells = 1, macros = 1;
  for (int a = 0; a < 3; ++a) {
    if (h.cells[a] < 1) return false;
    const auto n = static_cast<std::uint64_t>(h.cells[a]);  // in 64 bits before the rounding up: INT32_MAX cells
    cells = checked_mul(cells, n, overflow);
    macros = checked_mul(macros, (n + SingletonTable::kMacro - 1) / SingletonTable::kMacro, overflow);
  }
  if (overflow || h.singletons != cells || cells >= std::numeric_limits<std::uint32_t>::max()) return false;
  if (size != sizeof(CacheHead) + cells * sizeof(Singleton)) return false;
  const std::uint64_t bins = static_cast<std::uint64_t>(h.rows) * static_cast<std::uint64_t>(h.columns);
  // Singletons, bin entries and the bin index while filing; bin arrays; macro-cell ranges.
  const std::uint64_t table_bytes = cells * (sizeof(Singleton) + 8) + bins * 16 + macros * sizeof(glm::vec2);
  if (table_bytes > memory_budget_bytes) return false;
  SingletonTable t;
  t.singletons_.resize(cells);
  if (!f.read(reinterpret_cast<char*>(t.singletons_.data()), static_cast<std::streamsize>(cells * sizeof(Singleton))))
    return false;
  if (file_crc(h, t.singletons_.data(), cells) != h.crc) return false;
  for (const Singleton& s : t.singletons_)
    if (!plausible(s)) return false;
  for (int a = 0; a < 3; ++a) t.cells_[a] = h.cells[a];
  t.rows_ = h.rows;
  t.set_columns(h.columns);
  t.file_bins();
  out = std::move(t);
  return true;
}

namespace {

// A rebuild of up to 512 cells spread over the table (and the last) equals the file's, bit for bit.
bool sample_matches(const SingletonTable& t, const VolumeSpline& spline) {
  const std::size_t n = t.cell_count();
  const std::size_t samples = std::min<std::size_t>(n, 512);
  const std::size_t nx = t.cells()[0], nxy = nx * t.cells()[1];
  for (std::size_t j = 0; j <= samples; ++j) {
    const std::size_t i = j == samples ? n - 1 : j * n / samples;
    const int a = static_cast<int>(i % nx), b = static_cast<int>((i / nx) % t.cells()[1]);
    const Singleton fresh = singleton_of_cell(spline, a, b, static_cast<int>(i / nxy));
    if (std::memcmp(&fresh, &t.singletons()[i], sizeof(Singleton)) != 0) return false;
  }
  return true;
}

}  // namespace

SingletonTable cached_singleton_table(const VolumeSpline& spline, const ProgressSink& progress, bool* from_cache) {
  if (from_cache) *from_cache = false;
  const std::uint64_t limit = singleton_cache_limit_bytes();
  if (limit == 0) return build_singleton_table(spline, progress);
  const std::uint64_t key = singleton_cache_key(spline);
  char name[40];
  std::snprintf(name, sizeof(name), "%016llx%s", static_cast<unsigned long long>(key), kSuffix);
  const fs::path dir = singleton_cache_dir(), path = dir / name;
  SingletonTable t;
  std::error_code ec;
  if (read_singleton_cache(path, key, t)) {
    const std::array<int, 3> cells{spline.span_count(0), spline.span_count(1), spline.span_count(2)};
    if (t.cells() == cells && t.rows() == kSingletonTableRows && t.columns() == kSingletonTableColumns &&
        sample_matches(t, spline)) {
      fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // recently used: evicted last
      if (from_cache) *from_cache = true;
      progress.check(1.0);
      return t;
    }
  }
  // Missing or bad: rebuild; a bad file is removed first, so it is never read again whatever the write does.
  if (fs::exists(fs::symlink_status(path, ec))) fs::remove(path, ec);
  t = build_singleton_table(spline, progress);
  const std::uint64_t bytes = singleton_cache_file_bytes(t);
  if (bytes > limit) return t;  // larger than the whole cache: not written
  try {
    evict_singleton_cache(dir, limit - bytes);
    write_singleton_cache(t, path, key);
  } catch (const std::exception&) {
    // The cache is an optimisation: a read-only or full disk only costs the next load its preprocessing.
  }
  return t;
}

}  // namespace trispline::core
