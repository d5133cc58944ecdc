// The singleton table's disk cache (core/volume/singletons.h, singleton_cache.cpp): a damaged or tampered entry —
// a flipped payload byte, a truncated file, an inflated header count, a forged CRC over implausible or wrong values
// — is never used: the table equals a fresh build bit for bit and the file is rewritten; the folder is kept under its
// limit by evicting the least recently used entries, other files untouched; limit 0 reads and writes nothing.
#include <gtest/gtest.h>

#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <functional>

#include "core/volume/analytic_volumes.h"
#include "core/volume/singletons.h"

namespace trispline::core {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kHead = 48;      // header bytes (singleton_cache.cpp CacheHead)
constexpr std::size_t kCrcOffset = 36;  // its CRC-32 field

std::vector<char> read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void write_file(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Recomputes the file's CRC-32 as the writer does (header with the field 0, then the payload): a forged entry.
void forge_crc(std::vector<char>& bytes) {
  std::memset(bytes.data() + kCrcOffset, 0, 4);
  const std::uint32_t crc = static_cast<std::uint32_t>(
      crc32_z(crc32_z(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
  std::memcpy(bytes.data() + kCrcOffset, &crc, 4);
}

void expect_same_table(const SingletonTable& a, const SingletonTable& b) {
  ASSERT_EQ(a.cell_count(), b.cell_count());
  EXPECT_EQ(std::memcmp(a.singletons().data(), b.singletons().data(), a.cell_count() * sizeof(Singleton)), 0);
  EXPECT_EQ(a.cells(), b.cells());
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.columns(), b.columns());
  EXPECT_EQ(a.range_min(), b.range_min());
  EXPECT_EQ(a.range_max(), b.range_max());
  EXPECT_EQ(a.memory_bytes(), b.memory_bytes());
  for (double iso : {-0.6, -0.1, 0.0, 0.25, 0.7}) {
    EXPECT_EQ(a.cells_holding(iso), b.cells_holding(iso)) << iso;
    EXPECT_EQ(a.cells_holding(iso, glm::dvec3(0, 0, 1), 0.1), b.cells_holding(iso, glm::dvec3(0, 0, 1), 0.1)) << iso;
  }
}

class SingletonCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("trispline_singleton_cache_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    setenv("TRISPLINE_CACHE_DIR", dir_.c_str(), 1);
    unsetenv("TRISPLINE_CACHE_MAX_MB");
  }
  void TearDown() override {
    unsetenv("TRISPLINE_CACHE_DIR");
    unsetenv("TRISPLINE_CACHE_MAX_MB");
    fs::remove_all(dir_);
  }
  // Cache entries in the folder (name → bytes).
  std::map<std::string, std::uintmax_t> entries() const {
    std::map<std::string, std::uintmax_t> out;
    if (!fs::exists(dir_)) return out;
    for (const auto& e : fs::directory_iterator(dir_)) out[e.path().filename().string()] = fs::file_size(e.path());
    return out;
  }
  fs::path entry_path(const VolumeSpline& s) const {
    char name[40];
    std::snprintf(name, sizeof(name), "%016llx.singletons", static_cast<unsigned long long>(singleton_cache_key(s)));
    return dir_ / name;
  }
  fs::path dir_;
};

TEST_F(SingletonCacheTest, TamperedEntriesAreRebuiltBitForBitAndRewritten) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 20);
  const VolumeSpline s(v, 4);
  const SingletonTable fresh = build_singleton_table(s);
  bool hit = true;
  expect_same_table(cached_singleton_table(s, {}, &hit), fresh);
  EXPECT_FALSE(hit);
  const fs::path path = entry_path(s);
  ASSERT_TRUE(fs::exists(path));
  const std::vector<char> good = read_file(path);
  EXPECT_EQ(good.size(), singleton_cache_file_bytes(fresh));
  expect_same_table(cached_singleton_table(s, {}, &hit), fresh);
  EXPECT_TRUE(hit);

  const std::uint64_t key = singleton_cache_key(s);
  const std::size_t payload = good.size() - kHead;
  const std::vector<std::pair<const char*, std::function<void(std::vector<char>&)>>> tampers = {
      {"flipped payload byte", [&](std::vector<char>& b) { b[kHead + payload / 2] ^= 0x10; }},
      {"flipped last byte", [](std::vector<char>& b) { b.back() ^= 0x01; }},
      {"flipped header byte", [](std::vector<char>& b) { b[20] ^= 0x01; }},  // cells[1]
      {"truncated", [](std::vector<char>& b) { b.resize(b.size() - 7); }},
      {"header only", [](std::vector<char>& b) { b.resize(kHead); }},
      {"inflated cell count",
       [](std::vector<char>& b) {
         const std::int32_t big = 1 << 30;
         std::memcpy(b.data() + 16, &big, 4);  // cells[0]
         const std::uint64_t count = std::uint64_t(big) * 19 * 19;
         std::memcpy(b.data() + 40, &count, 8);  // the singleton count agrees with it; the file size does not
         forge_crc(b);
       }},
      {"appended bytes", [](std::vector<char>& b) { b.insert(b.end(), 24, '\0'); }},
      {"forged CRC over a NaN",
       [](std::vector<char>& b) {
         const float nan = std::numeric_limits<float>::quiet_NaN();
         std::memcpy(b.data() + kHead + 24 * 100, &nan, 4);
         forge_crc(b);
       }},
      {"forged CRC over lo > hi",
       [](std::vector<char>& b) {
         const float lo = 5.0f;
         std::memcpy(b.data() + kHead + 24 * 200, &lo, 4);
         forge_crc(b);
       }},
      {"forged CRC over another range of cell 0",  // plausible values: caught by the rebuild of sampled cells
       [](std::vector<char>& b) {
         float hi;
         std::memcpy(&hi, b.data() + kHead + 4, 4);
         hi = std::nextafter(hi, INFINITY);
         std::memcpy(b.data() + kHead + 4, &hi, 4);
         forge_crc(b);
       }},
      {"forged CRC over other rows",
       [](std::vector<char>& b) {
         const std::int32_t rows = 300;
         std::memcpy(b.data() + 28, &rows, 4);
         forge_crc(b);
       }},
      {"other magic", [](std::vector<char>& b) { b[7] = '1'; }},
  };
  for (const auto& [what, tamper] : tampers) {
    SCOPED_TRACE(what);
    std::vector<char> bad = good;
    tamper(bad);
    write_file(path, bad);
    SingletonTable ignored;
    const bool structurally_valid = read_singleton_cache(path, key, ignored);
    // Only forged-CRC entries of plausible values pass the file checks; the cache's rebuild of sampled cells and
    // its shape checks catch them.
    if (structurally_valid) {
      EXPECT_TRUE(std::string(what).find("cell 0") != std::string::npos ||
                  std::string(what).find("rows") != std::string::npos);
    }
    hit = true;
    expect_same_table(cached_singleton_table(s, {}, &hit), fresh);
    EXPECT_FALSE(hit);
    EXPECT_EQ(read_file(path), good);  // the file is replaced by a fresh one
  }
}

TEST_F(SingletonCacheTest, HeaderCountsAreCheckedAgainstTheBudgetBeforeAllocating) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sphere, 12);
  const VolumeSpline s(v, 4);
  const SingletonTable t = build_singleton_table(s);
  const fs::path path = dir_ / "a.singletons";
  write_singleton_cache(t, path, 7);
  SingletonTable r;
  EXPECT_TRUE(read_singleton_cache(path, 7, r));
  EXPECT_FALSE(read_singleton_cache(path, 7, r, t.cell_count() * sizeof(Singleton)));  // over a budget this small
  EXPECT_FALSE(read_singleton_cache(path, 8, r));                                       // another key
  EXPECT_FALSE(read_singleton_cache(dir_ / "missing.singletons", 7, r));
}

TEST_F(SingletonCacheTest, EvictionKeepsTheFolderUnderItsLimitOldestFirst) {
  fs::create_directories(dir_);
  const auto now = fs::file_time_type::clock::now();
  auto make = [&](const std::string& name, std::size_t bytes, int age_s) {
    write_file(dir_ / name, std::vector<char>(bytes, 'x'));
    fs::last_write_time(dir_ / name, now - std::chrono::seconds(age_s));
  };
  make("00000000000000a1.singletons", 1000, 400);  // oldest
  make("00000000000000a2.singletons", 1000, 300);
  make("00000000000000a3.singletons.123.tmp", 500, 250);  // a crashed write's temporary
  make("00000000000000a4.singletons", 1000, 200);
  make("00000000000000a5.singletons", 1000, 100);  // newest
  make("notes.txt", 5000, 1000);                  // not the cache's: never touched
  make("abc.singletons", 5000, 1000);
  EXPECT_EQ(evict_singleton_cache(dir_, 1000000), 4500u);  // under the limit: nothing removed
  EXPECT_EQ(entries().size(), 7u);
  EXPECT_EQ(evict_singleton_cache(dir_, 2400), 2000u);  // a1, a2 and the temporary go
  const auto left = entries();
  EXPECT_EQ(left.size(), 4u);
  EXPECT_TRUE(left.count("00000000000000a4.singletons"));
  EXPECT_TRUE(left.count("00000000000000a5.singletons"));
  EXPECT_TRUE(left.count("notes.txt"));
  EXPECT_TRUE(left.count("abc.singletons"));
  EXPECT_EQ(evict_singleton_cache(dir_, 0), 0u);
  EXPECT_EQ(entries().size(), 2u);
}

TEST_F(SingletonCacheTest, LoadsEvictTheLeastRecentlyUsedEntry) {
  setenv("TRISPLINE_CACHE_MAX_MB", "1", 1);
  EXPECT_EQ(singleton_cache_limit_bytes(), 1u << 20);
  std::vector<VolumeSpline> splines;
  for (int i = 0; i < 4; ++i) {
    ScalarVolume v = make_analytic_volume(AnalyticVolume::sphere, 24);
    for (float& x : v.values) x += static_cast<float>(i);
    splines.emplace_back(v, 4);
  }
  const std::uint64_t entry = sizeof(Singleton) * 23 * 23 * 23 + 48;  // three fit in 1 MiB, four do not
  ASSERT_LE(3 * entry, 1u << 20);
  ASSERT_GT(4 * entry, 1u << 20);
  const auto now = fs::file_time_type::clock::now();
  for (int i = 0; i < 3; ++i) {
    cached_singleton_table(splines[i]);
    fs::last_write_time(entry_path(splines[i]), now - std::chrono::seconds(300 - 100 * i));  // 0 oldest, 2 newest
  }
  bool hit = false;
  cached_singleton_table(splines[0], {}, &hit);  // a hit makes 0 the most recently used
  EXPECT_TRUE(hit);
  cached_singleton_table(splines[3], {}, &hit);
  EXPECT_FALSE(hit);
  EXPECT_TRUE(fs::exists(entry_path(splines[0])));
  EXPECT_FALSE(fs::exists(entry_path(splines[1])));  // the least recently used
  EXPECT_TRUE(fs::exists(entry_path(splines[2])));
  EXPECT_TRUE(fs::exists(entry_path(splines[3])));
  std::uintmax_t total = 0;
  for (const auto& [name, bytes] : entries()) total += bytes;
  EXPECT_LE(total, 1u << 20);
}

TEST_F(SingletonCacheTest, LimitZeroReadsAndWritesNothing) {
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::torus, 16);
  const VolumeSpline s(v, 3);
  setenv("TRISPLINE_CACHE_MAX_MB", "0", 1);
  EXPECT_EQ(singleton_cache_limit_bytes(), 0u);
  bool hit = true;
  expect_same_table(cached_singleton_table(s, {}, &hit), build_singleton_table(s));
  EXPECT_FALSE(hit);
  EXPECT_TRUE(entries().empty());
  // A valid entry written while the cache was on is not read with the limit 0.
  unsetenv("TRISPLINE_CACHE_MAX_MB");
  cached_singleton_table(s, {}, &hit);
  EXPECT_EQ(entries().size(), 1u);
  setenv("TRISPLINE_CACHE_MAX_MB", "0", 1);
  cached_singleton_table(s, {}, &hit);
  EXPECT_FALSE(hit);
}

TEST_F(SingletonCacheTest, LimitFromTheEnvironment) {
  EXPECT_EQ(singleton_cache_limit_bytes(), kSingletonCacheDefaultMiB << 20);
  setenv("TRISPLINE_CACHE_MAX_MB", "64", 1);
  EXPECT_EQ(singleton_cache_limit_bytes(), 64u << 20);
  for (const char* bad : {"-1", "1e3", "12MB", " 5", "99999999999999999999"}) {
    setenv("TRISPLINE_CACHE_MAX_MB", bad, 1);
    EXPECT_EQ(singleton_cache_limit_bytes(), kSingletonCacheDefaultMiB << 20) << bad;
  }
}

TEST_F(SingletonCacheTest, AnEntryLargerThanTheLimitIsNotWritten) {
  setenv("TRISPLINE_CACHE_MAX_MB", "1", 1);
  const ScalarVolume v = make_analytic_volume(AnalyticVolume::sines, 40);  // 39³ × 24 bytes > 1 MiB
  const VolumeSpline s(v, 4);
  fs::create_directories(dir_);
  write_file(dir_ / "00000000000000b1.singletons", std::vector<char>(1000, 'x'));
  bool hit = true;
  cached_singleton_table(s, {}, &hit);
  EXPECT_FALSE(hit);
  EXPECT_FALSE(fs::exists(entry_path(s)));
  EXPECT_TRUE(fs::exists(dir_ / "00000000000000b1.singletons"));  // nothing evicted for an entry that cannot fit
}

}  // namespace
}  // namespace trispline::core
