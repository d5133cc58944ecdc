// A DICOM series. Every file of the folder must resolve inside the folder; each is walked (walk_dicom_file, the only
// parser of the files' bytes: element lengths and nesting against the file, the header tags kept; a deflated file up
// to its Pixel Data); the series is chosen, its geometry and the memory budget checked on the header values; then one
// slice at a time is walked again keeping its Pixel Data and decoded (decode_slice: native samples directly,
// compressed fragments by GDCM's codecs in an image built from the checked header). The slice order and spacing are
// checked here rather than by gdcm::IPPSorter, which only says yes or no: a refused series names the slices that
// disagree.
#include <gdcmTrace.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/volume/volume_io_dicom_slice.h"
#include "core/volume/volume_io_dicom_walk.h"
#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

// Enhanced (multi-frame IOD) images keep the geometry in functional group sequences, which are not read.
const char* const kNoOrientation =
    ": no readable Image Orientation (Patient) (0020,0037) in the data set (an enhanced image keeps it in "
    "functional groups: enhanced images are not read)";

struct Slice {
  SliceHeader header;
  glm::dvec3 position{0.0};
  double distance = 0.0;  // position along the slice normal
};

// Whether `inner` (canonical) is `root` (canonical) or below it.
bool is_inside(const std::filesystem::path& inner, const std::filesystem::path& root) {
  const std::filesystem::path rel = inner.lexically_relative(root);
  return !rel.empty() && *rel.begin() != "..";
}

// The folder's files (regular, not hidden), sorted by name, plus `also` (the opened file, even if hidden). Each must
// resolve (symlinks, "..") inside the folder, else the load is refused naming the entry: a series is read from its
// own folder only.
std::vector<std::string> folder_files(const std::filesystem::path& folder, const std::filesystem::path& also,
                                      const std::filesystem::path& report) {
  std::error_code ec;
  const std::filesystem::path root = std::filesystem::canonical(folder, ec);
  if (ec) fail(report, "cannot resolve the folder: " + ec.message());
  std::vector<std::string> files;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code type_ec;
    if (name.empty() || name[0] == '.' || !it->is_regular_file(type_ec)) continue;
    files.push_back(it->path().string());
  }
  if (ec) fail(report, "cannot list the folder: " + ec.message());
  if (!also.empty() &&
      std::none_of(files.begin(), files.end(), [&](const std::string& f) { return f == also.string(); }))
    files.push_back(also.string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) {
    std::error_code real_ec;
    const std::filesystem::path real = std::filesystem::canonical(f, real_ec);
    if (real_ec) fail(report, file_name(f) + ": cannot resolve the entry: " + real_ec.message());
    if (!is_inside(real, root))
      fail(report, file_name(f) + " resolves to " + quoted(real) + ", outside the series folder " + quoted(root) +
                       ": a series is read from its own folder only (a symlink or '..' leading out is refused)");
  }
  return files;
}

// The geometry every slice must share, from the first; each slice's position. Fails naming the slice that differs.
struct SeriesGeometry {
  glm::dvec3 row_dir{1, 0, 0}, col_dir{0, 1, 0}, normal{0, 0, 1};
  double spacing[2] = {1.0, 1.0};  // Pixel Spacing: between rows, between columns
};

SeriesGeometry series_geometry(const TagTable& tags, const std::vector<std::string>& chosen,
                               const std::filesystem::path& path, std::vector<Slice>& slices) {
  const auto value = [&](const std::string& file, const gdcm::Tag& t) { return tags.get(file, t); };
  const std::string& first = chosen.front();
  SeriesGeometry g;
  double iop[6];
  const std::string iop_text = trimmed(value(first, kOrientation));
  const std::string spacing_text = trimmed(value(first, kPixelSpacing));
  if (!parse_numbers(iop_text.c_str(), 6, iop)) fail(path, file_name(first) + kNoOrientation);
  if (!parse_numbers(spacing_text.c_str(), 2, g.spacing) || !(g.spacing[0] > 0.0) || !(g.spacing[1] > 0.0))
    fail(path, file_name(first) + ": no readable positive Pixel Spacing (0028,0030)");
  g.row_dir = glm::dvec3(iop[0], iop[1], iop[2]);
  g.col_dir = glm::dvec3(iop[3], iop[4], iop[5]);
  if (std::abs(glm::length(g.row_dir) - 1.0) > 1e-2 || std::abs(glm::length(g.col_dir) - 1.0) > 1e-2 ||
      std::abs(glm::dot(g.row_dir, g.col_dir)) > 1e-2)
    fail(path, file_name(first) + ": Image Orientation (Patient) " + iop_text + " is not two orthonormal directions");
  g.row_dir = glm::normalize(g.row_dir);
  g.col_dir = glm::normalize(g.col_dir);
  g.normal = glm::normalize(glm::cross(g.row_dir, g.col_dir));

  const SliceHeader first_header = read_slice_header(tags, first, path);
  const std::string first_size = std::to_string(first_header.columns) + "×" + std::to_string(first_header.rows);
  for (const std::string& f : chosen) {
    Slice slice;
    slice.header = read_slice_header(tags, f, path);
    const SliceHeader& h = slice.header;
    if (h.rows != first_header.rows || h.columns != first_header.columns)
      fail(path, h.name + " is " + std::to_string(h.columns) + "×" + std::to_string(h.rows) + " pixels, " +
                     first_header.name + " " + first_size + ": one series, one slice size");
    if (h.bits_allocated != first_header.bits_allocated)
      fail(path, h.name + " has " + std::to_string(h.bits_allocated) + " bits allocated, " + first_header.name + " " +
                     std::to_string(first_header.bits_allocated) + ": one series, one pixel format");
    double o[6], s[2];
    if (!parse_numbers(value(f, kOrientation), 6, o)) fail(path, h.name + kNoOrientation);
    for (int i = 0; i < 6; ++i)
      if (std::abs(o[i] - iop[i]) > 1e-4)
        fail(path, h.name + ": Image Orientation (Patient) " + trimmed(value(f, kOrientation)) + " differs from " +
                       file_name(first) + "'s " + iop_text);
    if (!parse_numbers(value(f, kPixelSpacing), 2, s) || std::abs(s[0] - g.spacing[0]) > 1e-4 * g.spacing[0] ||
        std::abs(s[1] - g.spacing[1]) > 1e-4 * g.spacing[1])
      fail(path, h.name + ": Pixel Spacing " + trimmed(value(f, kPixelSpacing)) + " differs from " + file_name(first) +
                     "'s " + spacing_text);
    double p[3];
    if (!parse_numbers(value(f, kPosition), 3, p))
      fail(path, h.name + ": no readable Image Position (Patient) (0020,0032)");
    slice.position = glm::dvec3(p[0], p[1], p[2]);
    if (!(glm::length(slice.position) <= kMaxVolumeWorldMillimetres))
      fail(path, h.name + ": Image Position (Patient) " + trimmed(value(f, kPosition)) + " is farther than 1000 km");
    slice.distance = glm::dot(slice.position, g.normal);
    slices.push_back(slice);
  }
  return g;
}

// Sorts the slices along the normal and returns the step between neighbours, which must be one vector (within 1 %
// of its length).
glm::dvec3 slice_step(std::vector<Slice>& slices, const std::filesystem::path& path) {
  std::sort(slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.distance < b.distance; });
  const std::size_t n = slices.size();
  const glm::dvec3 step = (slices.back().position - slices.front().position) / static_cast<double>(n - 1);
  const double mean_gap = (slices.back().distance - slices.front().distance) / static_cast<double>(n - 1);
  if (!(mean_gap > 0.0)) fail(path, "all " + std::to_string(n) + " slices are at one position along their normal");
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double gap = slices[k + 1].distance - slices[k].distance;
    if (gap < 0.01 * mean_gap)
      fail(path, "two slices at one position: " + slices[k].header.name + " and " + slices[k + 1].header.name + " (" +
                     format_number(gap) + " mm apart along the normal)");
  }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double gap = slices[k + 1].distance - slices[k].distance;
    const glm::dvec3 s = slices[k + 1].position - slices[k].position;
    if (glm::length(s - step) > 0.01 * glm::length(step))
      fail(path, "slice spacing is not uniform: " + format_number(gap) + " mm between " + slices[k].header.name +
                     " and " + slices[k + 1].header.name + ", " + format_number(mean_gap) +
                     " mm on average (more than 1 % apart: a missing slice?)");
  }
  return step;
}

// The files of the series `path` names: a folder's only series, or the series of `opened` (a .dcm file of the
// folder; empty for a folder).
std::vector<std::string> choose_series(const TagTable& tags, const std::vector<std::string>& files,
                                       const std::vector<std::string>& dicom_files, const std::filesystem::path& path,
                                       const std::filesystem::path& opened) {
  const bool is_folder = opened.empty();
  const auto value = [&](const std::string& file, const gdcm::Tag& t) { return tags.get(file, t); };
  // Images: DICOM files with a series, rows and columns (a DICOMDIR or a report has none).
  std::map<std::string, std::vector<std::string>> series;  // SeriesInstanceUID → files
  for (const std::string& f : dicom_files)
    if (tags.has(f) && !trimmed(value(f, kSeriesUid)).empty() && value(f, kRows) && value(f, kColumns))
      series[trimmed(value(f, kSeriesUid))].push_back(f);
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
    return series.begin()->second;
  }
  const std::string key = opened.string();
  if (!tags.has(key)) fail(path, "not a DICOM file GDCM can read");
  const std::string uid = trimmed(value(key, kSeriesUid));
  if (uid.empty() || !value(key, kRows) || !value(key, kColumns))
    fail(path, "not a DICOM image (no Series Instance UID, Rows or Columns)");
  return series[uid];
}

}  // namespace

ScalarVolume load_dicom(const std::filesystem::path& path, const VolumeLoadOptions& options) {
  gdcm::Trace::WarningOff();  // GDCM reports on std::cerr; what matters reaches the message below
  gdcm::Trace::ErrorOff();

  std::error_code ec;
  const bool is_folder = std::filesystem::is_directory(path, ec);
  const std::filesystem::path folder = is_folder ? path : path.parent_path().empty() ? "." : path.parent_path();
  const std::filesystem::path opened = is_folder ? std::filesystem::path() : folder / path.filename();
  const std::vector<std::string> files = folder_files(folder, opened, path);

  // Element structure and header tags from the walk; a deflated file is walked up to its Pixel Data only.
  DicomWalkLimits header_limits;
  header_limits.inflate_cap = std::min(options.memory_budget_bytes, kMaxDicomHeaderBytes);
  header_limits.stop_at_pixel_data = true;
  header_limits.capture = slice_tag_keys();
  std::map<std::string, DicomWalk> walks;
  std::vector<std::string> dicom_files;
  for (const std::string& f : files) {
    std::optional<DicomWalk> walk = walk_dicom_file(f, header_limits, path, file_name(f));
    if (!walk) {
      if (f == opened.string()) fail(path, "not a DICOM file GDCM can read");
      continue;
    }
    dicom_files.push_back(f);
    walks[f] = std::move(*walk);
  }
  TagTable tags;
  for (auto& [f, walk] : walks) tags.add(f, std::move(walk.values));
  const std::vector<std::string> chosen = choose_series(tags, files, dicom_files, path, opened);
  if (chosen.size() < 2)
    fail(path, "the series " + trimmed(tags.get(chosen.front(), kSeriesUid)) + " has " + std::to_string(chosen.size()) +
                   " slice: a volume needs at least 2");

  std::vector<Slice> slices;
  const SeriesGeometry g = series_geometry(tags, chosen, path, slices);
  const SliceHeader& first = slices.front().header;
  const std::array<std::int64_t, 3> dims{first.columns, first.rows, static_cast<std::int64_t>(slices.size())};
  const std::uint64_t voxels = checked_voxel_count(path, dims);
  // Held at once besides the floats: one slice's Pixel Data as stored (at most its data set) and its decoded copy,
  // with room for a codec's own output buffer.
  std::uint64_t largest_data_set = 0;
  for (const Slice& s : slices) largest_data_set = std::max(largest_data_set, walks[s.header.file].data_set_bytes);
  check_budget(path, dims, voxels, largest_data_set + 2 * first.pixel_bytes(), options);

  const glm::dvec3 step = slice_step(slices, path);
  ScalarVolume v;
  v.dims = {first.columns, first.rows, static_cast<int>(slices.size())};
  v.index_to_world = glm::dmat4(1.0);
  v.index_to_world[0] = glm::dvec4(g.row_dir * g.spacing[1], 0.0);  // i: along a row, the column spacing
  v.index_to_world[1] = glm::dvec4(g.col_dir * g.spacing[0], 0.0);  // j: down a column, the row spacing
  v.index_to_world[2] = glm::dvec4(step, 0.0);
  v.index_to_world[3] = glm::dvec4(slices.front().position, 1.0);
  v.frame = "LPS";  // DICOM's patient coordinate system
  check_index_to_world(path, v.dims, v.index_to_world,
                       "Pixel Spacing (0028,0030) and Image Position (Patient) (0020,0032) of the slices");
  v.modality = trimmed(tags.get(first.file, kModality));
  v.units = v.modality == "CT" ? "HU" : "";

  // A deflated data set's size is known only inflated: counted (not kept) within what the budget leaves and the
  // pixels' size plus kMaxDicomHeaderBytes.
  DicomWalkLimits data_limits;
  const std::uint64_t decode_bytes = 2 * first.pixel_bytes();
  const std::uint64_t left = budget_left(voxels, options);
  data_limits.inflate_cap =
      std::min(left > decode_bytes ? left - decode_bytes : 0, first.pixel_bytes() + kMaxDicomHeaderBytes);
  for (const Slice& s : slices)
    if (walks[s.header.file].deflated) {
      const std::optional<DicomWalk> whole = walk_dicom_file(s.header.file, data_limits, path, s.header.name);
      if (!whole) fail(path, s.header.name + ": not a DICOM file GDCM can read");
      largest_data_set = std::max(largest_data_set, whole->data_set_bytes);
    }
  check_budget(path, dims, voxels, largest_data_set + decode_bytes, options);

  v.values.reserve(voxels);
  for (const Slice& s : slices) decode_slice(s.header, data_limits, path, v.values);
  return v;
}

}  // namespace trispline::core::volume_io
