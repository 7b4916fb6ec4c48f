// Text into HTML: the one escape every report page uses (compare, crosscheck, stability, mutants, the
// demo's index.html), so that a scene name, a path or an error message can never break a page.
//
// Implements: escaping of & < > " (enough for element text and double-quoted attribute values).
// Does not implement: escaping for <script> contents (report_html.cpp's scriptSafe does that) or URLs.
#pragma once

#include <string>
#include <string_view>

namespace tessera::verify {

inline std::string escapeHtml(std::string_view s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

}  // namespace tessera::verify
