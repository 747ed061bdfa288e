#pragma once
// Text spliced into generated HTML reports, JUnit XML and shell scripts or command lines is escaped
// here: names come from users' scenes and specs.
#include <string>

namespace omnicam {

// &, <, >, " and ' as entities; control characters other than tab and newline dropped (XML 1.0
// forbids them).
inline std::string escapeMarkup(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default:
        if (static_cast<unsigned char>(ch) >= 0x20 || ch == '\t' || ch == '\n') out += ch;
    }
  }
  return out;
}

// A relative file path as a URL path for href/src: every byte but letters, digits, "-._~" and '/'
// percent-encoded, so that '#', '%', '?' and spaces in a user's folder name stay part of the path.
// Pass the result through escapeMarkup too (it is then free of markup characters anyway).
inline std::string urlPath(const std::string& path) {
  static const char* const kHex = "0123456789ABCDEF";
  std::string out;
  for (char ch : path) {
    const auto byte = static_cast<unsigned char>(ch);
    const bool plain = (byte >= 'A' && byte <= 'Z') || (byte >= 'a' && byte <= 'z') || (byte >= '0' && byte <= '9') ||
                       ch == '-' || ch == '.' || ch == '_' || ch == '~' || ch == '/';
    if (plain) out += ch;
    else (out += '%', out += kHex[byte >> 4], out += kHex[byte & 15]);
  }
  return out;
}

// A POSIX shell word in single quotes: nothing inside is special; a quote is closed, escaped and
// reopened.
inline std::string shellQuote(const std::string& text) {
  std::string out = "'";
  for (char ch : text) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

// `text` as a shell word to paste: as it is when it holds nothing the shell treats specially,
// shellQuote'd otherwise. (A word that starts with '-' is an option to most commands, quoted or
// not: a path should then be given as ./-name.)
inline std::string shellWord(const std::string& text) {
  const bool plain = !text.empty() && text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./-+,:@=") ==
                                          std::string::npos;
  return plain ? text : shellQuote(text);
}

// A path as a shell word to paste: shellWord, with "./" before a path that starts with '-' so
// that no command takes it for an option.
inline std::string shellPath(const std::string& path) { return shellWord(!path.empty() && path[0] == '-' ? "./" + path : path); }

}  // namespace omnicam
