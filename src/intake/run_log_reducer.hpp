#pragma once
// The one-pass reduction of a run log (docs/model.md §13): rows in, ReducedLog out, the same for a log
// streamed from its file and for a CsvTable in memory, so both give the same bits.
//
// A bad log is refused with the error the whole-table reduction gave before it streamed: that reduction
// checked the time column over all rows first, then the output column, then each encoder column. The first
// problem of each kind is kept while the rows go by (a CSV error, found by the reader, still ends the read at
// once, as parse_csv did before any reduction), and the earliest kind in that order is thrown at the end.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/io/csv_stream.hpp"
#include "ccal/intake/encoder_fit.hpp"
#include "ccal/io/observation_csv.hpp"
#include "plain_decimal_row.hpp"
#include "ccal/intake/run_log.hpp"
#include "run_log_spread.hpp"

namespace ccal::detail {

class LogReducer final : public CsvRowSink {
 public:
  LogReducer(std::string source, const RunLogOptions& options, double planned_rate);
  void header(const std::vector<std::string>& names, int line) override;
  // A units row: each stated unit checked against the one the layout states, or taken as the column's.
  void units(const std::vector<std::string>& units, int line) override;
  void row(const std::string_view* fields, int line) override;
  // A row of plain decimals only ([-]digits[.digits] between commas, scan_plain_decimal, as many as the
  // header has names), read in one pass over its bytes: the usual row of a log. Anything else is declined
  // and comes split to row(); both give the same values, so the same reduction. The rows read are reduced
  // kRowBatch at a time, in their order (before any row that comes to row(), and at the end): reading a row
  // does not wait for the reduction of the one before.
  bool row_line(std::string_view line, int line_no) override;
  // The reduction of the rows seen; throws the log's first problem (CsvError).
  ReducedLog finish();
  // Throws the header's problem when it has no time column (a file's reading stopped by a bad row under a
  // header that is no log's: the header is the problem to report).
  void throw_no_time() const;

 private:
  // The kinds of problem, in the order they are reported.
  enum class Problem {
    no_time,
    time_cell,
    too_few,
    time_order,
    gap,
    span,
    output_columns,
    pulse_weight,
    output_cell,
    counter_wrap,
    mean_overflow,
    theta1_cell,
    theta1_spacing,
    gamma_cell,
    gamma_spacing,
  };
  struct Encoder {
    Encoder(std::size_t column_index, Problem cell_problem, Problem spacing_problem, int harmonic_order)
        : column(column_index), cell(cell_problem), spacing(spacing_problem), fit(harmonic_order) {}
    std::size_t column = 0;
    Problem cell, spacing;
    EncoderFit fit;
    double unwrapped = 0;  // the last sample's unwrapped angle [rad]
    double raw = 0;        // and its reading [rad]
    double tau = 0;        // and its time from the first sample [s]
    double first_unwrapped = 0, first_tau = 0;  // the first sample's (a gap is bridged at their mean rate)
    // The sample before it (for the wild-reading check), and how many samples were added (0, 1, 2 or more).
    double earlier_unwrapped = 0, earlier_tau = 0;
    int seen = 0;
    // Wild readings (left out of the fit): how many, and the first's error.
    std::size_t wild = 0;
    std::optional<CsvError> first_wild;
  };

  void defer(Problem kind, CsvError error);
  void throw_pending_before(Problem kind) const;
  CsvError cell_error(std::size_t column, int line, std::string problem) const;
  // A cell's number: a plain decimal read here (the usual cell of a log, kept inline), anything else by
  // cell_general.
  std::optional<double> cell(const std::string_view* fields, std::size_t column, Problem kind, int line) {
    double value = 0;
    if (parse_plain_decimal(fields[column], value)) return value;
    return cell_general(fields, column, kind, line);
  }
  [[gnu::noinline]] std::optional<double> cell_general(const std::string_view* fields, std::size_t column,
                                                       Problem kind, int line);
  // A timestamp of the time column (columns.iso_time): seconds from the log's first.
  std::optional<double> iso_time_cell(std::string_view field, int line);
  [[gnu::cold, gnu::noinline]] void note_gap(double step, int line);
  // A step longer than gap_threshold_ (a gap: true when bridged) or shorter than min_step_ (the new shortest).
  [[gnu::cold, gnu::noinline]] bool unusual_step(double step, int line);
  [[gnu::cold, gnu::noinline]] bool bridge_gap(Encoder& e, double a, double tau, int line);
  // The row's reduction, its cells read by `cells(column, kind, line)` (an optional<double>, empty for a
  // refused cell): the split fields of row() or the values row_line() read.
  // The problems a row can show, written out off the rows' path (cold: the usual row has none).
  [[gnu::cold, gnu::noinline]] void defer_time_order(int line, double t);
  [[gnu::cold, gnu::noinline]] void defer_count(int line, double value, std::string problem);
  // The count of a pulses column, unwrapped (counter_bits) or checked for a wrap that was not declared.
  void count_sample(double value, int line, double step_time);
  // A step of an undeclared counter's count, against its direction: a wrap, or with the step before or after
  // it that undoes it, one wild count (run_log_spread.cpp).
  void check_count_step(double step, double value, int line);
  // The step held back by check_count_step, given the step that follows it (none: the log ended).
  void settle_count_wrap(std::optional<double> next_step);
  // Throws the output's one wild sample, or the count's one wild step (run_log_spread.cpp).
  void throw_wild_output() const;
  [[gnu::cold, gnu::noinline]] void defer_spacing(const Encoder& e, int line, double step_time);
  [[gnu::cold, gnu::noinline]] void note_wild(Encoder& e, int line, double departure, double limit);
  void throw_wild(const Encoder& e) const;
  void reduce_batch();
  template <class Cells>
  void reduce_row(const Cells& cells, int line);
  template <class Cells>
  void encoder_sample(Encoder& e, const Cells& cells, int line, bool time_ok, double t);
  template <class Cells>
  [[gnu::cold, gnu::noinline]] void bridge_encoders(const Cells& cells, int line, double t);

  std::string source_;
  RunLogOptions options_;
  double planned_rate_;
  std::vector<std::string> header_;
  PlainDecimalRowReader row_reader_;
  // Rows read by row_line and not yet reduced: their values (one per column) and lines.
  static constexpr std::size_t kRowBatch = 64;
  std::vector<double> batch_values_;
  int batch_lines_[kRowBatch] = {};
  std::size_t batch_rows_ = 0;
  int header_line_ = 0;
  std::size_t time_ = 0;
  std::optional<std::size_t> output_;  // the pulses or output column, when exactly one and usable
  bool pulses_ = false;
  std::optional<Encoder> theta1_, gamma_;
  std::optional<Problem> pending_kind_;
  std::optional<CsvError> pending_;

  std::size_t rows_ = 0;
  int last_line_ = 0;
  bool have_previous_time_ = false;
  double t_first_ = 0, t_previous_ = 0;
  double output_first_ = 0, output_previous_ = 0, integral_ = 0;
  double count_raw_ = 0;         // the last count as read (before unwrapping)
  double count_travel_ = 0;      // Σ |step| of the count
  std::size_t count_steps_ = 0;  // steps summed
  // A count's last step and its line; a step against the count's direction held back until the next one.
  struct CountStep {
    double step = 0, value = 0;  // the step to this count, and the count
    int line = 0;
  };
  CountStep last_count_step_;
  std::optional<CountStep> held_wrap_;
  std::optional<std::int64_t> iso_first_;  // the first timestamp [ns]
  bool iso_zoned_ = false;                 // it states its zone (every other must then, and none if not)
  int iso_first_line_ = 0;
  std::string_view iso_field_;             // the row's timestamp as written (valid while its row is reduced)
  double bridge_count_ = 0;  // the count's step expected over a bridged gap (at its mean rate), else 0
  // Gaps: the shortest step between samples so far, and the steps of more than 1.5 times it.
  double min_step_ = std::numeric_limits<double>::infinity();
  double gap_threshold_ = std::numeric_limits<double>::infinity();  // a longer step is a gap
  std::size_t gaps_ = 0;
  double gap_time_ = 0, longest_gap_ = 0;
  double first_step_ = 0;  // the first step between samples (0: none yet)
  SampleSpread spread_;     // the output's samples, or the count's step rates [counts/s]
  double output_resolution_ = std::numeric_limits<double>::infinity();  // the least change between samples
};

}  // namespace ccal::detail
