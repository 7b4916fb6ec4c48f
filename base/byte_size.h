// Byte sizes written by people: "512MiB", "8GiB", "1.5KiB", "4096".
//
// Implements: the one parser of the byte sizes that options and files give (--memory-budget, the byte
// forms of mta render's --budget): a decimal number (digits, an optional fraction and exponent) and an
// optional binary unit, B, KiB, MiB, GiB or TiB (k, M, G, T are accepted as short forms of the same binary
// units). A whole number is multiplied exactly; a fractional one is scaled in double precision and
// truncated to whole bytes. Every result is overflow-checked: no input wraps around or converts out of
// range.
// Does not implement: decimal units (KB, MB: ambiguous, refused), signs, NaN or infinities, or the range a
// caller needs beyond "fits in 64 bits" (zero is returned as zero; the caller decides whether it is
// allowed). The inverse, for messages, is formatBytes (resource_limits.h).
#pragma once

#include <cstdint>
#include <string_view>

namespace tessera {

// Whether `unit` is one of the units above ("" counts: plain bytes).
bool isByteUnit(std::string_view unit);

// The number of bytes `text` describes. Throws Error "<what> '<text>': <reason>": not a number, an
// unknown unit, or more than 2^64 - 1 bytes.
uint64_t parseByteSize(std::string_view text, std::string_view what);

}  // namespace tessera
