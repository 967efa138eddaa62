#pragma once
// Exceptions for problems in what the user gave ccal (configuration, data files, command line), as opposed
// to programming errors. The CLI catches InputError to print the message without a stack of internals.
#include <concepts>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ccal {

// Anything the user supplied that ccal cannot accept. The message is meant for the user: it names the
// offending item and, where possible, says what would have been accepted.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An InputError at a place in a file: the source's name, the 1-based line and column (0 when not known),
// the item there (a TOML key, a CSV column) and the problem itself; what() is the whole located message.
class LocatedInputError : public InputError {
 public:
  LocatedInputError(const std::string& message, std::string source, int line, int column, std::string item,
                    std::string problem)
      : InputError(message),
        source_(std::move(source)),
        line_(line),
        column_(column),
        item_(std::move(item)),
        problem_(std::move(problem)) {}

  const std::string& source() const noexcept { return source_; }
  int line() const noexcept { return line_; }
  int column() const noexcept { return column_; }
  const std::string& item() const noexcept { return item_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string source_;
  int line_;
  int column_;
  std::string item_;
  std::string problem_;
};

// A quantity or unit that cannot be parsed, has the wrong dimension, or is not a finite number.
class UnitError : public InputError {
 public:
  using InputError::InputError;
};

// The test plan (or a table's data) cannot determine the requested terms: fewer observations than free
// terms, linearly dependent columns, a condition number above the allowed limit, or estimates too correlated
// to separate. terms() names the terms involved (empty where only column numbers are known), so that a front
// end can say what would help (more g-levels for powers of a_i, another mounting for terms in a_p or a_o).
class IllPosedFit : public InputError {
 public:
  explicit IllPosedFit(const std::string& message, std::vector<std::string> terms = {})
      : InputError(message), terms_(std::move(terms)) {}

  const std::vector<std::string>& terms() const noexcept { return terms_; }

 private:
  std::vector<std::string> terms_;
};

// Marks an InputError about an input file that cannot be opened (it does not exist, is a folder or cannot be
// read), so that a front end can give it its own kind: the Python module raises ccal.FileNotFound, a
// FileNotFoundError; the CLI treats it as any InputError (exit 2, the message).
class FileNotFoundMark {
 public:
  virtual ~FileNotFoundMark() = default;
};

// The reader's own error (e.g. CsvError, ConfigError, with its location) for a file it cannot open:
// `throw FileNotFound<CsvError>(name, 0, 0, "", unreadable_file_problem(name))`; caught as the reader's
// error, as an InputError, or as a FileNotFoundMark.
template <class Error>
  requires std::derived_from<Error, InputError>
class FileNotFound : public Error, public FileNotFoundMark {
 public:
  using Error::Error;
};

// Why an input file cannot be opened, and what is accepted, for the message of FileNotFound: "cannot read
// the file: no such file; accepted: …", "… it is a folder; …", "… permission denied; …".
inline std::string unreadable_file_problem(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found || path.empty())
    return "cannot read the file: no such file; accepted: the path of an existing file (check its spelling "
           "and folder)";
  if (status.type() == std::filesystem::file_type::directory)
    return "cannot read the file: it is a folder; accepted: the path of a file";
  return "cannot read the file: permission denied or unreadable; accepted: a file this user may read";
}

}  // namespace ccal
