#include "ccal/render/pdf_info.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdint>

#include "ccal/core/errors.hpp"

namespace ccal {
namespace {

// The text of HTML element content or of a quoted attribute, its entities decoded (the ones the pages write:
// &amp; &lt; &gt; &quot; &#39;, and numeric ones).
std::string html_text(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    const std::size_t end = s.find(';', i);
    if (end == std::string_view::npos) {
      out += s[i];
      continue;
    }
    const std::string_view name = s.substr(i + 1, end - i - 1);
    std::uint32_t code = 0;
    if (name == "amp")
      code = '&';
    else if (name == "lt")
      code = '<';
    else if (name == "gt")
      code = '>';
    else if (name == "quot")
      code = '"';
    else if (name == "apos")
      code = '\'';
    else if (name.size() > 1 && name[0] == '#') {
      const bool hex = name[1] == 'x' || name[1] == 'X';
      const std::string_view digits = name.substr(hex ? 2 : 1);
      std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
    }
    if (code == 0 || code > 0x10FFFF) {
      out += s[i];
      continue;
    }
    // UTF-8 of the code point
    if (code < 0x80) {
      out += char(code);
    } else if (code < 0x800) {
      out += char(0xC0 | (code >> 6));
      out += char(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += char(0xE0 | (code >> 12));
      out += char(0x80 | ((code >> 6) & 0x3F));
      out += char(0x80 | (code & 0x3F));
    } else {
      out += char(0xF0 | (code >> 18));
      out += char(0x80 | ((code >> 12) & 0x3F));
      out += char(0x80 | ((code >> 6) & 0x3F));
      out += char(0x80 | (code & 0x3F));
    }
    i = end;
  }
  return out;
}

// The content of <meta name="NAME" content="…"> as the pages write it ("" when there is none).
std::string meta(std::string_view html, std::string_view name) {
  const std::string open = fmt::format("<meta name=\"{}\" content=\"", name);
  const std::size_t at = html.find(open);
  if (at == std::string_view::npos) return {};
  const std::size_t from = at + open.size(), end = html.find('"', from);
  return end == std::string_view::npos ? std::string() : html_text(html.substr(from, end - from));
}

// The code points of UTF-8 text (a malformed byte read as U+FFFD).
std::u32string code_points(std::string_view s) {
  std::u32string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    const int n = b < 0x80 ? 1 : (b >> 5) == 6 ? 2 : (b >> 4) == 14 ? 3 : (b >> 3) == 30 ? 4 : 0;
    if (n == 0 || i + std::size_t(n) > s.size()) {
      out += U'\uFFFD';
      ++i;
      continue;
    }
    char32_t c = n == 1 ? b : n == 2 ? b & 0x1F : n == 3 ? b & 0x0F : b & 0x07;
    for (int k = 1; k < n; ++k) c = (c << 6) | (static_cast<unsigned char>(s[i + std::size_t(k)]) & 0x3F);
    out += c;
    i += std::size_t(n);
  }
  return out;
}

// D:YYYYMMDDHHmmSSZ from YYYY-MM-DDTHH:MM:SSZ (ISO 32000-1 §7.9.4).
std::string pdf_date(std::string_view iso) {
  std::string digits;
  for (const char c : iso)
    if (c >= '0' && c <= '9') digits += c;
  if (digits.size() != 14 || iso.size() != 20 || iso.back() != 'Z')
    throw InputError(fmt::format("the page's date '{}' is not written YYYY-MM-DDTHH:MM:SSZ", iso));
  return "D:" + digits + "Z";
}

// The number after `key` in a dictionary's text ("/Size 4668" → 4668), or -1.
long long number_after(std::string_view text, std::string_view key) {
  const std::size_t at = text.find(key);
  if (at == std::string_view::npos) return -1;
  std::size_t from = at + key.size();
  while (from < text.size() && (text[from] == ' ' || text[from] == '\n' || text[from] == '\r')) ++from;
  long long v = -1;
  std::from_chars(text.data() + from, text.data() + text.size(), v);
  return v;
}

}  // namespace

PdfInfo pdf_info_of_page(std::string_view html) {
  PdfInfo info;
  if (const std::size_t at = html.find("<title>"); at != std::string_view::npos) {
    const std::size_t end = html.find("</title>", at);
    if (end != std::string_view::npos) info.title = html_text(html.substr(at + 7, end - at - 7));
  }
  info.author = meta(html, "author");
  info.subject = meta(html, "description");
  info.keywords = meta(html, "keywords");
  info.creator = meta(html, "generator");
  info.date_utc = meta(html, "dcterms.created");
  return info;
}

std::string pdf_text_string(std::string_view utf8) {
  bool ascii = true;
  for (const char c : utf8) ascii = ascii && c >= 0x20 && c < 0x7F;
  if (ascii) {
    std::string out = "(";
    for (const char c : utf8) {
      if (c == '(' || c == ')' || c == '\\') out += '\\';
      out += c;
    }
    return out + ")";
  }
  std::string out = "<FEFF";
  for (const char32_t c : code_points(utf8)) {
    if (c < 0x10000) {
      out += fmt::format("{:04X}", std::uint32_t(c));
    } else {  // a surrogate pair
      const std::uint32_t v = std::uint32_t(c) - 0x10000;
      out += fmt::format("{:04X}{:04X}", 0xD800 + (v >> 10), 0xDC00 + (v & 0x3FF));
    }
  }
  return out + ">";
}

std::string with_pdf_info(std::string pdf, const PdfInfo& info) {
  const std::size_t startxref = pdf.rfind("startxref");
  const std::size_t trailer = pdf.rfind("trailer", startxref);
  if (startxref == std::string::npos || trailer == std::string::npos)
    throw InputError(
        "the browser's PDF has no classic trailer to update (an xref stream); its information "
        "dictionary cannot be set");
  const std::string_view tail = std::string_view(pdf).substr(trailer, startxref - trailer);
  const long long size = number_after(tail, "/Size"), root = number_after(tail, "/Root"),
                  previous = number_after(std::string_view(pdf).substr(startxref), "startxref");
  if (size <= 0 || root <= 0 || previous <= 0)
    throw InputError(
        "the browser's PDF trailer has no /Size, /Root or startxref; its information dictionary "
        "cannot be set");
  const std::size_t root_at = tail.find("/Root");
  std::string root_ref(tail.substr(root_at + 5, tail.find('R', root_at + 5) - root_at - 5 + 1));
  while (!root_ref.empty() && (root_ref.front() == ' ' || root_ref.front() == '\n')) root_ref.erase(0, 1);

  std::string dict = "<<";
  for (const auto& [key, value] : {std::pair<const char*, const std::string&>{"Title", info.title},
                                   {"Author", info.author},
                                   {"Subject", info.subject},
                                   {"Keywords", info.keywords},
                                   {"Creator", info.creator}})
    if (!value.empty()) dict += fmt::format("/{} {}\n", key, pdf_text_string(value));
  if (!info.date_utc.empty()) {
    const std::string d = pdf_date(info.date_utc);
    dict += fmt::format("/CreationDate ({0})\n/ModDate ({0})\n", d);
  }
  dict += ">>";

  if (pdf.empty() || pdf.back() != '\n') pdf += '\n';
  const std::size_t object_at = pdf.size();
  pdf += fmt::format("{} 0 obj\n{}\nendobj\n", size, dict);
  const std::size_t xref_at = pdf.size();
  // One subsection of one entry: 10-digit offset, 5-digit generation, "n", a two-character end of line.
  pdf += fmt::format(
      "xref\n{} 1\n{:010} 00000 n \ntrailer\n<</Size {}\n/Root {}\n/Info {} 0 R\n/Prev {}>>\n"
      "startxref\n{}\n%%EOF\n",
      size, object_at, size + 1, root_ref, size, previous, xref_at);
  return pdf;
}

}  // namespace ccal
