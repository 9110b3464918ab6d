// Base64 (RFC 4648, standard alphabet, '=' padding) for VTK's inline binary data.
#pragma once

#include <string>
#include <string_view>

namespace particula::io {

/// Appends the base64 encoding of `bytes` to `out`.
void base64_append(std::string& out, std::string_view bytes);

/// The base64 encoding of `bytes`.
std::string base64_encode(std::string_view bytes);

/// Decodes base64 text, ignoring ASCII whitespace. Padding is only accepted at the end.
/// Throws IoError (without a file name) on any character outside the alphabet or a bad length.
std::string base64_decode(std::string_view text);

}  // namespace particula::io
