// Private to the DICOM reader (volume_io_dicom.cpp, volume_io_dicom_slice.cpp): one slice file's header tags as
// walk_dicom_file captured them, checked, and its Pixel Data decoded.
//
//   kSliceTags          the tags every file is scanned for
//   read_slice_header   Rows, Columns, Bits Allocated / Stored, Pixel Representation, colour, frames, rescale
//   decode_slice        one file's Pixel Data as the walk keeps it: native samples read here, compressed fragments
//                       decoded by GDCM's codecs into an image built from the checked header → rows·columns floats
//                       appended to a volume
#pragma once

#include <gdcmTag.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/volume/volume_io_dicom_walk.h"

namespace trispline::core::volume_io {

inline const gdcm::Tag kTransferSyntax(0x0002, 0x0010);
inline const gdcm::Tag kModality(0x0008, 0x0060);
inline const gdcm::Tag kSeriesDescription(0x0008, 0x103E);
inline const gdcm::Tag kSeriesUid(0x0020, 0x000E);
inline const gdcm::Tag kPosition(0x0020, 0x0032);
inline const gdcm::Tag kOrientation(0x0020, 0x0037);
inline const gdcm::Tag kSamplesPerPixel(0x0028, 0x0002);
inline const gdcm::Tag kPhotometric(0x0028, 0x0004);
inline const gdcm::Tag kFrames(0x0028, 0x0008);
inline const gdcm::Tag kRows(0x0028, 0x0010);
inline const gdcm::Tag kColumns(0x0028, 0x0011);
inline const gdcm::Tag kPixelSpacing(0x0028, 0x0030);
inline const gdcm::Tag kBitsAllocated(0x0028, 0x0100);
inline const gdcm::Tag kBitsStored(0x0028, 0x0101);
inline const gdcm::Tag kPixelRepresentation(0x0028, 0x0103);
inline const gdcm::Tag kRescaleIntercept(0x0028, 0x1052);
inline const gdcm::Tag kRescaleSlope(0x0028, 0x1053);

// Those tags as group << 16 | element, for walk_dicom_file's capture.
std::vector<std::uint32_t> slice_tag_keys();

// Header tag values of a folder's files, as walk_dicom_file captured them (text as stored, US as a decimal number).
class TagTable {
 public:
  void add(const std::string& file, std::map<std::uint32_t, std::string> values) { walked_[file] = std::move(values); }
  bool has(const std::string& file) const { return walked_.count(file) != 0; }
  // The value, or nullptr when the file does not have the tag.
  const char* get(const std::string& file, const gdcm::Tag& tag) const;

 private:
  std::map<std::string, std::map<std::uint32_t, std::string>> walked_;
};

// DICOM strings are padded with spaces (and sometimes NULs); nullptr → "".
std::string trimmed(const char* s);

// A DS/IS value with `count` components separated by '\'; false unless there are exactly that many finite numbers.
bool parse_numbers(const char* s, std::size_t count, double* out);

// "transfer syntax 1.2.840.10008.1.2.4.94 (JPIP Referenced Transfer Syntax)", for messages.
std::string transfer_syntax_text(const char* uid_value);

std::string file_name(const std::string& file);

struct SliceHeader {
  std::string file, name;     // full path, file name (messages)
  int rows = 0, columns = 0;  // 1…65535
  int bits_allocated = 16, bits_stored = 16;
  bool is_signed = false;               // Pixel Representation 1
  bool monochrome1 = false;             // Photometric Interpretation MONOCHROME1 (else MONOCHROME2 or absent)
  double slope = 1.0, intercept = 0.0;  // Rescale Slope / Intercept (1, 0 when absent)
  std::string transfer_syntax;          // for messages

  std::uint64_t pixel_bytes() const {  // rows · columns · bits_allocated / 8: one decoded slice
    return std::uint64_t(rows) * std::uint64_t(columns) * std::uint64_t(bits_allocated / 8);
  }
};

// The header of `file` from the table; fails (naming the file) on unreadable or out-of-range Rows / Columns, Bits
// Allocated other than 8, 16, 32, Bits Stored 0 or above Bits Allocated, Pixel Representation other than 0 / 1,
// multi-frame or colour images, unreadable rescale values. `report` is the path messages start with.
SliceHeader read_slice_header(const TagTable& tags, const std::string& file, const std::filesystem::path& report);

// Decodes `slice` (its header as checked above) and appends rows·columns floats (stored value, bits above Bits
// Stored dropped, sign-extended, × slope + intercept) to `values`. The file is walked again keeping its Pixel Data
// (`limits.inflate_cap` bounds a deflated data set); compressed fragments go to GDCM's codecs in an image built from
// `slice`. Refused (VolumeLoadError naming the slice): a broken structure, no Pixel Data, encapsulated Pixel Data
// under a native transfer syntax or the reverse, native Pixel Data holding fewer bytes than rows·columns samples,
// fragments GDCM cannot decode or that decode to another size than the header's. Each slice is decoded into a buffer
// of its own.
void decode_slice(const SliceHeader& slice, const DicomWalkLimits& limits, const std::filesystem::path& report,
                  std::vector<float>& values);

}  // namespace trispline::core::volume_io
