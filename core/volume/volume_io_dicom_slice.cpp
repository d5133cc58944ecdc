// One DICOM slice: its header tags checked, its Pixel Data as the walk kept it decoded (native samples here, compressed
// fragments by GDCM's codecs into an image built from the checked header).
#include "core/volume/volume_io_dicom_slice.h"

#include <gdcmImage.h>
#include <gdcmPixelFormat.h>
#include <gdcmSequenceOfFragments.h>
#include <gdcmTrace.h>
#include <gdcmUIDs.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/volume/volume_io_dicom_walk.h"
#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

// Stored sample i of a decoded slice (GDCM hands it over in this machine's byte order) as its integer value: bits
// above Bits Stored dropped, sign-extended when signed.
struct SampleDecoder {
  int bytes = 2;
  bool is_signed = false;
  int bits_stored = 16;

  double operator()(const char* buffer, std::size_t i) const {
    const char* p = buffer + i * static_cast<std::size_t>(bytes);
    std::uint32_t raw = 0;
    if (bytes == 1) {
      raw = static_cast<unsigned char>(*p);
    } else if (bytes == 2) {
      std::uint16_t v;
      std::memcpy(&v, p, sizeof v);
      raw = v;
    } else {
      std::memcpy(&raw, p, sizeof raw);
    }
    const std::uint32_t mask = bits_stored >= 32 ? 0xFFFFFFFFu : ((1u << bits_stored) - 1u);
    raw &= mask;
    if (is_signed && bits_stored < 32 && ((raw >> (bits_stored - 1)) & 1u)) raw |= ~mask;
    return is_signed ? static_cast<double>(static_cast<std::int32_t>(raw)) : static_cast<double>(raw);
  }
};

// An IS value as an integer in [lo, hi]; false when absent, unreadable or outside.
bool parse_integer(const char* s, int lo, int hi, int* out) {
  double v = 0.0;
  if (!parse_numbers(s, 1, &v) || v != std::floor(v) || v < lo || v > hi) return false;
  *out = static_cast<int>(v);
  return true;
}

// Why an RLE Lossless frame (DICOM PS3.5 Annex G) cannot be decoded to `segment_count` segments of `segment_bytes`
// each, or "" when it can. GDCM's RLE decoder trusts the frame's 64-byte header (a segment count of 0 divides by
// zero, one above 15 reads past its offset table) and copies a short result as if it were whole, so the frame is
// walked here first, run by run as that decoder reads it: the count and offsets from the header, every segment
// decoding to exactly its bytes inside the frame.
std::string rle_frame_problem(const std::vector<char>& frame, std::size_t segment_count, std::size_t segment_bytes) {
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int b = 3; b >= 0; --b) v = v << 8 | static_cast<unsigned char>(frame[at + static_cast<std::size_t>(b)]);
    return v;
  };
  if (frame.size() < 64) return "an RLE frame of " + std::to_string(frame.size()) + " bytes has no 64-byte header";
  const std::uint32_t count = u32(0);
  if (count != segment_count)
    return "its RLE header declares " + std::to_string(count) + " segments, the pixel format needs " +
           std::to_string(segment_count);
  auto name = [&](std::size_t s) {
    return "RLE segment " + std::to_string(s + 1) + " of " + std::to_string(segment_count);
  };
  std::vector<std::size_t> starts(segment_count + 1, frame.size());  // segment s spans [starts[s], starts[s + 1])
  for (std::size_t s = 0; s < segment_count; ++s) {
    starts[s] = u32(4 + 4 * s);
    if (s == 0 ? starts[s] != 64 : starts[s] <= starts[s - 1] || starts[s] >= frame.size())
      return name(s) + " starts at byte " + std::to_string(starts[s]) + " of a " + std::to_string(frame.size()) +
             "-byte frame";
  }
  for (std::size_t s = 0; s < segment_count; ++s) {
    std::size_t at = starts[s], out = 0;
    const std::size_t end = starts[s + 1];
    while (out < segment_bytes) {
      if (at >= end) break;
      const int n = static_cast<signed char>(frame[at++]);
      std::size_t run = 0, read = 0;  // n ≥ 0: n + 1 literal bytes; -127..-1: 1 - n copies of one byte; -128: none
      if (n >= 0) {
        run = read = static_cast<std::size_t>(n) + 1;
      } else if (n != -128) {
        run = static_cast<std::size_t>(1 - n);
        read = 1;
      }
      if (read > end - at) break;
      at += read;
      out += run;
    }
    if (out != segment_bytes)
      return name(s) + " decodes to " + std::string(out < segment_bytes ? "only " : "") + std::to_string(out) +
             " bytes, not " + std::to_string(segment_bytes);
  }
  return "";
}

}  // namespace

namespace {

const gdcm::Tag* const kSliceTags[] = {
    &kTransferSyntax,   &kModality,        &kSeriesDescription, &kSeriesUid,  &kPosition,
    &kOrientation,      &kSamplesPerPixel, &kPhotometric,       &kFrames,     &kRows,
    &kColumns,          &kPixelSpacing,    &kBitsAllocated,     &kBitsStored, &kPixelRepresentation,
    &kRescaleIntercept, &kRescaleSlope};

}  // namespace

std::vector<std::uint32_t> slice_tag_keys() {
  std::vector<std::uint32_t> keys;
  for (const gdcm::Tag* t : kSliceTags) keys.push_back(std::uint32_t{t->GetGroup()} << 16 | t->GetElement());
  return keys;
}

const char* TagTable::get(const std::string& file, const gdcm::Tag& tag) const {
  const auto it = walked_.find(file);
  if (it == walked_.end()) return nullptr;
  const auto v = it->second.find(std::uint32_t{tag.GetGroup()} << 16 | tag.GetElement());
  return v == it->second.end() ? nullptr : v->second.c_str();
}

std::string trimmed(const char* s) {
  if (!s) return {};
  std::string t(s);
  const auto keep = [](char c) { return c != ' ' && c != '\0' && c != '\t' && c != '\r' && c != '\n'; };
  const auto b = std::find_if(t.begin(), t.end(), keep);
  const auto e = std::find_if(t.rbegin(), t.rend(), keep).base();
  return b < e ? std::string(b, e) : std::string();
}

bool parse_numbers(const char* s, std::size_t count, double* out) {
  const std::string text = trimmed(s);
  if (text.empty()) return false;
  std::size_t n = 0, start = 0;
  while (true) {
    const std::size_t end = std::min(text.find('\\', start), text.size());
    const std::string part = trimmed(text.substr(start, end - start).c_str());
    if (part.empty() || n == count) return false;
    char* stop = nullptr;
    const double value = std::strtod(part.c_str(), &stop);
    if (stop != part.c_str() + part.size() || !std::isfinite(value)) return false;
    out[n++] = value;
    if (end == text.size()) break;
    start = end + 1;
  }
  return n == count;
}

std::string transfer_syntax_text(const char* uid_value) {
  const std::string uid = trimmed(uid_value);
  if (uid.empty()) return "transfer syntax not given";
  gdcm::UIDs known;
  const bool named = known.SetFromUID(uid.c_str()) && known.GetName();
  return "transfer syntax " + uid + (named ? std::string(" (") + known.GetName() + ")" : std::string());
}

std::string file_name(const std::string& file) { return std::filesystem::path(file).filename().string(); }

SliceHeader read_slice_header(const TagTable& tags, const std::string& file, const std::filesystem::path& report) {
  const auto value = [&](const gdcm::Tag& t) { return tags.get(file, t); };
  SliceHeader h;
  h.file = file;
  h.name = file_name(file);
  h.transfer_syntax = transfer_syntax_text(value(kTransferSyntax));
  if (!parse_integer(value(kRows), 1, 65535, &h.rows) || !parse_integer(value(kColumns), 1, 65535, &h.columns))
    fail(report, h.name + ": Rows / Columns (" + trimmed(value(kRows)) + ", " + trimmed(value(kColumns)) +
                     ") are not whole numbers from 1 to 65535");
  double frames = 1.0;
  if (value(kFrames) && parse_numbers(value(kFrames), 1, &frames) && frames > 1.0)
    fail(report, h.name + ": a multi-frame image (" + trimmed(value(kFrames)) +
                     " frames): only series of single-frame slices are read");
  const std::string samples = trimmed(value(kSamplesPerPixel));
  const std::string photometric = trimmed(value(kPhotometric));
  if ((!samples.empty() && samples != "1") ||
      (!photometric.empty() && photometric != "MONOCHROME1" && photometric != "MONOCHROME2"))
    fail(report,
         h.name + ": a colour image (" + photometric + ", " + samples + " samples per pixel): grey levels expected");
  if (!parse_integer(value(kBitsAllocated), 8, 32, &h.bits_allocated) ||
      (h.bits_allocated != 8 && h.bits_allocated != 16 && h.bits_allocated != 32))
    fail(report,
         h.name + ": Bits Allocated (0028,0100) is '" + trimmed(value(kBitsAllocated)) + "': 8, 16 or 32 are read");
  if (!parse_integer(value(kBitsStored), 1, h.bits_allocated, &h.bits_stored))
    fail(report, h.name + ": Bits Stored (0028,0101) is '" + trimmed(value(kBitsStored)) +
                     "': from 1 to Bits Allocated (" + std::to_string(h.bits_allocated) + ") expected");
  int representation = 0;
  if (value(kPixelRepresentation) && !parse_integer(value(kPixelRepresentation), 0, 1, &representation))
    fail(report, h.name + ": Pixel Representation (0028,0103) is '" + trimmed(value(kPixelRepresentation)) +
                     "': 0 (unsigned) or 1 (signed) expected");
  h.is_signed = representation == 1;
  h.monochrome1 = photometric == "MONOCHROME1";
  if (value(kRescaleSlope) && !parse_numbers(value(kRescaleSlope), 1, &h.slope))
    fail(report, h.name + ": unreadable Rescale Slope " + trimmed(value(kRescaleSlope)));
  if (value(kRescaleIntercept) && !parse_numbers(value(kRescaleIntercept), 1, &h.intercept))
    fail(report, h.name + ": unreadable Rescale Intercept " + trimmed(value(kRescaleIntercept)));
  return h;
}

void decode_slice(const SliceHeader& slice, const DicomWalkLimits& limits, const std::filesystem::path& report,
                  std::vector<float>& values) {
  DicomWalkLimits keep = limits;
  keep.keep_pixel_data = true;
  keep.stop_at_pixel_data = false;
  keep.capture.clear();
  const std::optional<DicomWalk> walk = walk_dicom_file(slice.file, keep, report, slice.name);
  if (!walk) fail(report, slice.name + ": not a DICOM file");
  const DicomPixelData& pixels = walk->pixel_data;
  if (!pixels.found) fail(report, slice.name + ": no Pixel Data (7FE0,0010)");
  // No meta header: implicit VR little endian, as GDCM assumes.
  const std::string uid = walk->transfer_syntax.empty() ? "1.2.840.10008.1.2" : walk->transfer_syntax;
  const gdcm::TransferSyntax syntax = gdcm::TransferSyntax::GetTSType(uid.c_str());
  if (!syntax.IsValid()) fail(report, slice.name + ": unknown " + slice.transfer_syntax);
  if (syntax.IsEncapsulated() != pixels.encapsulated)
    fail(report, slice.name + ": Pixel Data (7FE0,0010) is " +
                     (syntax.IsEncapsulated() ? "not encapsulated" : "encapsulated") + " under its " +
                     slice.transfer_syntax);
  const std::string size_text = std::to_string(slice.columns) + "×" + std::to_string(slice.rows);
  const SampleDecoder decode{slice.bits_allocated / 8, slice.is_signed, slice.bits_stored};
  const std::size_t per_slice = static_cast<std::size_t>(slice.rows) * static_cast<std::size_t>(slice.columns);
  const std::size_t expected = per_slice * static_cast<std::size_t>(decode.bytes);
  std::vector<char> buffer;  // this slice's own: nothing of another slice can show through
  if (!pixels.encapsulated) {
    const std::size_t length = pixels.value.size();
    if (length < expected)
      fail(report, slice.name + ": Pixel Data (7FE0,0010) holds " + std::to_string(length) + " bytes, " +
                       std::to_string(length / static_cast<std::size_t>(decode.bytes)) + " samples of the " +
                       size_text + " = " + std::to_string(per_slice) + " the slice needs");
    buffer.assign(pixels.value.begin(), pixels.value.begin() + static_cast<std::ptrdiff_t>(expected));
    // Big-endian samples (explicit VR big endian; GE's private implicit syntax) into this machine's order.
    if (syntax.GetSwapCode() == gdcm::SwapCode::BigEndian ||
        syntax == gdcm::TransferSyntax::ImplicitVRBigEndianPrivateGE)
      for (std::size_t i = 0; i + decode.bytes <= buffer.size(); i += static_cast<std::size_t>(decode.bytes))
        std::reverse(buffer.begin() + static_cast<std::ptrdiff_t>(i),
                     buffer.begin() + static_cast<std::ptrdiff_t>(i) + decode.bytes);
  } else {
    // GDCM's codec decodes the fragments in memory into an image built from the checked header (its ImageReader
    // would interpret the header itself, and asserts on values a hostile file can hold).
    if (pixels.fragments.size() < 2)
      fail(report, slice.name + ": encapsulated Pixel Data (7FE0,0010) holds no fragment after its offset table");
    if (syntax == gdcm::TransferSyntax::RLELossless) {
      std::vector<char> frame;  // a 2-D image: GDCM decodes its fragments as one stream
      for (std::size_t k = 1; k < pixels.fragments.size(); ++k)
        frame.insert(frame.end(), pixels.fragments[k].begin(), pixels.fragments[k].end());
      const std::string problem = rle_frame_problem(frame, static_cast<std::size_t>(decode.bytes), per_slice);
      if (!problem.empty()) fail(report, slice.name + ": " + problem);
    }
    gdcm::SmartPointer<gdcm::SequenceOfFragments> fragments = new gdcm::SequenceOfFragments;
    const std::vector<char>& table = pixels.fragments.front();
    fragments->GetTable().SetByteValue(table.data(), static_cast<std::uint32_t>(table.size()));
    for (std::size_t k = 1; k < pixels.fragments.size(); ++k) {
      gdcm::Fragment fragment;
      fragment.SetByteValue(pixels.fragments[k].data(), static_cast<std::uint32_t>(pixels.fragments[k].size()));
      fragments->AddFragment(fragment);
    }
    gdcm::DataElement pixel_data(gdcm::Tag(0x7FE0, 0x0010));
    pixel_data.SetVR(gdcm::VR::OB);
    pixel_data.SetValue(*fragments);  // a sequence of fragments: undefined length
    gdcm::Image image;
    image.SetNumberOfDimensions(2);
    image.SetDimension(0, static_cast<unsigned>(slice.columns));
    image.SetDimension(1, static_cast<unsigned>(slice.rows));
    image.SetPixelFormat(gdcm::PixelFormat(
        1, static_cast<unsigned short>(slice.bits_allocated), static_cast<unsigned short>(slice.bits_stored),
        static_cast<unsigned short>(slice.bits_stored - 1), slice.is_signed ? 1 : 0));
    image.SetPhotometricInterpretation(slice.monochrome1 ? gdcm::PhotometricInterpretation::MONOCHROME1
                                                         : gdcm::PhotometricInterpretation::MONOCHROME2);
    image.SetTransferSyntax(syntax);
    image.SetDataElement(pixel_data);
    if (image.GetBufferLength() != expected)
      fail(report, slice.name + ": " + std::to_string(image.GetBufferLength()) + " bytes of pixel data, " +
                       std::to_string(expected) + " expected");
    buffer.resize(expected);
    bool decoded = false;
    try {
      decoded = image.GetBuffer(buffer.data());
    } catch (const std::exception&) {
    }
    if (!decoded) fail(report, slice.name + ": GDCM cannot decode its pixel data (" + slice.transfer_syntax + ")");
  }
  for (std::size_t i = 0; i < per_slice; ++i)
    values.push_back(to_float(decode(buffer.data(), i) * slice.slope + slice.intercept));
}

std::vector<float> load_dicom_slice(const std::filesystem::path& file, const VolumeLoadOptions& options) {
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
  const std::string name = file_name(file.string());
  DicomWalkLimits limits;
  limits.inflate_cap = std::min(options.memory_budget_bytes, kMaxDicomHeaderBytes);
  limits.stop_at_pixel_data = true;
  limits.capture = slice_tag_keys();
  const std::optional<DicomWalk> walk = walk_dicom_file(file, limits, file, name);
  if (!walk) fail(file, "not a DICOM file GDCM can read");
  TagTable tags;
  tags.add(file.string(), walk->values);
  if (!tags.has(file.string()) || !tags.get(file.string(), kRows)) fail(file, "not a DICOM image GDCM can read");
  const SliceHeader header = read_slice_header(tags, file.string(), file);
  const std::uint64_t voxels = std::uint64_t(header.rows) * std::uint64_t(header.columns);
  const std::array<std::int64_t, 3> dims{header.columns, header.rows, 1};
  check_budget(file, dims, voxels, walk->data_set_bytes + 2 * header.pixel_bytes(), options);
  // What decoding holds besides the floats: the Pixel Data as stored (no more than the data set) and the decoded
  // slice. A deflated data set's size is known only inflated: bounded by what the budget leaves and the pixels' size
  // plus kMaxDicomHeaderBytes.
  DicomWalkLimits data_limits;
  const std::uint64_t decode_bytes = 2 * header.pixel_bytes(), left = budget_left(voxels, options);
  data_limits.inflate_cap =
      std::min(left > decode_bytes ? left - decode_bytes : 0, header.pixel_bytes() + kMaxDicomHeaderBytes);
  std::vector<float> values;
  values.reserve(voxels);
  decode_slice(header, data_limits, file, values);
  return values;
}

}  // namespace trispline::core::volume_io
