// A DICOM series through GDCM: gdcm::Scanner reads the header tags of every file of the folder (it stops before
// the pixel data), the series is chosen and its geometry checked here, then gdcm::ImageReader decodes one slice at
// a time. The slice order and spacing are checked here rather than by gdcm::IPPSorter, which only says yes or no:
// a refused series names the slices that disagree.
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmPixelFormat.h>
#include <gdcmReader.h>
#include <gdcmScanner.h>
#include <gdcmTag.h>
#include <gdcmTrace.h>
#include <gdcmUIDs.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

const gdcm::Tag kTransferSyntax(0x0002, 0x0010);
const gdcm::Tag kModality(0x0008, 0x0060);
const gdcm::Tag kSeriesDescription(0x0008, 0x103E);
const gdcm::Tag kSeriesUid(0x0020, 0x000E);
const gdcm::Tag kPosition(0x0020, 0x0032);
const gdcm::Tag kOrientation(0x0020, 0x0037);
const gdcm::Tag kSamplesPerPixel(0x0028, 0x0002);
const gdcm::Tag kPhotometric(0x0028, 0x0004);
const gdcm::Tag kFrames(0x0028, 0x0008);
const gdcm::Tag kRows(0x0028, 0x0010);
const gdcm::Tag kColumns(0x0028, 0x0011);
const gdcm::Tag kPixelSpacing(0x0028, 0x0030);
const gdcm::Tag kRescaleIntercept(0x0028, 0x1052);
const gdcm::Tag kRescaleSlope(0x0028, 0x1053);

// Enhanced (multi-frame IOD) images keep the geometry in functional group sequences, which are not read.
const char* const kNoOrientation =
    ": no readable Image Orientation (Patient) (0020,0037) in the data set (an enhanced image keeps it in "
    "functional groups: enhanced images are not read)";

// DICOM strings are padded with spaces (and sometimes NULs).
std::string trimmed(const char* s) {
  if (!s) return {};
  std::string t(s);
  const auto keep = [](char c) { return c != ' ' && c != '\0' && c != '\t' && c != '\r' && c != '\n'; };
  const auto b = std::find_if(t.begin(), t.end(), keep);
  const auto e = std::find_if(t.rbegin(), t.rend(), keep).base();
  return b < e ? std::string(b, e) : std::string();
}

// A DS/IS value with `count` components separated by '\'; false unless there are exactly that many finite numbers.
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

struct Slice {
  std::string file;  // full path
  std::string name;  // file name, for messages
  glm::dvec3 position{0.0};
  double distance = 0.0;  // position along the slice normal
  double slope = 1.0, intercept = 0.0;
};

// The folder's files (regular, not hidden), sorted by name.
std::vector<std::string> folder_files(const std::filesystem::path& folder) {
  std::vector<std::string> files;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code type_ec;
    if (it->is_regular_file(type_ec)) files.push_back(it->path().string());
  }
  if (ec) fail(folder, "cannot list the folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

// Whether the file ends before the `declared` bytes of its Pixel Data value. GDCM fills pixel data cut short by the
// end of the file with zeros and only warns; here GDCM parses the data set up to Pixel Data and skips its value, and
// where that value starts plus its length is compared with the file size. A deflated data set (its stream positions
// are not file offsets) is left to zlib.
bool pixel_data_cut_short(const std::string& file, std::uint64_t declared) {
  const gdcm::Tag pixel_data(0x7fe0, 0x0010);
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  try {
    if (!reader.ReadUpToTag(pixel_data, {pixel_data})) return true;
  } catch (const std::exception&) {
    return true;
  }
  if (reader.GetFile().GetHeader().GetDataSetTransferSyntax().IsEncoded()) return false;
  const std::size_t start = reader.GetStreamCurrentPosition();
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  return ec || start == static_cast<std::size_t>(-1) || start > size || size - start < declared;
}

// "transfer syntax 1.2.840.10008.1.2.4.94 (JPIP Referenced Transfer Syntax)", for messages.
std::string transfer_syntax(const char* uid_value) {
  const std::string uid = trimmed(uid_value);
  if (uid.empty()) return "transfer syntax not given";
  gdcm::UIDs known;
  const bool named = known.SetFromUID(uid.c_str()) && known.GetName();
  return "transfer syntax " + uid + (named ? std::string(" (") + known.GetName() + ")" : std::string());
}

std::string file_name(const std::string& file) { return std::filesystem::path(file).filename().string(); }

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

}  // namespace

ScalarVolume load_dicom(const std::filesystem::path& path, const VolumeLoadOptions& options) {
  gdcm::Trace::WarningOff();  // GDCM reports on std::cerr; what matters reaches the message below
  gdcm::Trace::ErrorOff();

  std::error_code ec;
  const bool is_folder = std::filesystem::is_directory(path, ec);
  const std::filesystem::path folder = is_folder ? path : path.parent_path().empty() ? "." : path.parent_path();
  std::vector<std::string> files = folder_files(folder);
  if (!is_folder) {  // the file itself, even if the listing skipped it (a hidden name)
    const auto same = [&](const std::string& f) { return std::filesystem::path(f).filename() == path.filename(); };
    if (std::none_of(files.begin(), files.end(), same)) files.push_back(path.string());
  }

  gdcm::Scanner scanner;
  for (const gdcm::Tag& t :
       {kTransferSyntax, kModality, kSeriesDescription, kSeriesUid, kPosition, kOrientation, kSamplesPerPixel,
        kPhotometric, kFrames, kRows, kColumns, kPixelSpacing, kRescaleIntercept, kRescaleSlope})
    scanner.AddTag(t);
  bool scanned = true;
  try {
    scanned = files.empty() || scanner.Scan(files);
  } catch (const std::exception& e) {
    fail(path, std::string("GDCM cannot scan the folder: ") + e.what());
  }
  if (!scanned) fail(path, "GDCM cannot scan the folder");
  const auto value = [&](const std::string& file, const gdcm::Tag& t) { return scanner.GetValue(file.c_str(), t); };

  // Images: DICOM files with a series, rows and columns (a DICOMDIR or a report has none).
  std::map<std::string, std::vector<std::string>> series;  // SeriesInstanceUID → files
  for (const std::string& f : files)
    if (scanner.IsKey(f.c_str()) && !trimmed(value(f, kSeriesUid)).empty() && value(f, kRows) && value(f, kColumns))
      series[trimmed(value(f, kSeriesUid))].push_back(f);

  std::vector<std::string> chosen;
  if (is_folder) {
    if (series.empty())
      fail(path, "no DICOM images in the folder (" + std::to_string(files.size()) + " files looked at)");
    if (series.size() > 1) {
      std::string list;
      for (const auto& [uid, members] : series) {
        const std::string& f = members.front();
        list += "\n  " + uid + " (" + trimmed(value(f, kModality)) + ", " + std::to_string(members.size()) +
                " images, \"" + trimmed(value(f, kSeriesDescription)) + "\", e.g. " + file_name(f) + ")";
      }
      fail(path,
           "the folder holds " + std::to_string(series.size()) +
               " DICOM series; open a file of the one wanted (it loads its series) or a folder of one series:" + list);
    }
    chosen = series.begin()->second;
  } else {
    const auto it = std::find_if(files.begin(), files.end(), [&](const std::string& f) {
      return std::filesystem::path(f).filename() == path.filename();
    });
    const std::string key = it != files.end() ? *it : std::string();
    if (key.empty() || !scanner.IsKey(key.c_str())) fail(path, "not a DICOM file GDCM can read");
    const std::string uid = trimmed(value(key, kSeriesUid));
    if (uid.empty() || !value(key, kRows) || !value(key, kColumns))
      fail(path, "not a DICOM image (no Series Instance UID, Rows or Columns)");
    chosen = series[uid];
  }

  // The geometry every slice must share, taken from the first.
  const std::string& first = chosen.front();
  double rows_cols[2];
  if (!parse_numbers(value(first, kRows), 1, &rows_cols[0]) || !parse_numbers(value(first, kColumns), 1, &rows_cols[1]))
    fail(path, file_name(first) + ": unreadable Rows / Columns");
  for (const double d : rows_cols)
    if (!(d >= 0.0 && d <= 65535.0)) fail(path, file_name(first) + ": Rows / Columns out of range");
  const std::string rows_text = trimmed(value(first, kRows)), cols_text = trimmed(value(first, kColumns));
  double iop[6], spacing[2];
  const std::string iop_text = trimmed(value(first, kOrientation));
  const std::string spacing_text = trimmed(value(first, kPixelSpacing));
  if (!parse_numbers(iop_text.c_str(), 6, iop)) fail(path, file_name(first) + kNoOrientation);
  if (!parse_numbers(spacing_text.c_str(), 2, spacing) || !(spacing[0] > 0.0) || !(spacing[1] > 0.0))
    fail(path, file_name(first) + ": no readable positive Pixel Spacing (0028,0030)");
  glm::dvec3 row_dir(iop[0], iop[1], iop[2]), col_dir(iop[3], iop[4], iop[5]);
  if (std::abs(glm::length(row_dir) - 1.0) > 1e-2 || std::abs(glm::length(col_dir) - 1.0) > 1e-2 ||
      std::abs(glm::dot(row_dir, col_dir)) > 1e-2)
    fail(path, file_name(first) + ": Image Orientation (Patient) " + iop_text + " is not two orthonormal directions");
  row_dir = glm::normalize(row_dir);
  col_dir = glm::normalize(col_dir);
  const glm::dvec3 normal = glm::normalize(glm::cross(row_dir, col_dir));

  std::vector<Slice> slices;
  std::uintmax_t largest_file = 0;
  for (const std::string& f : chosen) {
    const std::string name = file_name(f);
    double frames = 1.0;
    if (value(f, kFrames) && parse_numbers(value(f, kFrames), 1, &frames) && frames > 1.0)
      fail(path, name + ": a multi-frame image (" + trimmed(value(f, kFrames)) +
                     " frames): only series of single-frame slices are read");
    const std::string samples = trimmed(value(f, kSamplesPerPixel));
    const std::string photometric = trimmed(value(f, kPhotometric));
    if ((!samples.empty() && samples != "1") ||
        (!photometric.empty() && photometric != "MONOCHROME1" && photometric != "MONOCHROME2"))
      fail(path,
           name + ": a colour image (" + photometric + ", " + samples + " samples per pixel): grey levels expected");
    if (trimmed(value(f, kRows)) != rows_text || trimmed(value(f, kColumns)) != cols_text)
      fail(path, name + " is " + trimmed(value(f, kColumns)) + "×" + trimmed(value(f, kRows)) + " pixels, " +
                     file_name(first) + " " + cols_text + "×" + rows_text + ": one series, one slice size");
    double o[6], s[2];
    if (!parse_numbers(value(f, kOrientation), 6, o)) fail(path, name + kNoOrientation);
    for (int i = 0; i < 6; ++i)
      if (std::abs(o[i] - iop[i]) > 1e-4)
        fail(path, name + ": Image Orientation (Patient) " + trimmed(value(f, kOrientation)) + " differs from " +
                       file_name(first) + "'s " + iop_text);
    if (!parse_numbers(value(f, kPixelSpacing), 2, s) || std::abs(s[0] - spacing[0]) > 1e-4 * spacing[0] ||
        std::abs(s[1] - spacing[1]) > 1e-4 * spacing[1])
      fail(path, name + ": Pixel Spacing " + trimmed(value(f, kPixelSpacing)) + " differs from " + file_name(first) +
                     "'s " + spacing_text);
    Slice slice;
    slice.file = f;
    slice.name = name;
    double p[3];
    if (!parse_numbers(value(f, kPosition), 3, p))
      fail(path, name + ": no readable Image Position (Patient) (0020,0032)");
    slice.position = glm::dvec3(p[0], p[1], p[2]);
    if (glm::length(slice.position) > 1e9)
      fail(path, name + ": Image Position (Patient) " + trimmed(value(f, kPosition)) + " is farther than 1000 km");
    slice.distance = glm::dot(slice.position, normal);
    if (value(f, kRescaleSlope) && !parse_numbers(value(f, kRescaleSlope), 1, &slice.slope))
      fail(path, name + ": unreadable Rescale Slope " + trimmed(value(f, kRescaleSlope)));
    if (value(f, kRescaleIntercept) && !parse_numbers(value(f, kRescaleIntercept), 1, &slice.intercept))
      fail(path, name + ": unreadable Rescale Intercept " + trimmed(value(f, kRescaleIntercept)));
    std::error_code size_ec;
    const std::uintmax_t file_size = std::filesystem::file_size(f, size_ec);
    if (size_ec) fail(path, name + ": cannot read the file size: " + size_ec.message());
    largest_file = std::max(largest_file, file_size);
    slices.push_back(slice);
  }
  const int rows = static_cast<int>(rows_cols[0]), cols = static_cast<int>(rows_cols[1]);
  if (slices.size() < 2)
    fail(path, "the series " + trimmed(value(first, kSeriesUid)) + " has " + std::to_string(slices.size()) +
                   " slice: a volume needs at least 2");
  const std::uint64_t voxels =
      checked_voxel_count(path, {static_cast<std::int64_t>(rows_cols[1]), static_cast<std::int64_t>(rows_cols[0]),
                                 static_cast<std::int64_t>(slices.size())});
  check_budget(path, voxels, 2 * static_cast<std::uint64_t>(largest_file), options);

  // Order along the normal; the step between neighbours must be one vector (within 1 % of its length).
  std::sort(slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.distance < b.distance; });
  const std::size_t n = slices.size();
  const glm::dvec3 step = (slices.back().position - slices.front().position) / static_cast<double>(n - 1);
  const double mean_gap = (slices.back().distance - slices.front().distance) / static_cast<double>(n - 1);
  if (!(mean_gap > 0.0)) fail(path, "all " + std::to_string(n) + " slices are at one position along their normal");
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double gap = slices[k + 1].distance - slices[k].distance;
    if (gap < 0.01 * mean_gap)
      fail(path, "two slices at one position: " + slices[k].name + " and " + slices[k + 1].name + " (" +
                     format_number(gap) + " mm apart along the normal)");
  }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double gap = slices[k + 1].distance - slices[k].distance;
    const glm::dvec3 s = slices[k + 1].position - slices[k].position;
    if (glm::length(s - step) > 0.01 * glm::length(step))
      fail(path, "slice spacing is not uniform: " + format_number(gap) + " mm between " + slices[k].name + " and " +
                     slices[k + 1].name + ", " + format_number(mean_gap) +
                     " mm on average (more than 1 % apart: a missing slice?)");
  }

  ScalarVolume v;
  v.dims = {cols, rows, static_cast<int>(n)};
  v.index_to_world = glm::dmat4(1.0);
  v.index_to_world[0] = glm::dvec4(row_dir * spacing[1], 0.0);  // i: along a row, the column spacing
  v.index_to_world[1] = glm::dvec4(col_dir * spacing[0], 0.0);  // j: down a column, the row spacing
  v.index_to_world[2] = glm::dvec4(step, 0.0);
  v.index_to_world[3] = glm::dvec4(slices.front().position, 1.0);
  v.modality = trimmed(value(first, kModality));
  v.units = v.modality == "CT" ? "HU" : "";

  v.values.reserve(voxels);
  const std::size_t per_slice = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  std::vector<char> buffer;
  for (const Slice& slice : slices) {
    gdcm::ImageReader reader;
    reader.SetFileName(slice.file.c_str());
    bool read = false;
    try {
      read = reader.Read();
    } catch (const std::exception& e) {
      fail(path, slice.name + ": GDCM cannot read the image (" + transfer_syntax(value(slice.file, kTransferSyntax)) +
                     "): " + e.what());
    }
    if (!read)
      fail(path,
           slice.name + ": GDCM cannot read the image (" + transfer_syntax(value(slice.file, kTransferSyntax)) + ")");
    const gdcm::Image& image = reader.GetImage();
    const unsigned ndims = image.GetNumberOfDimensions();
    if (image.GetColumns() != static_cast<unsigned>(cols) || image.GetRows() != static_cast<unsigned>(rows) ||
        (ndims == 3 && image.GetDimension(2) != 1))
      fail(path, slice.name + ": the pixel data is not one " + cols_text + "×" + rows_text + " slice");
    const gdcm::PixelFormat& pf = image.GetPixelFormat();
    const int bits = pf.GetBitsAllocated();
    if (pf.GetSamplesPerPixel() != 1 || (bits != 8 && bits != 16 && bits != 32) || pf.GetBitsStored() == 0 ||
        pf.GetBitsStored() > bits || pf.GetPixelRepresentation() > 1)
      fail(path, slice.name + ": pixel format " + std::to_string(bits) + " bits allocated, " +
                     std::to_string(pf.GetBitsStored()) + " stored, " + std::to_string(pf.GetSamplesPerPixel()) +
                     " samples is not supported (grey integers of 8, 16 or 32 bits are)");
    const SampleDecoder decode{bits / 8, pf.GetPixelRepresentation() == 1, pf.GetBitsStored()};
    const std::size_t expected = per_slice * static_cast<std::size_t>(decode.bytes);
    if (const gdcm::ByteValue* stored = image.GetDataElement().GetByteValue())  // not encapsulated
      if (pixel_data_cut_short(slice.file, stored->GetLength()))
        fail(path, slice.name + ": truncated: the file ends inside its pixel data (" +
                       std::to_string(stored->GetLength()) + " bytes declared)");
    if (image.GetBufferLength() != expected)
      fail(path, slice.name + ": " + std::to_string(image.GetBufferLength()) + " bytes of pixel data, " +
                     std::to_string(expected) + " expected");
    buffer.resize(expected);
    bool decoded = false;
    try {
      decoded = image.GetBuffer(buffer.data());
    } catch (const std::exception&) {
    }
    if (!decoded)
      fail(path, slice.name + ": GDCM cannot decode its pixel data (" +
                     transfer_syntax(value(slice.file, kTransferSyntax)) + ")");
    for (std::size_t i = 0; i < per_slice; ++i)
      v.values.push_back(to_float(decode(buffer.data(), i) * slice.slope + slice.intercept));
  }
  return v;
}

}  // namespace trispline::core::volume_io
