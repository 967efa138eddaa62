#pragma once
// The document information of a printed page (ISO 32000-1 §14.3.3: Title, Author, Subject, Keywords, Creator
// and the dates), set by an incremental update of the PDF (§7.5.6): a new information dictionary, an xref
// section for it and a trailer that points back to the browser's. The browser sets the title only; the page
// states the rest in its <head> (<meta name="author">, "description", "keywords", "generator",
// "dcterms.created").
#include <string>
#include <string_view>

namespace ccal {

struct PdfInfo {
  std::string title, author, subject, keywords, creator;
  std::string
      date_utc;  // ISO 8601 UTC, YYYY-MM-DDTHH:MM:SSZ: CreationDate and ModDate; "" keeps the browser's
  bool operator==(const PdfInfo&) const = default;
};

// What the page states: its <title> and its <meta name=… content=…> elements, entities decoded.
PdfInfo pdf_info_of_page(std::string_view html);

// The PDF with `info` as its document information (an empty field is left out), appended as an incremental
// update; the bytes before are kept as they are. InputError for a PDF without a classic trailer (an xref
// stream): the browser's has one.
std::string with_pdf_info(std::string pdf, const PdfInfo& info);

// A text as a PDF string: (literal) for printable ASCII, with ( ) \ escaped; else <FEFF…> UTF-16BE in hex.
std::string pdf_text_string(std::string_view utf8);

}  // namespace ccal
