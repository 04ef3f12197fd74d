// zlib inflate of a whole in-memory gzip file (see gzip.h for why the cap).
#include "io/gzip.h"

#include <zlib.h>

#include <algorithm>
#include <limits>

#include "intrinsic/error.h"

namespace intrinsic::io {

bool is_gzip(const std::string& bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

namespace {

struct InflateStream {
  z_stream zs{};
  bool live = false;
  ~InflateStream() {
    if (live) inflateEnd(&zs);
  }
};

std::string size_text(std::uint64_t bytes) {
  if (bytes >= (1ull << 30)) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (1ull << 20)) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string gunzip(const std::string& bytes, const std::string& name, std::uint64_t max_bytes) {
  // The trailer's ISIZE (size mod 4 GiB) of the last member is a good first
  // guess for the output size; it is only a hint, so it is capped and the
  // buffer still grows if the data says otherwise.
  // Damaged data can claim any ISIZE, so the guess is also bounded by deflate's
  // best ratio (about 1032:1) and by 1 GiB.
  std::uint64_t guess = std::uint64_t(bytes.size()) * 4;
  if (bytes.size() >= 18) {
    const auto* t = reinterpret_cast<const unsigned char*>(bytes.data() + bytes.size() - 4);
    std::uint64_t isize = t[0] | (t[1] << 8) | (t[2] << 16) | (std::uint64_t(t[3]) << 24);
    if (isize >= bytes.size()) guess = std::min<std::uint64_t>(isize, std::uint64_t(bytes.size()) * 1032);
  }
  guess = std::min<std::uint64_t>({guess + 64, max_bytes + 1, std::uint64_t(1) << 30});

  std::string out;
  out.resize(static_cast<std::size_t>(guess));
  std::size_t produced = 0;
  std::size_t consumed = 0;

  while (consumed < bytes.size()) {
    if (consumed > 0 && bytes.size() - consumed < 2) break;
    if (consumed > 0 && !is_gzip(bytes.substr(consumed, 2))) {
      // Trailing garbage after a complete member: gzip(1) warns and ignores
      // it; zero padding from tape-style writers is common enough.
      break;
    }
    InflateStream s;
    if (inflateInit2(&s.zs, 15 + 16) != Z_OK) throw_input(name + ": cannot initialise zlib");
    s.live = true;
    s.zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + consumed));
    std::size_t in_left = bytes.size() - consumed;
    int ret = Z_OK;
    while (true) {
      if (produced == out.size()) {
        if (out.size() > max_bytes)
          throw_input(name + ": decompressed data exceeds the limit of " + size_text(max_bytes) +
                      " (refusing a possible gzip bomb)");
        std::uint64_t grown = std::min<std::uint64_t>(std::uint64_t(out.size()) * 2 + 4096, max_bytes + 1);
        out.resize(static_cast<std::size_t>(grown));
      }
      const uInt chunk_in = static_cast<uInt>(std::min<std::size_t>(in_left, std::numeric_limits<uInt>::max()));
      const uInt chunk_out = static_cast<uInt>(
          std::min<std::size_t>(out.size() - produced, std::numeric_limits<uInt>::max()));
      s.zs.avail_in = chunk_in;
      s.zs.next_out = reinterpret_cast<Bytef*>(&out[produced]);
      s.zs.avail_out = chunk_out;
      ret = inflate(&s.zs, Z_NO_FLUSH);
      in_left -= chunk_in - s.zs.avail_in;
      produced += chunk_out - s.zs.avail_out;
      if (ret == Z_STREAM_END) break;
      if (ret == Z_BUF_ERROR && s.zs.avail_out != 0) {
        throw_input(name + ": truncated gzip data (compressed stream ends early)");
      }
      if (ret != Z_OK && ret != Z_BUF_ERROR) {
        std::string why = s.zs.msg ? s.zs.msg : "error " + std::to_string(ret);
        throw_input(name + ": corrupt gzip data (" + why + ") at compressed byte " +
                    std::to_string(bytes.size() - in_left));
      }
      if (in_left == 0 && s.zs.avail_out != 0) throw_input(name + ": truncated gzip data");
    }
    consumed = bytes.size() - in_left;
  }
  if (produced > max_bytes)
    throw_input(name + ": decompressed data exceeds the limit of " + size_text(max_bytes) +
                " (refusing a possible gzip bomb)");
  out.resize(produced);
  return out;
}

}  // namespace intrinsic::io
