#pragma once
// An HTML page printed to PDF by a headless Chromium (the browser the page is made for: its charts are drawn by
// scripts, its print layout is CSS paged media, A4 with the page count at the foot). The page is printed from a
// private temporary folder with the network refused, and the PDF's bytes are returned: the caller writes them
// where it wants, atomically, as every output of ccal is written.
#include <string>
#include <string_view>

namespace ccal {

struct PdfPrintOptions {
  // The browser's program: a path, or a name looked up in PATH. Empty: the environment's CCAL_CHROMIUM, else
  // the first of chromium, chromium-browser, google-chrome-stable, google-chrome found in PATH.
  std::string browser;
  double timeout_s = 180;  // the browser is stopped after this long and the print refused
};

// The browser that print_pdf would run (a path), or empty if there is none.
std::string find_pdf_browser(const PdfPrintOptions& options = {});
// The same, or InputError saying which browser is missing and how to install one: a front end's check before
// a long computation whose result it will print.
std::string require_pdf_browser(const PdfPrintOptions& options = {});

// The page printed to PDF: its bytes (they begin "%PDF-"). InputError when no browser is found (saying how to
// install one), when the browser fails or times out (with the end of what it wrote on its error stream), or
// when it writes no PDF.
std::string print_pdf(std::string_view html, const PdfPrintOptions& options = {});

}  // namespace ccal
