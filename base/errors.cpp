#include "errors.h"

#include <cstdio>

namespace omnicam {

namespace {

bool isContinuation(unsigned char byte) { return (byte & 0xC0) == 0x80; }

struct Utf8Lead {
  size_t length;  // bytes in the sequence
  unsigned char low = 0x80, high = 0xBF;  // allowed range of its second byte
};

// What a lead byte announces; length 0 if it cannot start a sequence. The second-byte ranges
// exclude overlong forms, surrogates and code points past U+10FFFF.
Utf8Lead utf8Lead(unsigned char lead) {
  if (lead >= 0xC2 && lead <= 0xDF) return {2};
  if (lead == 0xE0) return {3, 0xA0, 0xBF};
  if (lead == 0xED) return {3, 0x80, 0x9F};
  if (lead >= 0xE1 && lead <= 0xEF) return {3};
  if (lead == 0xF0) return {4, 0x90, 0xBF};
  if (lead == 0xF4) return {4, 0x80, 0x8F};
  if (lead >= 0xF1 && lead <= 0xF3) return {4};
  return {0};
}

// Bytes in the valid UTF-8 sequence at text[at], or 0 if none starts there.
size_t utf8Length(std::string_view text, size_t at) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const Utf8Lead lead = utf8Lead(byte(0));
  if (lead.length == 0 || at + lead.length > text.size() || byte(1) < lead.low || byte(1) > lead.high) return 0;
  for (size_t k = 2; k < lead.length; ++k)
    if (!isContinuation(byte(k))) return 0;
  return lead.length;
}

std::string hexEscape(unsigned char byte) {
  char buf[5];
  std::snprintf(buf, sizeof buf, "\\x%02X", byte);
  return buf;
}

// One character of the output: its text, the input bytes it stands for, and the columns it
// takes (a UTF-8 character one, an escape its length).
struct Piece {
  std::string text;
  size_t bytes, columns;
};

// `quoting`: also escape backslash and double quote (inside quotes), or leave them (oneLine).
Piece nextPiece(std::string_view text, size_t at, bool quoting) {
  const auto ch = static_cast<unsigned char>(text[at]);
  if (ch == '\n') return {"\\n", 1, 2};
  if (ch == '\t') return {"\\t", 1, 2};
  if (ch == '\r') return {"\\r", 1, 2};
  if (quoting && (ch == '\\' || ch == '"')) return {std::string{'\\', static_cast<char>(ch)}, 1, 2};
  if (ch < 0x20 || ch == 0x7F) return {hexEscape(ch), 1, 4};
  if (ch < 0x80) return {std::string(1, static_cast<char>(ch)), 1, 1};
  const size_t length = utf8Length(text, at);
  // C1 controls (U+0080..U+009F, 0xC2 0x80..0x9F) act on terminals like C0 ones.
  const bool c1 = length == 2 && ch == 0xC2 && static_cast<unsigned char>(text[at + 1]) < 0xA0;
  if (length == 0) return {hexEscape(ch), 1, 4};
  if (c1) return {hexEscape(ch) + hexEscape(static_cast<unsigned char>(text[at + 1])), 2, 8};
  return {std::string(text.substr(at, length)), length, 1};
}

// True if oneLine() would change `text` (every escape is longer than the bytes it replaces).
bool needsEscaping(std::string_view text) {
  for (size_t at = 0; at < text.size();) {
    const Piece piece = nextPiece(text, at, false);
    if (piece.text.size() != piece.bytes) return true;
    at += piece.bytes;
  }
  return false;
}

}  // namespace

std::string quote(std::string_view text, size_t maxChars) {
  std::string out = "\"";
  size_t at = 0, columns = 0;
  while (at < text.size()) {
    const Piece piece = nextPiece(text, at, true);
    if (columns + piece.columns > maxChars) break;
    out += piece.text;
    columns += piece.columns;
    at += piece.bytes;
  }
  if (at == text.size()) return out + "\"";
  // Cut whole pieces only: never inside a UTF-8 sequence or an escape.
  return out + "…\" (" + std::to_string(text.size()) + " bytes)";
}

bool isValidUtf8(std::string_view text) {
  for (size_t at = 0; at < text.size();) {
    if (static_cast<unsigned char>(text[at]) < 0x80) {
      ++at;
      continue;
    }
    const size_t length = utf8Length(text, at);
    if (length == 0) return false;
    at += length;
  }
  return true;
}

std::string showPath(std::string_view path) {
  if (path.size() <= kEchoedPathChars && !needsEscaping(path)) return std::string(path);
  return quote(path, kEchoedPathChars);
}

std::string oneLine(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (size_t at = 0; at < message.size();) {
    const Piece piece = nextPiece(message, at, false);
    out += piece.text;
    at += piece.bytes;
  }
  return out;
}

}  // namespace omnicam
