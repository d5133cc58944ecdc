// Private to load_dicom (volume_io_dicom.cpp): the only parser of a DICOM file's bytes. GDCM never parses a file: its
// parser allocates each value at its declared length before reading it, and where it reads a damaged structure
// differently from this walk (its recovery heuristics) a 500-byte file can make it allocate gigabytes. The walk keeps
// the header tags the reader needs and the Pixel Data; GDCM's codecs then decode fragments handed to them in memory.
//
//   walk_dicom_file  preamble + "DICM" (or none), the group 0002 meta header (explicit VR little endian), then the
//                    data set in its transfer syntax (implicit VR LE, explicit VR LE, explicit VR BE, or deflated
//                    explicit VR LE inflated on the fly), down through sequences and items.
//
// What is checked (PS3.5 §7): every defined value length fits in the bytes left in the file (or in the inflated data
// set) and in its enclosing item or sequence; every undefined-length sequence, item and encapsulated Pixel Data is
// closed by its delimiter before the end; nesting is at most kMaxDicomNesting deep and a file holds at most
// kMaxDicomElements elements; a deflated data set inflates to at most the given cap. Values are skipped, not read,
// except the transfer syntax UID.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace trispline::core::volume_io {

inline constexpr int kMaxDicomNesting = 32;                     // sequences within sequences (real files: < 8)
inline constexpr std::uint64_t kMaxDicomElements = 1u << 20;    // elements in one file, at every depth
inline constexpr std::uint64_t kMaxDicomMetaBytes = 64u << 10;  // the group 0002 meta header
// Bytes of a data set besides its Pixel Data value (a CT slice's header is a few KB; a vendor's private header
// rarely 1 MB): what a deflated data set may inflate to before its Pixel Data, and beyond the pixels' size in all.
inline constexpr std::uint64_t kMaxDicomHeaderBytes = 64ull << 20;

// The top-level Pixel Data (7FE0,0010) as stored, kept by a walk with DicomWalkLimits::keep_pixel_data.
struct DicomPixelData {
  bool found = false;                        // the data set has a top-level Pixel Data element
  bool encapsulated = false;                 // undefined length: a sequence of fragments (compressed transfer syntaxes)
  std::vector<char> value;                   // native: the value's bytes, in the transfer syntax's byte order
  std::vector<std::vector<char>> fragments;  // encapsulated: each item's bytes; the first is the Basic Offset Table
};

struct DicomWalk {
  std::string transfer_syntax;       // (0002,0010) trimmed; "" when the file has no meta header
  bool deflated = false;             // 1.2.840.10008.1.2.1.99: the data set after the meta header is deflated
  bool complete = false;             // the whole data set was walked (false: stopped at Pixel Data, see below)
  std::uint64_t data_set_bytes = 0;  // bytes of the data set as GDCM holds it: the file size, or the inflated size
  // Values of the top-level elements named in DicomWalkLimits::capture (at most 1 KiB each), as gdcm::Scanner gives
  // them: text as stored (DS, IS, CS, UI, ...), US as a decimal number. Key: group << 16 | element.
  std::map<std::uint32_t, std::string> values;
  DicomPixelData pixel_data;  // with DicomWalkLimits::keep_pixel_data only
};

struct DicomWalkLimits {
  std::uint64_t inflate_cap = 0;       // most bytes a deflated data set may inflate to (walked so far)
  bool stop_at_pixel_data = false;     // a deflated data set: stop at the top-level Pixel Data (7FE0,0010)
  std::vector<std::uint32_t> capture;  // top-level tags (group << 16 | element) whose values to keep
  // Keep the top-level Pixel Data's bytes (DicomWalk::pixel_data). They are read in 1 MiB steps as they arrive, so
  // what is held never exceeds what the file (or the inflated data set, within inflate_cap) really holds.
  bool keep_pixel_data = false;
};

// Walks `file`. Returns nullopt when it is not DICOM at all (no "DICM" at byte 128 and no element structure from
// byte 0: a text file, noise); throws VolumeLoadError "'<report>': <name>: at byte <offset> of the file, <what is
// wrong>: ..." when it is DICOM but an element does not fit. A plain (not deflated) data set is always walked whole.
std::optional<DicomWalk> walk_dicom_file(const std::filesystem::path& file, const DicomWalkLimits& limits,
                                         const std::filesystem::path& report, const std::string& name);

}  // namespace trispline::core::volume_io
