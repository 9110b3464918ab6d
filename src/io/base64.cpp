// Base64 encoder and strict decoder.
#include "particula/io/base64.hpp"

#include <array>
#include <cstdint>

#include "particula/io/error.hpp"

namespace particula::io {
namespace {

constexpr std::string_view kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Maps a character to its 6-bit value; -1 for characters outside the alphabet.
constexpr std::array<std::int8_t, 256> make_decode_table() {
  std::array<std::int8_t, 256> t{};
  for (auto& v : t) v = -1;
  for (std::size_t i = 0; i < kAlphabet.size(); ++i) t[static_cast<unsigned char>(kAlphabet[i])] = i;
  return t;
}
constexpr auto kDecode = make_decode_table();

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

}  // namespace

void base64_append(std::string& out, std::string_view bytes) {
  const std::size_t old_size = out.size();
  out.resize(old_size + (bytes.size() + 2) / 3 * 4);
  char* o = out.data() + old_size;
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3, o += 4) {
    const std::uint32_t v = (b[i] << 16) | (b[i + 1] << 8) | b[i + 2];
    o[0] = kAlphabet[(v >> 18) & 63];
    o[1] = kAlphabet[(v >> 12) & 63];
    o[2] = kAlphabet[(v >> 6) & 63];
    o[3] = kAlphabet[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest == 0) return;
  const std::uint32_t v = (b[i] << 16) | (rest == 2 ? b[i + 1] << 8 : 0);
  o[0] = kAlphabet[(v >> 18) & 63];
  o[1] = kAlphabet[(v >> 12) & 63];
  o[2] = rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
  o[3] = '=';
}

std::string base64_encode(std::string_view bytes) {
  std::string out;
  base64_append(out, bytes);
  return out;
}

std::string base64_decode(std::string_view text) {
  std::string out;
  out.reserve(text.size() / 4 * 3);
  std::uint32_t acc = 0;  // bits collected so far
  int nbits = 0, nchars = 0, npad = 0;
  for (const char c : text) {
    if (is_space(c)) continue;
    ++nchars;
    if (c == '=') {
      ++npad;
      continue;
    }
    const int v = kDecode[static_cast<unsigned char>(c)];
    if (v < 0) throw IoError("invalid character in base64 data");
    if (npad > 0) throw IoError("base64 padding before the end of the data");
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    nbits += 6;
    if (nbits >= 8) {
      nbits -= 8;
      out += static_cast<char>((acc >> nbits) & 0xFF);
    }
  }
  if (nchars % 4 != 0 || npad > 2 || (npad > 0 && (nchars - npad) % 4 + npad != 4))
    throw IoError("base64 data has an invalid length");
  return out;
}

}  // namespace particula::io
