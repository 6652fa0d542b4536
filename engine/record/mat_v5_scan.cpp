#include "engine/record/mat_v5_scan.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>

namespace dampbench {
namespace {

/// True when the next `bytes` bytes of `in` are a zlib stream that inflates to its end, its checksum right.
bool zlib_stream_complete(std::istream& in, std::uint32_t bytes) {
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) return false;
  std::vector<unsigned char> input(std::size_t{1} << 16), output(std::size_t{1} << 16);
  int status = Z_OK;
  for (std::uint32_t left = bytes; left > 0 && status != Z_STREAM_END;) {
    const std::uint32_t chunk = std::min<std::uint32_t>(left, static_cast<std::uint32_t>(input.size()));
    if (!in.read(reinterpret_cast<char*>(input.data()), chunk)) break;
    left -= chunk;
    stream.next_in = input.data();
    stream.avail_in = chunk;
    do {
      stream.next_out = output.data();
      stream.avail_out = static_cast<uInt>(output.size());
      status = inflate(&stream, Z_NO_FLUSH);
    } while (status == Z_OK && stream.avail_out == 0);
    if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) break;
  }
  inflateEnd(&stream);
  return status == Z_STREAM_END;
}


/// The bytes of one top-level v5 element after its tag, in order, as matio reads them: from the file, or inflated
/// from its zlib stream. read and skip fail where the bytes end (the end of the file or of the stream, a damaged
/// stream, or the end of what the element's tag counts).
class ElementBytes {
 public:
  ElementBytes(const std::string& path, const V5Element& element, std::uintmax_t file_bytes)
      : in_(path, std::ios::binary), compressed_(element.compressed) {
    const std::uintmax_t in_file = element.offset < file_bytes ? file_bytes - element.offset : 0;
    input_left_ = std::min<std::uintmax_t>(element.bytes, in_file);
    if (!in_.seekg(static_cast<std::streamoff>(element.offset))) input_left_ = 0;
    if (compressed_) {
      zlib_ready_ = inflateInit(&stream_) == Z_OK;
      input_.resize(std::size_t{1} << 16);
    }
  }
  ~ElementBytes() {
    if (zlib_ready_) inflateEnd(&stream_);
  }
  ElementBytes(const ElementBytes&) = delete;
  ElementBytes& operator=(const ElementBytes&) = delete;

  bool read(void* out, std::uint64_t count) { return pull(static_cast<unsigned char*>(out), count); }
  bool skip(std::uint64_t count) {
    if (!compressed_) {
      if (count > input_left_ || !in_.seekg(static_cast<std::streamoff>(count), std::ios::cur)) return fail();
      input_left_ -= count;
      position_ += count;
      return true;
    }
    return pull(nullptr, count);
  }
  /// How many bytes read and skip have delivered.
  std::uint64_t position() const { return position_; }

 private:
  bool fail() {
    input_left_ = 0;
    ended_ = true;
    return false;
  }

  /// Delivers the next `count` bytes into `out`, or discards them when `out` is null.
  bool pull(unsigned char* out, std::uint64_t count) {
    if (ended_) return false;
    if (!compressed_) {
      if (count > input_left_ || !in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(count)))
        return fail();
      input_left_ -= count;
      position_ += count;
      return true;
    }
    if (!zlib_ready_) return fail();
    unsigned char discard[4096];
    while (count > 0) {
      if (stream_.avail_in == 0) {
        if (input_left_ == 0) return fail();
        const auto chunk = static_cast<std::size_t>(std::min<std::uintmax_t>(input_left_, input_.size()));
        if (!in_.read(reinterpret_cast<char*>(input_.data()), static_cast<std::streamsize>(chunk))) return fail();
        input_left_ -= chunk;
        stream_.next_in = input_.data();
        stream_.avail_in = static_cast<uInt>(chunk);
      }
      const auto room = static_cast<uInt>(std::min<std::uint64_t>(count, out ? 1u << 30 : sizeof discard));
      stream_.next_out = out ? out : discard;
      stream_.avail_out = room;
      const int status = inflate(&stream_, Z_NO_FLUSH);
      const uInt made = room - stream_.avail_out;
      count -= made;
      position_ += made;
      if (out) out += made;
      if (status == Z_STREAM_END) {
        ended_ = true;
        return count == 0;
      }
      if (status != Z_OK && status != Z_BUF_ERROR) return fail();
      if (status == Z_BUF_ERROR && stream_.avail_in != 0) return fail();  // no progress
    }
    return true;
  }

  std::ifstream in_;
  bool compressed_;
  bool zlib_ready_ = false;
  bool ended_ = false;
  std::uintmax_t input_left_ = 0;  ///< bytes of the element in the file not yet read
  std::uint64_t position_ = 0;
  z_stream stream_{};
  std::vector<unsigned char> input_;
};

/// Walks the header of a v5 element the way Mat_VarReadNextInfo does (and, for a struct, a cell or a function
/// handle, the headers of all the elements inside, which matio lists with it) and checks each size that matio
/// allocates from before it reads the bytes behind it: the dimensions, the name, a struct's field names and its
/// elements × fields field pointers, a cell's or function handle's element pointers, and, in a compressed struct or
/// cell, the values of a small field, which matio reads with the header. A size must fit in the bytes its element
/// claims and those bytes must be there; a layout that matio would misread (e.g. a dimensions tag of another type)
/// is unsafe as well, since matio would then take sizes from the wrong bytes. Data that is merely cut short is not
/// unsafe: matio reads it with an error (v5_element_intact catches the rest).
class V5HeaderScan {
 public:
  V5HeaderScan(ElementBytes& bytes, bool swapped, bool compressed)
      : bytes_(bytes), swapped_(swapped), compressed_(compressed) {}

  V5Verdict run() {
    try {
      std::uint64_t end = kNoEnd;  // uncompressed: the count in the element's tag (limit_to)
      if (compressed_) {           // the zlib stream holds a miMATRIX element, tag and all
        const auto [type, count] = tag(kNoEnd);
        if (type != kMatrixType) return V5Verdict::unsafe;
        end = bytes_.position() + count;
      }
      return matrix(end, Kind::top, 0);
    } catch (const Unsafe&) {
      return V5Verdict::unsafe;
    } catch (const RanOut&) {
      // The bytes end early: safe unless a size matio allocates from reached past where they end.
      return bytes_.position() < backed_end_ ? V5Verdict::unsafe : V5Verdict::listable;
    }
  }

  /// The bytes of an uncompressed element, which its tag counts: set before run.
  void limit_to(std::uint64_t bytes) { top_bytes_ = bytes; }

 private:
  struct Unsafe {};
  struct RanOut {};
  enum class Kind { top, field, cell };
  static constexpr std::uint64_t kNoEnd = UINT64_MAX;
  static constexpr std::uint32_t kInt8 = 1, kInt32 = 5, kUint32 = 6, kMatrixType = 14;
  static constexpr std::uint32_t kCellClass = 1, kStructClass = 2, kSparseClass = 5, kFunctionClass = 16,
                                 kOpaqueClass = 17;
  /// Deeper nesting than this is unsafe: matio follows structs and cells by recursion, one stack frame a level.
  static constexpr int kMaxDepth = 64;
  /// matio reads the values of a field of a compressed struct or cell with its header up to this many bytes.
  static constexpr std::uint64_t kMatioInflateWindow = 1u << 15;

  static std::uint64_t product(std::uint64_t a, std::uint64_t b) {
    std::uint64_t p;
    return __builtin_mul_overflow(a, b, &p) ? UINT64_MAX : p;
  }
  static std::uint64_t padded(std::uint64_t n) { return n + (8 - n % 8) % 8; }

  std::uint32_t word(const unsigned char* at) const {
    std::uint32_t w;
    std::memcpy(&w, at, sizeof w);
    return swapped_ ? __builtin_bswap32(w) : w;
  }
  std::uint64_t left(std::uint64_t end) const {
    const std::uint64_t at = bytes_.position();
    return end > at ? end - at : 0;
  }
  /// Bytes that the element layout puts here: unsafe when the element (its claimed size) is too short for them.
  void within(std::uint64_t count, std::uint64_t end) const {
    if (count > left(end)) throw Unsafe{};
  }
  /// A size matio allocates from before it reads that many bytes here: they must fit and (checked as they are
  /// consumed, or when the bytes run out) be there.
  void backed(std::uint64_t count, std::uint64_t end) {
    within(count, end);
    backed_end_ = std::max(backed_end_, bytes_.position() + count);
  }
  void read(void* out, std::uint64_t count, std::uint64_t end) {
    within(count, end);
    if (!bytes_.read(out, count)) throw RanOut{};
  }
  void skip(std::uint64_t count, std::uint64_t end) {
    within(count, end);
    if (!bytes_.skip(count)) throw RanOut{};
  }
  std::pair<std::uint32_t, std::uint32_t> tag(std::uint64_t end) {
    unsigned char raw[8];
    read(raw, sizeof raw, end);
    return {word(raw), word(raw + 4)};
  }
  std::uint64_t end_of(std::uint64_t end) const { return end == kNoEnd ? top_bytes_ : end; }

  /// The contents of a miMATRIX element (after its tag) that end at `end`.
  V5Verdict matrix(std::uint64_t end, Kind kind, int depth) {
    end = end_of(end);
    if (depth > kMaxDepth) throw Unsafe{};
    unsigned char flags[16];
    read(flags, sizeof flags, end);
    const std::uint32_t flags_type = word(flags);
    if (flags_type != kUint32 && !(flags_type == kInt32 && kind == Kind::top && !compressed_)) throw Unsafe{};
    const std::uint32_t class_type = word(flags + 8) & 0xff;
    const std::uint32_t nzmax = word(flags + 12);
    if (class_type == kOpaqueClass) return opaque(end);

    const auto [dims_type, dims_bytes] = tag(end);
    if (dims_type != kInt32 || dims_bytes % 4 != 0) throw Unsafe{};
    backed(padded(dims_bytes), end);
    std::uint64_t elements = 1, columns = 0;
    for (std::uint32_t d = 0; d < dims_bytes / 4; ++d) {
      unsigned char raw[4];
      read(raw, sizeof raw, end);
      elements = product(elements, word(raw));
      if (d == 1) columns = word(raw);
    }
    skip(padded(dims_bytes) - dims_bytes, end);

    const auto [name_type, name_bytes] = tag(end);
    if (name_type == kInt8 && name_bytes > 0) {
      // matio reads the name of a variable and of a cell element, but takes a struct field's as its data.
      if (kind == Kind::field) throw Unsafe{};
      backed(padded(name_bytes), end);
      skip(padded(name_bytes), end);
    }

    switch (class_type) {
      case kStructClass: return structure(end, elements, depth);
      case kCellClass: return elements_of(end, elements, Kind::cell, depth);
      case kFunctionClass:
        if (kind == Kind::top && !compressed_) return elements_of(end, elements, Kind::top, depth);
        return V5Verdict::listable;
      case kSparseClass:
        // matio reads a small sparse field of a compressed struct or cell with its header; nzmax sizes it.
        if (kind != Kind::top && compressed_ && left(end) <= kMatioInflateWindow &&
            (nzmax > left(end) || columns > left(end)))
          throw Unsafe{};
        return V5Verdict::listable;
      default:
        break;
    }
    // Every value takes at least one byte. matio reads a small field of a compressed struct or cell with its
    // header, into elements × (bytes of its class); at the top level it only lists the header.
    if (elements > left(end)) {
      if (kind != Kind::top) {
        if (compressed_ && left(end) <= kMatioInflateWindow) throw Unsafe{};
        return V5Verdict::listable;  // read_matrix checks its size against the file before reading
      }
      return V5Verdict::unreadable;
    }
    return V5Verdict::listable;
  }

  /// An object: matio reads no dimensions in a compressed one; in an uncompressed one it takes the tag where the
  /// dimensions would be and, if that is not an int32 tag, the next 8 bytes as the name tag.
  V5Verdict opaque(std::uint64_t end) {
    if (compressed_) return V5Verdict::listable;
    const auto [type, count] = tag(end);
    if (type == kInt32) {
      backed(padded(count), end);
      return V5Verdict::listable;
    }
    const auto [name_type, name_bytes] = tag(end);
    if (name_type == kInt8) {
      backed(padded(name_bytes), end);
      skip(padded(name_bytes), end);
    }
    return V5Verdict::listable;
  }

  /// A struct's field-name length, its field names, then its elements × fields field elements.
  V5Verdict structure(std::uint64_t end, std::uint64_t elements, int depth) {
    const auto [length_type, name_length] = tag(end);
    if ((length_type & 0xffff) != kInt32 || name_length == 0) throw Unsafe{};
    const auto [names_type, names_bytes] = tag(end);
    std::uint64_t fields = 0;
    if (names_type == kInt8) {
      if (names_bytes % name_length != 0) throw Unsafe{};  // matio would read the rest as the first field
      fields = names_bytes / name_length;
      backed(padded(names_bytes), end);
      skip(padded(names_bytes), end);
    } else if ((names_type & 0xffff) == kInt8 && (names_type >> 16) >= 1 && (names_type >> 16) <= 4) {
      fields = (names_type >> 16) / name_length;
    }
    if (fields == 0) return V5Verdict::listable;
    return elements_of(end, product(elements, fields), Kind::field, depth);
  }

  /// `count` sub-elements, for each of which matio holds a pointer (and a matvar_t): each takes at least its tag.
  V5Verdict elements_of(std::uint64_t end, std::uint64_t count, Kind kind, int depth) {
    backed(product(count, 8), end);
    for (std::uint64_t i = 0; i < count; ++i) {
      const auto [type, bytes] = tag(end);
      if (type != kMatrixType) throw Unsafe{};
      within(bytes, end);
      if (bytes == 0) continue;
      const std::uint64_t sub_end = bytes_.position() + bytes;
      if (matrix(sub_end, kind, depth + 1) == V5Verdict::unsafe) throw Unsafe{};
      skip(left(sub_end), sub_end);
    }
    return V5Verdict::listable;
  }

  ElementBytes& bytes_;
  bool swapped_;
  bool compressed_;
  std::uint64_t top_bytes_ = kNoEnd;
  std::uint64_t backed_end_ = 0;  ///< the bytes up to here back a size matio allocates from
};

}  // namespace

/// The top-level elements of the v5 file `path`, from their tags, in the order matio lists the variables.
std::vector<V5Element> v5_elements(const std::string& path, std::uintmax_t file_bytes) {
  constexpr std::uintmax_t kHeaderBytes = 128, kTagBytes = 8;
  constexpr std::uint32_t kCompressedType = 15;  // miCOMPRESSED
  std::ifstream in(path, std::ios::binary);
  char header[kHeaderBytes];
  if (!in.read(header, sizeof header)) return {};
  std::uint16_t endian_mark;  // 'M' 'I' as one number: 0x4d49 when the file has this machine's byte order
  std::memcpy(&endian_mark, header + 126, sizeof endian_mark);
  const bool swapped = endian_mark != 0x4d49;
  std::vector<V5Element> elements;
  for (std::uintmax_t at = kHeaderBytes; at + kTagBytes <= file_bytes;) {
    std::uint32_t tag[2];
    if (!in.seekg(static_cast<std::streamoff>(at)) || !in.read(reinterpret_cast<char*>(tag), sizeof tag)) break;
    if (swapped) {
      tag[0] = __builtin_bswap32(tag[0]);
      tag[1] = __builtin_bswap32(tag[1]);
    }
    elements.push_back({at + kTagBytes, tag[1], tag[0] == kCompressedType, swapped});
    at += kTagBytes + tag[1];
  }
  return elements;
}

/// True when all of `element` is in the file and, if compressed, its zlib stream is whole. matio checks neither: a
/// variable cut short by a truncated file or a full disk comes back with uninitialised or zero values and no error.
bool v5_element_intact(const std::string& path, const V5Element& element, std::uintmax_t file_bytes) {
  if (element.offset + element.bytes > file_bytes) return false;
  if (!element.compressed) return true;
  std::ifstream in(path, std::ios::binary);
  return in.seekg(static_cast<std::streamoff>(element.offset)) && zlib_stream_complete(in, element.bytes);
}

/// The pre-scan of `element` (V5HeaderScan).
V5Verdict scan_v5_element(const std::string& path, const V5Element& element, std::uintmax_t file_bytes) {
  ElementBytes bytes(path, element, file_bytes);
  V5HeaderScan scan(bytes, element.swapped, element.compressed);
  if (!element.compressed) scan.limit_to(element.bytes);
  return scan.run();
}

}  // namespace dampbench
