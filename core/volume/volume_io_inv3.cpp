// InVesalius 3 projects (.inv3) through libarchive (the tar, gzip'd or not) and tinyxml2 (its main.plist).
//
// Layout (InVesalius 3's project.py, and the Cranium.inv3 example): one folder in the tar holding main.plist, the
// image as matrix.dat, masks (mask_N.plist + .dat, one voxel larger on each axis), surfaces (.vtp) and measurements.
// main.plist is an XML property list; the keys read here:
//   matrix   dict: filename (string, "matrix.dat"), shape (array of 3 integers: z, y, x), dtype (string, "int16")
//   spacing  array of 3 reals: x, y, z in millimetres
//   modality string, "CT" in projects made from CT (optional here)
// The matrix file is a raw numpy array of that shape in C order (x fastest), little-endian, exactly
// z·y·x·2 bytes. Nothing is extracted to disk: main.plist is read into memory (at most kMaxPlistBytes) and the
// matrix converted to float block by block as libarchive decompresses it. Older InVesalius writes main.plist first,
// newer last; when the matrix comes first the archive is read a second time. The spacing and the shape are checked
// (geometry bounds, the memory budget) as soon as main.plist is read, before a byte of the matrix is inflated.
#include <archive.h>
#include <archive_entry.h>
#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

constexpr std::size_t kMaxPlistBytes = std::size_t{1} << 20;

struct ArchiveFree {
  void operator()(archive* a) const { archive_read_free(a); }
};
using ArchivePtr = std::unique_ptr<archive, ArchiveFree>;

std::string archive_message(archive* a) {
  const char* s = archive_error_string(a);
  return s ? s : "unknown libarchive error";
}

ArchivePtr open_archive(const std::filesystem::path& path) {
  ArchivePtr a(archive_read_new());
  if (!a) fail(path, "libarchive cannot start");
  archive_read_support_filter_gzip(a.get());
  archive_read_support_format_tar(a.get());
  if (archive_read_open_filename(a.get(), path.c_str(), 64 * 1024) != ARCHIVE_OK)
    fail(path, "cannot read it as a tar or tar.gz archive (libarchive: " + archive_message(a.get()) +
                   "): not an InVesalius project, or a damaged one");
  return a;
}

// An entry's path without a leading "./".
std::string entry_path(archive_entry* entry) {
  const char* p = archive_entry_pathname(entry);
  std::string s = p ? p : "";
  while (s.rfind("./", 0) == 0) s.erase(0, 2);
  return s;
}

std::string folder_of(const std::string& entry) {
  const std::size_t slash = entry.rfind('/');
  return slash == std::string::npos ? std::string() : entry.substr(0, slash + 1);
}

struct Inv3Header {
  std::string matrix_file;                    // the matrix entry's name, in main.plist's folder
  std::array<std::int64_t, 3> dims{0, 0, 0};  // x, y, z
  glm::dvec3 spacing{0.0};                    // millimetres
  std::string modality;                       // "" when absent
};

// The value element after <key>name</key> in a plist <dict>, or nullptr.
const tinyxml2::XMLElement* dict_value(const tinyxml2::XMLElement* dict, const char* name) {
  if (!dict) return nullptr;
  for (const tinyxml2::XMLElement* e = dict->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (std::strcmp(e->Name(), "key") == 0 && e->GetText() && std::strcmp(e->GetText(), name) == 0)
      return e->NextSiblingElement();
  }
  return nullptr;
}

bool is(const tinyxml2::XMLElement* e, const char* name) { return e && std::strcmp(e->Name(), name) == 0; }

// The numbers of a plist <array> of <integer> (or also <real> when reals_too) elements; false unless exactly `count`.
bool plist_numbers(const tinyxml2::XMLElement* array, std::size_t count, bool reals_too, double* out) {
  if (!is(array, "array")) return false;
  std::size_t n = 0;
  for (const tinyxml2::XMLElement* e = array->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (n == count || !(is(e, "integer") || (reals_too && is(e, "real"))) || !e->GetText()) return false;
    const char* text = e->GetText();
    char* end = nullptr;
    errno = 0;
    // Integers are clamped to ±2^62 (exact as double) so that a huge shape reaches the dimension check intact.
    const double value = is(e, "integer")
                             ? static_cast<double>(std::clamp(std::strtoll(text, &end, 10), -(1LL << 62), 1LL << 62))
                             : std::strtod(text, &end);
    while (end && (*end == ' ' || *end == '\n' || *end == '\t' || *end == '\r')) ++end;
    if (end == text || *end != '\0' || errno == ERANGE || !std::isfinite(value)) return false;
    out[n++] = value;
  }
  return n == count;
}

Inv3Header parse_main_plist(const std::filesystem::path& path, const std::string& text) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    fail(path, std::string("main.plist is not readable XML: ") + doc.ErrorStr());
  const tinyxml2::XMLElement* top = doc.FirstChildElement("plist");
  const tinyxml2::XMLElement* dict = top ? top->FirstChildElement("dict") : nullptr;
  if (!dict) fail(path, "main.plist is not a property list (no <plist><dict>)");

  Inv3Header h;
  const tinyxml2::XMLElement* matrix = dict_value(dict, "matrix");
  if (!is(matrix, "dict")) fail(path, "main.plist has no 'matrix' dictionary");
  const tinyxml2::XMLElement* filename = dict_value(matrix, "filename");
  if (!is(filename, "string") || !filename->GetText()) fail(path, "main.plist has no matrix 'filename'");
  h.matrix_file = filename->GetText();
  if (h.matrix_file.empty() || h.matrix_file == "." || h.matrix_file == ".." ||
      h.matrix_file.find_first_of("/\\") != std::string::npos)
    fail(path, "main.plist names the matrix file '" + h.matrix_file + "': a plain file name expected");
  const tinyxml2::XMLElement* dtype = dict_value(matrix, "dtype");
  if (!is(dtype, "string") || !dtype->GetText()) fail(path, "main.plist has no matrix 'dtype'");
  if (std::strcmp(dtype->GetText(), "int16") != 0)
    fail(path,
         std::string("the matrix dtype is '") + dtype->GetText() + "': only int16 (what InVesalius writes) is read");
  double shape[3];
  if (!plist_numbers(dict_value(matrix, "shape"), 3, false, shape))
    fail(path, "main.plist has no matrix 'shape' of 3 integers (z, y, x)");
  h.dims = {static_cast<std::int64_t>(shape[2]), static_cast<std::int64_t>(shape[1]),
            static_cast<std::int64_t>(shape[0])};
  double spacing[3];
  if (!plist_numbers(dict_value(dict, "spacing"), 3, true, spacing))
    fail(path, "main.plist has no 'spacing' of 3 numbers (x, y, z millimetres)");
  if (!(spacing[0] > 0.0 && spacing[1] > 0.0 && spacing[2] > 0.0)) fail(path, "main.plist's spacing is not positive");
  h.spacing = glm::dvec3(spacing[0], spacing[1], spacing[2]);
  const tinyxml2::XMLElement* modality = dict_value(dict, "modality");
  if (is(modality, "string") && modality->GetText()) h.modality = modality->GetText();
  return h;
}

// Reads the current entry (size checked by the caller) into a string.
std::string read_entry_text(const std::filesystem::path& path, archive* a, std::size_t size, const std::string& name) {
  std::string text(size, '\0');
  std::size_t done = 0;
  while (done < size) {
    const la_ssize_t got = archive_read_data(a, text.data() + done, size - done);
    if (got < 0) fail(path, "damaged archive while reading " + name + ": " + archive_message(a));
    if (got == 0)
      fail(path,
           "truncated: " + name + " ends after " + std::to_string(done) + " of " + std::to_string(size) + " bytes");
    done += static_cast<std::size_t>(got);
  }
  return text;
}

// Streams the current entry (exactly voxels·2 bytes, int16 little-endian) into `values` as floats.
void read_matrix(const std::filesystem::path& path, archive* a, std::uint64_t voxels, const std::string& name,
                 std::vector<float>& values) {
  values.reserve(static_cast<std::size_t>(voxels));
  std::vector<unsigned char> block(kStreamBlockBytes);
  const std::uint64_t total = voxels * 2;
  std::uint64_t done = 0;
  int pending = -1;  // the low byte of a sample split between two reads
  while (done < total) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(block.size(), total - done));
    const la_ssize_t got = archive_read_data(a, block.data(), want);
    if (got < 0) fail(path, "damaged archive while reading " + name + ": " + archive_message(a));
    if (got == 0)
      fail(path,
           "truncated: " + name + " ends after " + std::to_string(done) + " of " + std::to_string(total) + " bytes");
    for (la_ssize_t i = 0; i < got; ++i) {
      if (pending < 0) {
        pending = block[static_cast<std::size_t>(i)];
      } else {
        const auto sample = static_cast<std::int16_t>(
            static_cast<std::uint16_t>(pending) | static_cast<std::uint16_t>(block[static_cast<std::size_t>(i)] << 8));
        values.push_back(static_cast<float>(sample));
        pending = -1;
      }
    }
    done += static_cast<std::uint64_t>(got);
  }
}

}  // namespace

ScalarVolume load_inv3(const std::filesystem::path& path, const VolumeLoadOptions& options) {
  bool have_plist = false, have_matrix = false;
  Inv3Header header;
  std::string matrix_entry;  // main.plist's folder + the matrix file name
  std::uint64_t voxels = 0;
  ScalarVolume v;
  for (int pass = 0; pass < 2 && !have_matrix; ++pass) {
    if (pass == 1 && !have_plist) break;
    const ArchivePtr a = open_archive(path);
    archive_entry* entry = nullptr;
    while (!(have_plist && have_matrix)) {
      const int r = archive_read_next_header(a.get(), &entry);
      if (r == ARCHIVE_EOF) break;
      if (r != ARCHIVE_OK && r != ARCHIVE_WARN)
        fail(path,
             "cannot read it as a tar or tar.gz archive (libarchive: " + archive_message(a.get()) +
                 (have_plist ? "): a damaged InVesalius project" : "): not an InVesalius project, or a damaged one"));
      if (archive_entry_filetype(entry) != AE_IFREG) continue;
      const std::string name = entry_path(entry);
      const bool sized = archive_entry_size_is_set(entry) && archive_entry_size(entry) >= 0;
      const std::uint64_t size = sized ? static_cast<std::uint64_t>(archive_entry_size(entry)) : 0;
      const std::string base = name.substr(name.rfind('/') == std::string::npos ? 0 : name.rfind('/') + 1);
      if (!have_plist && base == "main.plist") {
        if (!sized || size > kMaxPlistBytes)
          fail(path, "main.plist is " + (sized ? format_bytes(size) : std::string("of unknown size")) + ": at most " +
                         format_bytes(kMaxPlistBytes) + " expected");
        header = parse_main_plist(path, read_entry_text(path, a.get(), static_cast<std::size_t>(size), "main.plist"));
        have_plist = true;
        matrix_entry = folder_of(name) + header.matrix_file;
        voxels = checked_voxel_count(path, header.dims);
        v.dims = {static_cast<int>(header.dims[0]), static_cast<int>(header.dims[1]), static_cast<int>(header.dims[2])};
        v.index_to_world = glm::dmat4(1.0);
        for (int a = 0; a < 3; ++a) v.index_to_world[a][a] = header.spacing[a];
        check_index_to_world(path, v.dims, v.index_to_world, "main.plist's spacing (x, y, z millimetres)");
        check_budget(path, header.dims, voxels, kStreamBlockBytes + kMaxPlistBytes, options);
      } else if (have_plist && !have_matrix && name == matrix_entry) {
        const std::uint64_t expected = voxels * 2;
        if (!sized || size != expected)
          fail(path, header.matrix_file + " holds " +
                         (sized ? std::to_string(size) : std::string("an unknown number of")) + " bytes; the shape " +
                         std::to_string(header.dims[2]) + "×" + std::to_string(header.dims[1]) + "×" +
                         std::to_string(header.dims[0]) + " (z, y, x) of int16 needs " + std::to_string(expected));
        read_matrix(path, a.get(), voxels, header.matrix_file, v.values);
        have_matrix = true;
      }
    }
  }
  if (!have_plist) fail(path, "not an InVesalius project (no main.plist in the archive)");
  if (!have_matrix)
    fail(path, "the project's image '" + matrix_entry + "' (named in main.plist) is not in the archive");

  v.modality = header.modality.empty() ? "CT" : header.modality;
  v.units = v.modality == "CT" ? "HU" : "";
  return v;
}

}  // namespace trispline::core::volume_io
