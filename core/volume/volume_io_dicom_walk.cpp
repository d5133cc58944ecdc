// walk_dicom_file: a DICOM file's element headers, walked over a buffered byte source (the plain file, or zlib's
// inflation of a deflated data set counted and dropped as it goes).
#include "core/volume/volume_io_dicom_walk.h"

#include <gdcmTransferSyntax.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "core/volume/volume_io_formats.h"

namespace trispline::core::volume_io {

namespace {

constexpr std::uint32_t kUndefinedLength = 0xFFFFFFFFu;

struct WalkError {
  std::string what;
  std::uint64_t offset;
};

// Bytes in order from a buffer refilled by the subclass; read, peek and skip.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  std::uint64_t position() const { return pos_; }
  virtual std::optional<std::uint64_t> left() const = 0;  // bytes left, when known without reading them
  virtual const char* where() const = 0;                  // " of the file", " of the inflated data set"

  std::size_t read(unsigned char* out, std::size_t n) {
    std::size_t done = 0;
    while (done < n) {
      if (begin_ == end_ && !refill_buffer()) break;
      const std::size_t take = std::min(n - done, end_ - begin_);
      std::memcpy(out + done, buf_.data() + begin_, take);
      begin_ += take, done += take, pos_ += take;
    }
    return done;
  }

  // The next n (≤ 8) bytes without consuming them; false when fewer are left.
  bool peek(unsigned char* out, std::size_t n) {
    while (end_ - begin_ < n) {
      std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
      end_ -= begin_, begin_ = 0;
      const std::size_t got = refill(buf_.data() + end_, buf_.size() - end_);
      if (got == 0) return false;
      end_ += got;
    }
    std::memcpy(out, buf_.data() + begin_, n);
    return true;
  }

  // Skips n bytes; false when the data ends first.
  virtual bool skip(std::uint64_t n) {
    while (n > 0) {
      if (begin_ == end_ && !refill_buffer()) return false;
      const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(n, end_ - begin_));
      begin_ += take, pos_ += take, n -= take;
    }
    return true;
  }

 protected:
  virtual std::size_t refill(unsigned char* out, std::size_t capacity) = 0;  // 0 at the end
  bool refill_buffer() {
    begin_ = 0;
    end_ = refill(buf_.data(), buf_.size());
    return end_ > 0;
  }
  std::vector<unsigned char> buf_ = std::vector<unsigned char>(64 * 1024);
  std::size_t begin_ = 0, end_ = 0;
  std::uint64_t pos_ = 0;  // bytes delivered or skipped
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// The plain file: position = file offset, skips seek.
class FileSource : public ByteSource {
 public:
  // `file` positioned at byte `start`.
  FileSource(std::FILE* file, std::uint64_t size, std::uint64_t start) : file_(file), size_(size) { pos_ = start; }
  std::optional<std::uint64_t> left() const override { return pos_ > size_ ? 0 : size_ - pos_; }
  const char* where() const override { return " of the file"; }
  bool skip(std::uint64_t n) override {
    if (pos_ > size_ || n > size_ - pos_) return false;
    if (n <= end_ - begin_) return ByteSource::skip(n);
    pos_ += n;
    begin_ = end_ = 0;
    return fseeko(file_, static_cast<off_t>(pos_), SEEK_SET) == 0;
  }

 protected:
  std::size_t refill(unsigned char* out, std::size_t capacity) override { return std::fread(out, 1, capacity, file_); }

 private:
  std::FILE* file_;
  std::uint64_t size_;
};

// A deflated data set (raw deflate, PS3.5 §A.5; a zlib header is accepted too) from the file's current offset,
// inflated into the buffer and dropped as it is consumed; more than `cap` inflated bytes fail.
class InflateSource : public ByteSource {
 public:
  InflateSource(std::FILE* file, std::uint64_t cap) : file_(file), cap_(cap) {
    unsigned char head[2] = {0, 0};
    const std::size_t got = std::fread(head, 1, 2, file_);
    const bool zlib_header = got == 2 && (head[0] & 0x0F) == 8 && ((head[0] << 8) | head[1]) % 31 == 0;
    in_len_ = got;
    std::memcpy(in_.data(), head, got);
    if (inflateInit2(&z_, zlib_header ? 15 : -15) != Z_OK) throw WalkError{"zlib cannot start", 0};
  }
  ~InflateSource() override { inflateEnd(&z_); }
  std::optional<std::uint64_t> left() const override { return std::nullopt; }
  const char* where() const override { return " of the inflated data set"; }
  std::uint64_t inflated() const { return total_; }

 protected:
  std::size_t refill(unsigned char* out, std::size_t capacity) override {
    if (ended_) return 0;
    z_.next_out = out;
    z_.avail_out = static_cast<uInt>(capacity);
    while (z_.avail_out == capacity) {
      if (z_.avail_in == 0) {
        if (in_len_ == 0) in_len_ = std::fread(in_.data(), 1, in_.size(), file_);
        if (in_len_ == 0) throw WalkError{"the deflated data set is cut short (no end of its deflate stream)", pos_};
        z_.next_in = in_.data();
        z_.avail_in = static_cast<uInt>(in_len_);
        in_len_ = 0;
      }
      const int r = inflate(&z_, Z_NO_FLUSH);
      if (r == Z_STREAM_END) {
        ended_ = true;
        break;
      }
      if (r != Z_OK && r != Z_BUF_ERROR)
        throw WalkError{std::string("the deflated data set is damaged (zlib: ") + (z_.msg ? z_.msg : "error") + ")",
                        pos_};
    }
    const std::size_t got = capacity - z_.avail_out;
    total_ += got;
    if (total_ > cap_)
      throw WalkError{"the deflated data set inflates to more than " + format_bytes(cap_) +
                          " (its bound: what the memory budget leaves for one slice file, and no more than its pixels "
                          "plus " +
                          format_bytes(kMaxDicomHeaderBytes) + " of other elements)",
                      pos_};
    return got;
  }

 private:
  std::FILE* file_;
  std::uint64_t cap_;
  z_stream z_{};
  std::vector<unsigned char> in_ = std::vector<unsigned char>(64 * 1024);
  std::size_t in_len_ = 0;  // bytes in in_ not yet handed to zlib
  std::uint64_t total_ = 0;
  bool ended_ = false;
};

enum class Syntax { kImplicitLittle, kExplicitLittle, kExplicitBig };

std::uint16_t u16(const unsigned char* p, bool big) {
  return big ? static_cast<std::uint16_t>(p[0] << 8 | p[1]) : static_cast<std::uint16_t>(p[1] << 8 | p[0]);
}
std::uint32_t u32(const unsigned char* p, bool big) {
  return big ? (std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3])
             : (std::uint32_t{p[3]} << 24 | std::uint32_t{p[2]} << 16 | std::uint32_t{p[1]} << 8 | p[0]);
}

// One of the value representations of PS3.5 Table 6.2-1 (GDCM stops on an assertion at an unknown one in the meta
// header).
bool is_vr(const unsigned char* p) {
  static const char* const kVrs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FD", "FL", "IS", "LO", "LT",
                                     "OB", "OD", "OF", "OL", "OV", "OW", "PN", "SH", "SL", "SQ", "SS", "ST",
                                     "SV", "TM", "UC", "UI", "UL", "UN", "UR", "US", "UT", "UV"};
  return std::any_of(std::begin(kVrs), std::end(kVrs), [&](const char* v) { return p[0] == v[0] && p[1] == v[1]; });
}

// Explicit VRs with a 2-byte reserved field and a 4-byte length (PS3.5 Table 7.1-1).
bool has_long_length(const unsigned char* vr) {
  static const char* const kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "UC", "UN", "UR", "UT", "SV", "UV"};
  return std::any_of(std::begin(kLong), std::end(kLong), [&](const char* v) { return vr[0] == v[0] && vr[1] == v[1]; });
}

std::string tag_text(std::uint16_t group, std::uint16_t element) {
  char text[16];
  std::snprintf(text, sizeof text, "(%04X,%04X)", group, element);
  return text;
}

// The element structure of one data set, depth first, without recursion.
class Walker {
 public:
  // `pixels`: where to keep the top-level Pixel Data, or nullptr to skip it.
  Walker(ByteSource& src, std::uint64_t& elements, const std::vector<std::uint32_t>& capture,
         std::map<std::uint32_t, std::string>& values, DicomPixelData* pixels)
      : src_(src), elements_(elements), capture_(capture), values_(values), pixels_(pixels) {}

  // Walks the data set to its end (true) or, with stop_at_pixel_data, to the top-level Pixel Data tag (false).
  bool walk(Syntax syntax, bool stop_at_pixel_data) {
    stack_.assign(1, Frame{Kind::kDataSet, std::nullopt, syntax});
    while (true) {
      const Frame f = stack_.back();
      if (f.end && src_.position() == *f.end) {
        stack_.pop_back();
        continue;
      }
      if (f.end && src_.position() > *f.end)
        throw WalkError{"an element header crosses the end of its enclosing " + kind_name(f.kind), src_.position()};
      unsigned char tag[4];
      const std::uint64_t at = src_.position();
      const std::size_t got = src_.read(tag, 4);
      if (got == 0 && stack_.size() == 1) return true;
      if (got == 0) throw WalkError{"the data ends inside an undefined-length " + kind_name(f.kind), at};
      if (got < 4) throw WalkError{"the data ends inside an element's tag", at};
      const bool big = f.syntax == Syntax::kExplicitBig;
      const std::uint16_t group = u16(tag, big), element = u16(tag + 2, big);
      if (++elements_ > kMaxDicomElements)
        throw WalkError{"more than " + std::to_string(kMaxDicomElements) + " data elements", at};
      if (group == 0xFFFE) {
        delimiter_or_item(f, element, at);
        continue;
      }
      if (f.kind == Kind::kSequence || f.kind == Kind::kFragments)
        throw WalkError{"element " + tag_text(group, element) + " where a sequence item was expected", at};
      if (stop_at_pixel_data && stack_.size() == 1 && group == 0x7FE0 && element == 0x0010) return false;
      data_element(f, group, element, at);
    }
  }

 private:
  enum class Kind { kDataSet, kSequence, kItem, kFragments };
  struct Frame {
    Kind kind;
    std::optional<std::uint64_t> end;  // where a defined-length frame ends
    Syntax syntax;
    bool keep = false;  // the top-level Pixel Data's fragments, kept
  };

  static std::string kind_name(Kind k) {
    return k == Kind::kSequence ? "sequence" : k == Kind::kItem ? "item" : "encapsulated Pixel Data";
  }

  // Fails unless `length` bytes from here fit in the data and in the innermost defined-length frame.
  void check_fits(std::uint64_t length, std::uint64_t at, const std::string& what) const {
    if (const std::optional<std::uint64_t> left = src_.left(); left && length > *left)
      throw WalkError{what + " declares " + std::to_string(length) + " bytes; " + std::to_string(*left) + " are left" +
                          src_.where() + " (truncated, or a false length)",
                      at};
    for (auto it = stack_.rbegin(); it != stack_.rend(); ++it)
      if (it->end) {
        if (src_.position() > *it->end || length > *it->end - src_.position())
          throw WalkError{what + " declares " + std::to_string(length) + " bytes, past the end of its enclosing " +
                              kind_name(it->kind),
                          at};
        break;
      }
  }

  void push(Kind kind, std::optional<std::uint64_t> length, Syntax syntax, std::uint64_t at, bool keep = false) {
    if (static_cast<int>(stack_.size()) > kMaxDicomNesting)
      throw WalkError{"sequences nested more than " + std::to_string(kMaxDicomNesting) + " deep", at};
    std::optional<std::uint64_t> end;
    if (length) end = src_.position() + *length;
    stack_.push_back(Frame{kind, end, syntax, keep});
  }

  // Reads a value of `length` bytes (already checked to fit) onto the end of `out`, 1 MiB at a time: memory grows
  // with the bytes that really arrive, never ahead of them from the declared length.
  void read_into(std::vector<char>& out, std::uint64_t length, std::uint64_t at, const std::string& what) {
    constexpr std::uint64_t kStep = 1u << 20;
    while (length > 0) {
      const std::size_t n = static_cast<std::size_t>(std::min(length, kStep));
      const std::size_t old = out.size();
      out.resize(old + n);
      if (src_.read(reinterpret_cast<unsigned char*>(out.data() + old), n) != n)
        throw WalkError{what + " is cut short: the data ends inside its value (truncated)", at};
      length -= n;
    }
  }

  void skip(std::uint64_t length, std::uint64_t at, const std::string& what) {
    if (!src_.skip(length))
      throw WalkError{what + " declares " + std::to_string(length) + " bytes; the data ends first (truncated)", at};
  }

  void delimiter_or_item(const Frame& f, std::uint16_t element, std::uint64_t at) {
    unsigned char len_bytes[4];
    if (src_.read(len_bytes, 4) != 4) throw WalkError{"the data ends inside an item's length", at};
    const std::uint32_t length = u32(len_bytes, f.syntax == Syntax::kExplicitBig);
    if (element == 0xE000) {
      if (f.kind == Kind::kFragments) {
        if (length == kUndefinedLength) throw WalkError{"an encapsulated pixel data fragment of undefined length", at};
        check_fits(length, at, "a pixel data fragment");
        if (f.keep)
          read_into(pixels_->fragments.emplace_back(), length, at, "a pixel data fragment");
        else
          skip(length, at, "a pixel data fragment");
      } else if (f.kind == Kind::kSequence) {
        if (length != kUndefinedLength) check_fits(length, at, "an item");
        push(Kind::kItem, length == kUndefinedLength ? std::nullopt : std::optional<std::uint64_t>(length), f.syntax,
             at);
      } else {
        throw WalkError{"an item (FFFE,E000) outside a sequence", at};
      }
    } else if (element == 0xE00D && f.kind == Kind::kItem && !f.end) {
      stack_.pop_back();
    } else if (element == 0xE0DD && (f.kind == Kind::kSequence || f.kind == Kind::kFragments) && !f.end) {
      stack_.pop_back();
    } else {
      throw WalkError{"a delimiter " + tag_text(0xFFFE, element) + " where it closes nothing", at};
    }
  }

  void data_element(const Frame& f, std::uint16_t group, std::uint16_t element, std::uint64_t at) {
    const bool big = f.syntax == Syntax::kExplicitBig;
    unsigned char vr[2] = {0, 0};
    std::uint32_t length = 0;
    unsigned char b[6];
    if (f.syntax == Syntax::kImplicitLittle) {
      if (src_.read(b, 4) != 4) throw WalkError{"the data ends inside an element header", at};
      length = u32(b, false);
    } else {
      if (src_.read(vr, 2) != 2) throw WalkError{"the data ends inside an element header", at};
      if (!is_vr(vr)) throw WalkError{"element " + tag_text(group, element) + " has no known value representation", at};
      if (has_long_length(vr)) {
        if (src_.read(b, 6) != 6) throw WalkError{"the data ends inside an element header", at};
        length = u32(b + 2, big);
      } else {
        if (src_.read(b, 2) != 2) throw WalkError{"the data ends inside an element header", at};
        length = u16(b, big);
      }
    }
    const std::string what = "element " + tag_text(group, element);
    const bool pixel_data = group == 0x7FE0 && element == 0x0010;
    const bool explicit_vr = f.syntax != Syntax::kImplicitLittle;
    const bool sq = explicit_vr && vr[0] == 'S' && vr[1] == 'Q', un = explicit_vr && vr[0] == 'U' && vr[1] == 'N';
    const bool keep = pixel_data && pixels_ && stack_.size() == 1;
    if (keep) {
      if (pixels_->found) throw WalkError{"a second Pixel Data (7FE0,0010)", at};
      pixels_->found = true;
      pixels_->encapsulated = length == kUndefinedLength;
    }
    if (length == kUndefinedLength) {
      if (pixel_data && (!explicit_vr || vr[0] == 'O'))
        push(Kind::kFragments, std::nullopt, f.syntax, at, keep);
      else if (!explicit_vr || sq || un)
        push(Kind::kSequence, std::nullopt, un ? Syntax::kImplicitLittle : f.syntax, at);
      else
        throw WalkError{what + " (" + std::string(vr, vr + 2) + ") has an undefined length", at};
      return;
    }
    check_fits(length, at, what);
    unsigned char first[4];
    // A defined-length value that opens with an item tag is a sequence to GDCM (SQ, or UN / implicit holding one).
    const bool item_first = (!explicit_vr || un) && !pixel_data && length >= 8 && src_.peek(first, 4) &&
                            u16(first, big) == 0xFFFE && u16(first + 2, big) == 0xE000;
    const std::uint32_t key = std::uint32_t{group} << 16 | element;
    if (keep)
      read_into(pixels_->value, length, at, what);
    else if (sq || item_first)
      push(Kind::kSequence, length, sq ? f.syntax : Syntax::kImplicitLittle, at);
    else if (stack_.size() == 1 && length <= 1024 && std::find(capture_.begin(), capture_.end(), key) != capture_.end())
      capture(group, element, explicit_vr ? vr : nullptr, length, big, at);
    else
      skip(length, at, what);
  }

  // Keeps a captured top-level value (the source is at its first byte).
  void capture(std::uint16_t group, std::uint16_t element, const unsigned char* vr, std::uint32_t length, bool big,
               std::uint64_t at) {
    std::string value(length, '\0');
    if (src_.read(reinterpret_cast<unsigned char*>(value.data()), length) != length)
      throw WalkError{"element " + tag_text(group, element) + " is cut short", at};
    // US: an unsigned 16-bit number. The image pixel module's US tags (PS3.3 C.7.6.3) are read as US whatever VR
    // the file gives them (none in implicit VR; writers also put UN or SS there), as GDCM's dictionary does.
    const bool pixel_module_us = group == 0x0028 && (element == 0x0002 || element == 0x0010 || element == 0x0011 ||
                                                     element == 0x0100 || element == 0x0101 || element == 0x0103);
    const bool us = pixel_module_us || (vr && vr[0] == 'U' && vr[1] == 'S');
    if (us && length == 2) value = std::to_string(u16(reinterpret_cast<const unsigned char*>(value.data()), big));
    values_[std::uint32_t{group} << 16 | element] = value;
  }

  ByteSource& src_;
  std::uint64_t& elements_;
  const std::vector<std::uint32_t>& capture_;
  std::map<std::uint32_t, std::string>& values_;
  DicomPixelData* pixels_;
  std::vector<Frame> stack_;
};

std::string trimmed_uid(const unsigned char* p, std::size_t n) {
  std::string s(reinterpret_cast<const char*>(p), n);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  while (!s.empty() && s.front() == ' ') s.erase(0, 1);
  return s;
}

// The group 0002 meta header (explicit VR little endian) from the current position; returns the transfer syntax,
// which a meta header must hold, and checks the elements end where the group length says.
std::string walk_meta(FileSource& src) {
  std::string uid;
  const std::uint64_t start = src.position();
  std::optional<std::uint64_t> group_end;
  unsigned char tag[4];
  while (src.peek(tag, 4) && u16(tag, false) == 0x0002) {
    const std::uint64_t at = src.position();
    if (at - start > kMaxDicomMetaBytes)
      throw WalkError{"the meta header (group 0002) is longer than " + format_bytes(kMaxDicomMetaBytes), at};
    unsigned char h[8];
    if (src.read(h, 8) != 8) throw WalkError{"the data ends inside a meta header element", at};
    const std::uint16_t element = u16(h + 2, false);
    if (!is_vr(h + 4))
      throw WalkError{"meta header element " + tag_text(2, element) + " has no known value representation", at};
    std::uint32_t length = u16(h + 6, false);
    if (has_long_length(h + 4)) {
      unsigned char l[4];
      if (src.read(l, 4) != 4) throw WalkError{"the data ends inside a meta header element", at};
      length = u32(l, false);
    }
    if (length > *src.left())
      throw WalkError{"meta header element " + tag_text(2, element) + " declares " + std::to_string(length) +
                          " bytes; " + std::to_string(*src.left()) + " are left of the file",
                      at};
    if (element == 0x0000 && length == 4) {  // File Meta Information Group Length: the bytes after it
      unsigned char l[4];
      src.read(l, 4);
      group_end = src.position() + u32(l, false);
    } else if (element == 0x0010 && length <= 64) {
      unsigned char value[64];
      src.read(value, length);
      uid = trimmed_uid(value, length);
    } else if (!src.skip(length)) {
      throw WalkError{"meta header element " + tag_text(2, element) + " is cut short", at};
    }
  }
  // GDCM reads the meta header by its group length where the elements disagree with it: they must agree.
  if (group_end && src.position() != *group_end)
    throw WalkError{"the meta header's group length (0002,0000) ends it at byte " + std::to_string(*group_end) +
                        ", its elements at byte " + std::to_string(src.position()),
                    src.position()};
  if (src.position() > start && uid.empty())
    throw WalkError{"the meta header has no Transfer Syntax UID (0002,0010)", src.position()};
  // GDCM stops on an assertion reading a data set in a transfer syntax it does not know.
  if (!uid.empty() && gdcm::TransferSyntax::GetTSType(uid.c_str()) == gdcm::TransferSyntax::TS_END)
    throw WalkError{"the transfer syntax '" + uid + "' (0002,0010) is not a known DICOM transfer syntax",
                    src.position()};
  return uid;
}

// The syntax of a data set without a reliable meta header, from its first element: a VR after the tag → explicit.
Syntax guess_syntax(ByteSource& src, Syntax declared) {
  if (declared == Syntax::kExplicitBig) return declared;
  unsigned char head[6];
  if (!src.peek(head, 6)) return declared;
  if (u16(head, false) == 0xFFFE) return declared;
  return is_vr(head + 4) ? Syntax::kExplicitLittle : Syntax::kImplicitLittle;
}

}  // namespace

std::optional<DicomWalk> walk_dicom_file(const std::filesystem::path& file, const DicomWalkLimits& limits,
                                         const std::filesystem::path& report, const std::string& name) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) fail(report, name + ": cannot read the file size: " + ec.message());
  FilePtr handle(std::fopen(file.c_str(), "rb"));
  if (!handle) fail(report, name + ": cannot open the file");
  unsigned char preamble[132];
  const bool dicm = std::fread(preamble, 1, 132, handle.get()) == 132 && std::memcmp(preamble + 128, "DICM", 4) == 0;
  if (fseeko(handle.get(), dicm ? 132 : 0, SEEK_SET) != 0) fail(report, name + ": cannot read the file");
  FileSource src(handle.get(), size, dicm ? 132 : 0);
  DicomWalk walk;
  std::uint64_t elements = 0;
  std::string where = src.where();
  try {
    walk.transfer_syntax = walk_meta(src);
    const std::string& ts = walk.transfer_syntax;
    if (!ts.empty()) walk.values[0x00020010] = ts;
    walk.deflated = ts == "1.2.840.10008.1.2.1.99";
    if (walk.deflated) {
      if (fseeko(handle.get(), static_cast<off_t>(src.position()), SEEK_SET) != 0)
        fail(report, name + ": cannot read the file");
      InflateSource inflated(handle.get(), limits.inflate_cap);
      where = inflated.where();
      Walker walker(inflated, elements, limits.capture, walk.values,
                    limits.keep_pixel_data ? &walk.pixel_data : nullptr);
      walk.complete = walker.walk(Syntax::kExplicitLittle, limits.stop_at_pixel_data);
      walk.data_set_bytes = inflated.inflated();
      return walk;
    }
    const Syntax declared = ts == "1.2.840.10008.1.2"     ? Syntax::kImplicitLittle
                            : ts == "1.2.840.10008.1.2.2" ? Syntax::kExplicitBig
                                                          : Syntax::kExplicitLittle;
    Walker walker(src, elements, limits.capture, walk.values, limits.keep_pixel_data ? &walk.pixel_data : nullptr);
    walk.complete = walker.walk(guess_syntax(src, declared), false);
    walk.data_set_bytes = size;
    if (!dicm && elements == 0) return std::nullopt;  // an empty file
    if (elements == 0) throw WalkError{"no data set after the meta header", src.position()};
    return walk;
  } catch (const WalkError& e) {
    if (!dicm && elements < 2) return std::nullopt;  // no preamble and no element structure: not DICOM
    fail(report, name + ": at byte " + std::to_string(e.offset) + where + ", " + e.what + ": a broken DICOM structure");
  }
}

}  // namespace trispline::core::volume_io
