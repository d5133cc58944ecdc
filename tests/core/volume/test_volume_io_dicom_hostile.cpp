// load_volume on hostile DICOM series the test writes itself (GDCM, or byte by byte with DicomBytes): entries that
// resolve outside the series folder, Pixel Data shorter than Rows × Columns, declared lengths larger than the file,
// unclosed or too deeply nested sequences, deflate bombs, pixel formats and geometry out of range. Every refusal is
// a VolumeLoadError naming the folder and the slice; the bombs are refused without their memory (peak RSS).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "core/volume/volume_io.h"
#include "tests/core/volume/volume_test_files.h"

namespace fs = std::filesystem;
using namespace trispline::core;
using namespace trispline::test;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using Syntax = DicomBytes::Syntax;

namespace {

std::vector<std::int16_t> ramp(int n, int k) {  // sample i of slice k = i + 100 k
  std::vector<std::int16_t> s;
  for (int i = 0; i < n; ++i) s.push_back(static_cast<std::int16_t>(i + 100 * k));
  return s;
}

// n byte-built 4×3 slices (z = 0, 1, ...) as <prefix><k>.dcm; `edit(k, header)` may change slice k's elements
// before its Pixel Data, `pixels(k)` its Pixel Data value.
void write_byte_series(const fs::path& dir, const std::string& prefix, int n, Syntax syntax = Syntax::kExplicitLittle,
                       const std::function<std::vector<unsigned char>(int)>& pixels = {},
                       const std::function<void(DicomBytes&)>& extra_in_slice_1 = {}) {
  const std::string uid = new_series_uid();
  for (int k = 0; k < n; ++k) {
    DicomBytes d = ct_slice_header(syntax, uid, k, 3, 4, 16, k == 1 ? extra_in_slice_1 : nullptr);
    d.element(0x7FE0, 0x0010, "OW", pixels ? pixels(k) : pixel_bytes(ramp(12, k), syntax == Syntax::kExplicitBig));
    write_bytes(dir / (prefix + std::to_string(k) + ".dcm"), d.file());
  }
}

}  // namespace

// The byte builder's files are real DICOM: GDCM reads all three syntaxes the walker walks.
TEST(DicomHostile, ByteBuiltSeriesLoadInEverySyntax) {
  for (const Syntax syntax : {Syntax::kExplicitLittle, Syntax::kImplicitLittle, Syntax::kExplicitBig}) {
    TempFolder dir;
    write_byte_series(dir.path(), "s", 3, syntax);
    const ScalarVolume v = load_volume(dir.path());
    ASSERT_EQ(v.dims, (std::array<int, 3>{4, 3, 3}));
    EXPECT_EQ(v.at(3, 2, 2), 11.0f + 200.0f);
  }
}

// ------------------------------------------------------------------------------------------------- containment

TEST(DicomHostile, EntryResolvingOutsideTheFolderIsRefused) {
  TempFolder dir;
  fs::create_directories(dir / "series");
  fs::create_directories(dir / "elsewhere");
  write_byte_series(dir / "series", "s", 3);
  write_byte_series(dir / "elsewhere", "x", 4);  // the same series UID is not needed: the file is never read
  fs::create_symlink("../elsewhere/x3.dcm", dir / "series" / "s3.dcm");
  const std::string why = volume_load_error(dir / "series");
  EXPECT_THAT(why, AllOf(HasSubstr("s3.dcm"), HasSubstr("outside the series folder")));
  // Opening one file of the folder loads its siblings: the same rule.
  EXPECT_THAT(volume_load_error(dir / "series" / "s0.dcm"), AllOf(HasSubstr("s3.dcm"), HasSubstr("outside")));
  // Through ".." in the link, and a link to a folder that leads out then back in elsewhere.
  fs::remove(dir / "series" / "s3.dcm");
  fs::create_symlink("../series/../elsewhere/x2.dcm", dir / "series" / "s3.dcm");
  EXPECT_THAT(volume_load_error(dir / "series"), AllOf(HasSubstr("s3.dcm"), HasSubstr("outside")));
  // An absolute link to a file outside.
  fs::remove(dir / "series" / "s3.dcm");
  fs::create_symlink(fs::absolute(dir / "elsewhere" / "x1.dcm"), dir / "series" / "s3.dcm");
  EXPECT_THAT(volume_load_error(dir / "series"), AllOf(HasSubstr("s3.dcm"), HasSubstr("outside")));
  // A link inside the folder is no escape: it is read (here, a duplicate position).
  fs::remove(dir / "series" / "s3.dcm");
  fs::create_symlink("s2.dcm", dir / "series" / "s3.dcm");
  EXPECT_THAT(volume_load_error(dir / "series"), HasSubstr("two slices at one position"));
  fs::remove(dir / "series" / "s3.dcm");
  EXPECT_EQ(load_volume(dir / "series").dims[2], 3);
}

// ---------------------------------------------------------------------------------------- short pixel data

TEST(DicomHostile, PixelDataShorterThanRowsTimesColumnsIsRefused) {
  for (const std::size_t bytes : {0u, 2u, 8u, 22u}) {
    TempFolder dir;
    write_byte_series(dir.path(), "s", 3, Syntax::kExplicitLittle, [&](int k) {
      std::vector<unsigned char> p = pixel_bytes(ramp(12, k));
      if (k == 2) p.resize(bytes);
      return p;
    });
    EXPECT_THAT(volume_load_error(dir.path()),
                AllOf(HasSubstr("s2.dcm"), HasSubstr("Pixel Data"), HasSubstr("the slice needs")))
        << bytes << " bytes";
  }
}

// --------------------------------------------------------------------------------------- element bounds

TEST(DicomHostile, DeclaredLengthBeyondTheFileIsRefusedWithoutItsMemory) {
  TempFolder dir;
  const std::uint64_t before = peak_rss_bytes();
  write_byte_series(dir.path(), "s", 3);
  DicomBytes d = ct_slice_header(Syntax::kExplicitLittle, new_series_uid(), 7.0);
  d.element(0x7FE0, 0x0010, "OW", pixel_bytes(ramp(12, 0)), 0xFFFFFFF0u);  // 4 GiB declared, 24 bytes there
  for (const std::string name : {"s1.dcm", "s9.dcm"}) {
    write_byte_series(dir.path(), "s", 3);
    write_bytes(dir / name, d.file());
    EXPECT_THAT(volume_load_error(dir.path()),
                AllOf(HasSubstr(name), HasSubstr("declares 4294967280 bytes"), HasSubstr("left of the file")));
  }
  // A value longer than the sequence item holding it.
  write_byte_series(dir.path(), "s", 3, Syntax::kExplicitLittle, {}, [](DicomBytes& e) {
    e.element(0x0008, 0x1140, "SQ", {}, 20).item_tag(0xE000, 12).text(0x0008, 0x1150, "UI", "1.2.3.4.5.6");
  });
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("past the end of its enclosing")));
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{200} << 20);
}

TEST(DicomHostile, UnclosedOrDeepSequencesAreRefused) {
  TempFolder dir;
  // An undefined-length sequence whose item is never closed: the file ends inside it.
  write_byte_series(dir.path(), "s", 3);
  DicomBytes open_sq(Syntax::kExplicitLittle);
  open_sq.text(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2")
      .element(0x0008, 0x1140, "SQ", {}, 0xFFFFFFFFu)
      .item_tag(0xE000, 0xFFFFFFFFu)
      .text(0x0008, 0x1150, "UI", "1.2.3");
  write_bytes(dir / "s1.dcm", open_sq.file());
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("undefined-length item")));
  // The same in implicit VR (where an undefined length always opens a sequence).
  DicomBytes open_implicit(Syntax::kImplicitLittle);
  open_implicit.text(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2").element(0x0008, 0x1140, "SQ", {}, 0xFFFFFFFFu);
  write_bytes(dir / "s1.dcm", open_implicit.file());
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("undefined-length sequence")));
  // 40 sequences within sequences, each closed: too deep.
  DicomBytes deep(Syntax::kExplicitLittle);
  deep.text(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");
  for (int i = 0; i < 40; ++i) deep.element(0x0008, 0x1140, "SQ", {}, 0xFFFFFFFFu).item_tag(0xE000, 0xFFFFFFFFu);
  for (int i = 0; i < 40; ++i) deep.item_tag(0xE00D, 0).item_tag(0xE0DD, 0);
  write_bytes(dir / "s1.dcm", deep.file());
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("nested more than 32")));
  // A delimiter that closes nothing.
  DicomBytes stray(Syntax::kExplicitLittle);
  stray.text(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2").item_tag(0xE0DD, 0);
  write_bytes(dir / "s1.dcm", stray.file());
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("closes nothing")));
}

// What GDCM 3.0 stops on with an assertion (found by fuzz_volume_dicom) is refused by the walk first: an unknown
// transfer syntax, an unknown VR in the meta header, a meta header whose elements overrun its group length, no data
// set after the meta header.
TEST(DicomHostile, MetaHeadersGdcmWouldAssertOnAreRefused) {
  TempFolder dir;
  write_byte_series(dir.path(), "s", 3);
  const DicomBytes slice = ct_slice_header(Syntax::kExplicitLittle, new_series_uid(), 9.0);
  write_bytes(dir / "s1.dcm", slice.file("1.2.84"));
  EXPECT_THAT(volume_load_error(dir.path()),
              AllOf(HasSubstr("s1.dcm"), HasSubstr("not a known DICOM transfer syntax")));
  const std::vector<unsigned char> none;
  write_bytes(dir / "s1.dcm", slice.file({}, &none));
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("no data set")));
  std::vector<unsigned char> bytes = slice.file();
  const std::string text(bytes.begin(), bytes.end());
  bytes[text.find("UI", 132)] = 'X';  // (0002,0002) "XI"
  write_bytes(dir / "s1.dcm", bytes);
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("no known value representation")));
  bytes = slice.file();
  bytes[132 + 8] += 2;  // the group length says 2 bytes more than the elements take
  write_bytes(dir / "s1.dcm", bytes);
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("group length")));
  // The inputs that stopped GDCM in the fuzzer, and one its parser (recovering from a damaged element the walk reads
  // otherwise) answered by allocating gigabytes: GDCM no longer parses files, so none costs memory.
  const fs::path regressions = fs::path(TRISPLINE_SOURCE_DIR) / "tests/fuzz/regressions/fuzz_volume_dicom";
  const std::uint64_t before = peak_rss_bytes();
  int n = 0;
  for (const auto& entry : fs::directory_iterator(regressions)) {
    TempFolder one;
    fs::copy_file(entry.path(), one / "input.dcm");
    EXPECT_THAT(volume_load_error(one / "input.dcm"), HasSubstr("input.dcm")) << entry.path();
    ++n;
  }
  EXPECT_EQ(n, 6);  // the RLE frame whose segment count GDCM trusted among them
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{100} << 20);
}

// ------------------------------------------------------------------------------------------- budgets, deflate

namespace {

// A deflated slice: the header elements (with, when private_zeros > 0, a private OB value of that many zeros after
// the modality), then Pixel Data of rows·cols int16 zeros; the data set deflated by streaming.
void write_deflated_slice(const fs::path& p, const std::string& uid, double z, int rows, int cols,
                          std::uint64_t private_zeros = 0) {
  const DicomBytes head = ct_slice_header(Syntax::kExplicitLittle, uid, z, rows, cols, 16, [&](DicomBytes& d) {
    if (private_zeros > 0) d.element(0x0009, 0x1010, "OB", {}, static_cast<std::uint32_t>(private_zeros));
  });
  const std::vector<unsigned char>& all = head.data_set();
  std::size_t split = all.size();  // where the private value's zeros go
  if (private_zeros > 0) split = std::string(all.begin(), all.end()).find(std::string("\x09\x00\x10\x10OB", 6)) + 12;
  std::vector<unsigned char> first(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(split));
  std::vector<unsigned char> rest(all.begin() + static_cast<std::ptrdiff_t>(split), all.end());
  DicomBytes pixel_header;
  const std::uint64_t pixel_zeros = static_cast<std::uint64_t>(rows) * static_cast<std::uint64_t>(cols) * 2;
  pixel_header.element(0x7FE0, 0x0010, "OW", {}, static_cast<std::uint32_t>(pixel_zeros));
  rest.insert(rest.end(), pixel_header.data_set().begin(), pixel_header.data_set().end());
  const std::vector<unsigned char> none;
  const std::vector<unsigned char> meta = DicomBytes().file("1.2.840.10008.1.2.1.99", &none);
  if (private_zeros == 0) {
    first.insert(first.end(), rest.begin(), rest.end());
    write_deflated(p, meta, first, pixel_zeros, false);
  } else {
    rest.resize(rest.size() + static_cast<std::size_t>(pixel_zeros));
    write_deflated(p, meta, first, private_zeros, false, rest);
  }
}

}  // namespace

TEST(DicomHostile, DeflatedSeriesIsBudgetedBeforeItIsInflated) {
  TempFolder dir;
  const std::string uid = new_series_uid();
  // Two 16384×16384 slices: 512 MiB of zeros each, about 0.5 MB deflated.
  for (int k = 0; k < 2; ++k) write_deflated_slice(dir / ("d" + std::to_string(k) + ".dcm"), uid, k, 16384, 16384);
  ASSERT_LT(fs::file_size(dir / "d0.dcm"), std::uintmax_t{2} << 20);
  const std::uint64_t before = peak_rss_bytes();
  VolumeLoadOptions options;
  options.extra_bytes_per_voxel = 24;
  const std::string why = volume_load_error(dir.path(), options);
  EXPECT_THAT(why, AllOf(HasSubstr("16384×16384×2"), HasSubstr("over the memory budget of 4.0 GiB"),
                         HasSubstr("24 bytes a voxel")));
  VolumeLoadOptions small;
  small.memory_budget_bytes = std::uint64_t{256} << 20;
  EXPECT_THAT(volume_load_error(dir / "d1.dcm", small), AllOf(HasSubstr("16384×16384×2"), HasSubstr("256.0 MiB")));
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{200} << 20) << "inflated before the budget refused";
}

TEST(DicomHostile, DeflatedDataSetInflatingPastItsBoundIsRefused) {
  TempFolder dir;
  const std::string uid = new_series_uid();
  // A 4×3 slice whose private element inflates to 40 MiB of zeros (before its Pixel Data).
  for (int k = 0; k < 2; ++k)
    write_deflated_slice(dir / ("d" + std::to_string(k) + ".dcm"), uid, k, 3, 4, std::uint64_t{40} << 20);
  const std::uint64_t before = peak_rss_bytes();
  VolumeLoadOptions options;
  options.memory_budget_bytes = std::uint64_t{16} << 20;
  EXPECT_THAT(volume_load_error(dir.path(), options),
              AllOf(HasSubstr("d0.dcm"), HasSubstr("inflates to more than 16.0 MiB")));
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{40} << 20);
  // Under a budget that holds it, the same series loads.
  options.memory_budget_bytes = std::uint64_t{512} << 20;
  EXPECT_EQ(load_volume(dir.path(), options).dims, (std::array<int, 3>{4, 3, 2}));
  // 100 MiB of other elements in a slice is refused whatever the budget.
  write_deflated_slice(dir / "d1.dcm", uid, 1, 3, 4, std::uint64_t{100} << 20);
  EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("d1.dcm"), HasSubstr("inflates to more than 64.0 MiB")));
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{100} << 20);
}

// ------------------------------------------------------------------------------------- pixel format, geometry

TEST(DicomHostile, BitsStoredZeroOrAboveBitsAllocatedIsRefused) {
  for (const int bits : {0, 17, 40}) {
    TempFolder dir;
    const std::string uid = new_series_uid();
    for (int k = 0; k < 3; ++k) {
      DicomBytes d = ct_slice_header(Syntax::kExplicitLittle, uid, k, 3, 4, k == 1 ? bits : 16);
      d.element(0x7FE0, 0x0010, "OW", pixel_bytes(ramp(12, k)));
      write_bytes(dir / ("s" + std::to_string(k) + ".dcm"), d.file());
    }
    EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s1.dcm"), HasSubstr("Bits Stored")));
  }
}

TEST(DicomHostile, AbsurdSpacingOrPositionIsRefused) {
  const DicomSlice base = [] {
    DicomSlice s;
    s.series_uid = new_series_uid();
    return s;
  }();
  for (const auto& [spacing, gap, field] :
       {std::tuple{1e300, 1.0, "Pixel Spacing"}, std::tuple{1.0, 5e8, "Image Position"},
        std::tuple{1e-9, 1.0, "Pixel Spacing"}}) {
    TempFolder dir;
    for (int k = 0; k < 3; ++k) {
      DicomSlice s = base;
      s.spacing_x = s.spacing_y = spacing;
      s.position = glm::dvec3(0, 0, gap * k);
      s.pixels = ramp(12, k);
      write_dicom_slice(dir / ("s" + std::to_string(k) + ".dcm"), s);
    }
    EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr(field), Not(HasSubstr("loaded"))))
        << spacing << " " << gap;
  }
}

// ------------------------------------------------------------------------------------------------- RLE frames

namespace {

// One RLE Lossless frame (PS3.5 Annex G) of 4×3 int16 samples: a 64-byte header (segment count, offsets), then
// segment 1 (the samples' high bytes) and segment 2 (their low bytes), each one literal run of 12 bytes.
std::vector<unsigned char> rle_frame(const std::vector<std::int16_t>& samples) {
  std::vector<unsigned char> high{11}, low{11};
  for (const std::int16_t v : samples) {
    high.push_back(static_cast<unsigned char>(static_cast<std::uint16_t>(v) >> 8));
    low.push_back(static_cast<unsigned char>(static_cast<std::uint16_t>(v) & 0xFF));
  }
  std::vector<unsigned char> frame(64, 0);
  const std::uint32_t header[3] = {2, 64, static_cast<std::uint32_t>(64 + high.size())};
  for (int i = 0; i < 3; ++i)
    for (int b = 0; b < 4; ++b)
      frame[static_cast<std::size_t>(4 * i + b)] = static_cast<unsigned char>(header[i] >> (8 * b));
  frame.insert(frame.end(), high.begin(), high.end());
  frame.insert(frame.end(), low.begin(), low.end());
  return frame;
}

// n 4×3 slices in RLE Lossless, slice k's frame given by `frame(k)`, as one fragment after an empty offset table.
void write_rle_series(const fs::path& dir, int n, const std::function<std::vector<unsigned char>(int)>& frame) {
  const std::string uid = new_series_uid();
  for (int k = 0; k < n; ++k) {
    DicomBytes d = ct_slice_header(Syntax::kExplicitLittle, uid, k, 3, 4, 16);
    std::vector<unsigned char> f = frame(k);
    if (f.size() % 2) f.push_back(0);
    d.element(0x7FE0, 0x0010, "OB", {}, 0xFFFFFFFFu).item_tag(0xE000, 0);
    d.item_tag(0xE000, static_cast<std::uint32_t>(f.size())).raw(f).item_tag(0xE0DD, 0);
    write_bytes(dir / ("s" + std::to_string(k) + ".dcm"), d.file("1.2.840.10008.1.2.5"));
  }
}

}  // namespace

// GDCM's RLE decoder trusts the frame's header and copies a short result as if whole: a segment count of 0 or above
// 15 crashed it (found by fuzz_volume_dicom). The frame is walked before GDCM sees it.
TEST(DicomHostile, RleFramesAreCheckedBeforeGdcmDecodesThem) {
  {
    TempFolder dir;
    write_rle_series(dir.path(), 3, [](int k) { return rle_frame(ramp(12, k)); });
    const ScalarVolume v = load_volume(dir.path());
    ASSERT_EQ(v.dims, (std::array<int, 3>{4, 3, 3}));
    EXPECT_EQ(v.at(3, 2, 2), 11.0f + 200.0f);
  }
  const std::vector<std::pair<std::function<void(std::vector<unsigned char>&)>, std::string>> cases{
      {[](auto& f) { f[0] = 0; }, "declares 0 segments, the pixel format needs 2"},
      {[](auto& f) { f[0] = 16; }, "declares 16 segments"},
      {[](auto& f) { f[8] = 200; }, "RLE segment 2 of 2 starts at byte 200 of a 90-byte frame"},
      {[](auto& f) { f[8] = 60; }, "RLE segment 2 of 2 starts at byte 60"},
      {[](auto& f) { f[4] = 66; }, "RLE segment 1 of 2 starts at byte 66"},
      {[](auto& f) { f[64] = 12; }, "RLE segment 1 of 2 decodes to only 0 bytes, not 12"},
      {[](auto& f) { f[64] = static_cast<unsigned char>(-12); }, "RLE segment 1 of 2 decodes to 13 bytes, not 12"},
      {[](auto& f) { f.resize(80); }, "RLE segment 2 of 2 decodes to only 0 bytes"},
      {[](auto& f) { f.resize(40); }, "an RLE frame of 40 bytes has no 64-byte header"},
  };
  for (const auto& c : cases) {
    TempFolder dir;
    write_rle_series(dir.path(), 3, [&](int k) {
      std::vector<unsigned char> f = rle_frame(ramp(12, k));
      if (k == 2) c.first(f);
      return f;
    });
    EXPECT_THAT(volume_load_error(dir.path()), AllOf(HasSubstr("s2.dcm"), HasSubstr(c.second))) << c.second;
  }
}
