#include "run_log_reducer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "ccal/core/units.hpp"
#include "ccal/intake/iso_time.hpp"
#include "plain_decimal_row.hpp"

namespace ccal::detail {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

double wrapped(double angle) {
  const double a = std::fmod(angle, kTwoPi);
  return a < 0 ? a + kTwoPi : a;
}

// The main-axis encoder's line fit: its rate, its start phase, its residual and its harmonics. A count
// latched down stands for the middle of its count (angle_offset): a constant added to every reading moves the
// line's phases by it, and its harmonics not at all (their phase by k·offset, below 1e-6 rad for half a count
// of any encoder of 2^22 counts or more), so it is added to the phases here.
void add_theta1_fit(const EncoderFitResult& f, double angle_offset, ReducedLog& r) {
  r.has_theta1 = true;
  r.theta1_rate = f.slope;
  r.theta1_start = wrapped(f.start + angle_offset);
  r.theta1_rms = f.rms;
  r.theta1_harmonics = f.harmonics;
  r.theta1_harmonic_sigma = f.harmonic_sigma;
}

// The platform encoder's line fit, likewise, with its end phase.
void add_gamma_fit(const EncoderFitResult& f, double angle_offset, ReducedLog& r) {
  r.has_gamma = true;
  r.gamma_rate = f.slope;
  r.gamma_start = wrapped(f.start + angle_offset);
  r.gamma_end = wrapped(f.end + angle_offset);
  r.gamma_rms = f.rms;
  r.gamma_harmonics = f.harmonics;
  r.gamma_harmonic_sigma = f.harmonic_sigma;
}

}  // namespace

LogReducer::LogReducer(std::string source, const RunLogOptions& options, double planned_rate)
    : source_(std::move(source)), options_(options), planned_rate_(planned_rate) {
  if (options_.max_gap > 0) gap_threshold_ = options_.max_gap;  // the first step too
}

void LogReducer::defer(Problem kind, CsvError error) {
  if (pending_kind_ && *pending_kind_ <= kind) return;  // an earlier kind, or the first of this kind, stays
  pending_kind_ = kind;
  pending_.emplace(std::move(error));
}

void LogReducer::throw_no_time() const {
  if (pending_kind_ == Problem::no_time) throw *pending_;
}

void LogReducer::throw_pending_before(Problem kind) const {
  if (pending_kind_ && *pending_kind_ <= kind) throw *pending_;
}

CsvError LogReducer::cell_error(std::size_t column, int line, std::string problem) const {
  return CsvError(source_, line, int(column + 1), header_[column], std::move(problem));
}

void LogReducer::header(const std::vector<std::string>& names, int line) {
  header_ = names;
  header_line_ = line;
  batch_values_.assign(kRowBatch * header_.size(), 0.0);
  auto find = [&](std::string_view name) -> std::optional<std::size_t> {
    for (std::size_t k = 0; k < header_.size(); ++k)
      if (header_[k] == name) return k;
    return std::nullopt;
  };
  const LogColumns& c = options_.columns;
  const auto time = find(c.time);
  if (!time) {
    // A header that names none of a log's columns is likely no header: a preamble's line, or the first line
    // of a file in another layout.
    bool none = true;
    for (const std::string* name : {&c.time, &c.pulses, &c.output, &c.theta1, &c.gamma}) none = none && !find(*name);
    const CsvFormat& f = options_.format;
    defer(Problem::no_time,
          CsvError(source_, header_line_, 0, c.time,
                   none && f.header_line == 0 && f.skip_lines == 0
                       ? fmt::format("no such column: the header, line {} ('{}'), names none of a log's columns: a "
                                     "preamble above it? accepted: header_line or skip_lines in the [format] table "
                                     "of the manifest or of the layout file",
                                     header_line_, fmt::join(header_, ","))
                       : fmt::format("no such column (needed by every run log); accepted: one of the columns {}",
                                     fmt::join(header_, ", "))));
  }
  time_ = time.value_or(0);
  const auto pulses = find(c.pulses), output = find(c.output);
  if (pulses.has_value() == output.has_value()) {
    defer(Problem::output_columns,
          CsvError(source_, header_line_, 0, pulses ? c.pulses : c.output,
                   pulses ? fmt::format("both '{}' and '{}' columns; accepted: exactly one of them", c.pulses,
                                        c.output)
                          : fmt::format("no output column; accepted: '{}' (cumulative count) or '{}' "
                                        "(the instrument's output); the columns are {}",
                                        c.pulses, c.output, fmt::join(header_, ", "))));
  } else if (pulses && !(options_.pulse_weight > 0)) {
    defer(Problem::pulse_weight,
          CsvError(source_, header_line_, int(*pulses + 1), c.pulses,
                   "a pulse count needs the pulse weight (the instrument's quantum, or the pulse_weight option); "
                   "accepted: a positive integrated output per pulse"));
  } else {
    output_ = pulses ? pulses : output;
    pulses_ = pulses.has_value();
  }
  const int order = options_.harmonic_order;
  if (const auto k = find(c.theta1))
    theta1_.emplace(*k, Problem::theta1_cell, Problem::theta1_spacing, order);
  if (const auto k = find(c.gamma))
    gamma_.emplace(*k, Problem::gamma_cell, Problem::gamma_spacing, order);
}

std::optional<double> LogReducer::cell_general(const std::string_view* fields, std::size_t column,
                                               Problem kind, int line) {
  // The fields come trimmed: a number with an exponent is read directly; anything else (a '+', blanks) by
  // parse_number, which accepts the same numbers.
  const std::string_view f = fields[column];
  double value = 0;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), value);
  if (ec == std::errc{} && end == f.data() + f.size() && std::isfinite(value)) return value;
  if (const std::optional<double> v = parse_number(f)) return v;
  // In a file of another delimiter a comma in a cell comes as that delimiter (csv_stream.hpp): shown as written.
  const CsvFormat& format = options_.format;
  if (format.delimiter != ',' && format.decimal == '.' &&
      f.find(format.delimiter) != std::string_view::npos) {
    std::string written(f);
    std::replace(written.begin(), written.end(), format.delimiter, ',');
    defer(kind, cell_error(column, line,
                           fmt::format("'{}' is not a number: a decimal comma? accepted: decimal = \"comma\" in "
                                       "the [format] table, or numbers with a decimal point",
                                       written)));
    return std::nullopt;
  }
  defer(kind, cell_error(column, line, number_cell_problem(fields[column])));
  return std::nullopt;
}

std::optional<double> LogReducer::iso_time_cell(std::string_view field, int line) {
  std::string problem;
  const std::optional<IsoTimestamp> stamp = parse_iso8601(field, &problem);
  if (!stamp) {
    defer(Problem::time_cell, cell_error(time_, line, fmt::format("'{}' is not a timestamp: {}; accepted: {} "
                                                                  "(time_unit = \"iso8601\")",
                                                                  field, problem, kIso8601Accepted)));
    return std::nullopt;
  }
  iso_field_ = field;
  if (!iso_first_) {
    iso_first_ = stamp->ns;
    iso_zoned_ = stamp->zoned;
    iso_first_line_ = line;
  } else if (stamp->zoned != iso_zoned_) {
    // One timestamp with its zone and another without: the one without is in a zone nobody stated, so the
    // time between them is not known (an hour off, or more).
    defer(Problem::time_cell,
          cell_error(time_, line,
                     fmt::format("'{}' states {} zone, the log's first timestamp (line {}) {}: the time between "
                                 "them is not known; accepted: every timestamp of a log with its zone ('Z' or an "
                                 "offset such as +01:00), or none",
                                 field, stamp->zoned ? "its" : "no", iso_first_line_,
                                 iso_zoned_ ? "does" : "none")));
    return std::nullopt;
  }
  return double(stamp->ns - *iso_first_) * 1e-9;  // exact to the ns from the first sample: no epoch in the sum
}

bool LogReducer::unusual_step(double step, int line) {
  if (!(first_step_ > 0)) first_step_ = step;  // the first step is always unusual (min_step_ starts at ∞)
  if (step > gap_threshold_) {
    note_gap(step, line);
    return options_.max_gap > 0;
  }
  if (step > 0 && step < min_step_) {  // (a step ≤ 0 is refused as times not increasing)
    min_step_ = step;
    gap_threshold_ = options_.max_gap > 0 ? std::min(1.5 * step, options_.max_gap) : 1.5 * step;
  }
  return false;
}

void LogReducer::note_gap(double step, int line) {
  ++gaps_;
  gap_time_ += step;
  longest_gap_ = std::max(longest_gap_, step);
  if (options_.max_gap > 0 && step > options_.max_gap)
    defer(Problem::gap,
          cell_error(time_, line,
                     fmt::format("a gap of {:.6g} s after the sample at {:.6g} s (from the log's first); accepted: "
                                 "at most max_gap = {:.6g} s (the [format] table)",
                                 step, t_previous_ - t_first_, options_.max_gap)));
}

namespace {

bool pulse_unit(std::string_view u) {
  for (const std::string_view ok : {"counts", "count", "cts", "pulses", "pulse", "1", "-"})
    if (u == ok) return true;
  return false;
}

// The SI size of a unit of the given dimension; nullopt for anything else.
std::optional<double> unit_of(std::string_view text, Dimension dim) {
  try {
    const Quantity q = parse_unit(text);
    if (q.dim == dim && q.value_si > 0) return q.value_si;
  } catch (const UnitError&) {
  }
  return std::nullopt;
}

bool same_size(double a, double b) { return std::abs(a - b) <= 1e-12 * std::abs(b); }

}  // namespace

void LogReducer::units(const std::vector<std::string>& units, int line) {
  const auto refuse = [&](std::size_t k, std::string problem) {
    throw CsvError(source_, line, int(k + 1), header_[k], std::move(problem));
  };
  // A row of numbers where the units row should be: the file has none.
  if (std::all_of(units.begin(), units.end(), [](const std::string& u) { return u.empty() || parse_number(u); }) &&
      !std::all_of(units.begin(), units.end(), [](const std::string& u) { return u.empty(); }))
    refuse(0, "a row of numbers where the units row should be (units_row = true in the [format] table); accepted: "
              "the columns' units on the line under the header, or units_row = false for a file without them");
  if (pending_kind_ != Problem::no_time && !units[time_].empty() && !options_.columns.iso_time) {
    const std::optional<double> size = unit_of(units[time_], kind::time);
    if (!size) refuse(time_, fmt::format("'{}' is not a time unit; accepted: s, ms, us, µs, min, …", units[time_]));
    if (!options_.time_unit_stated.empty() && !same_size(*size, options_.columns.time_scale))
      refuse(time_, fmt::format("the units row says '{}', the layout's time_unit is '{}'; accepted: one unit (the "
                                "manifest's time_unit left out, the units row gives it)",
                                units[time_], options_.time_unit_stated));
    options_.columns.time_scale = *size;
  }
  for (const std::optional<Encoder>* e : {&theta1_, &gamma_}) {
    if (!e->has_value()) continue;
    const std::size_t k = (*e)->column;
    const std::string& u = units[k];
    if (u.empty()) continue;
    if (u == "counts" || u == "count" || u == "cts") {
      if (!(options_.angle_quantum > 0))
        refuse(k, fmt::format("'{}': the layout gives no counts per revolution; accepted: angle_unit = \"counts\" "
                              "with counts_per_revolution in the [columns] table",
                              u));
      continue;
    }
    const std::optional<double> size = unit_of(u, kind::angle);
    if (!size) refuse(k, fmt::format("'{}' is not an angle unit; accepted: rad, deg, arcsec, … or counts", u));
    if (options_.angle_quantum > 0 ||
        (!options_.angle_unit_stated.empty() && !same_size(*size, options_.angle_scale)))
      refuse(k, fmt::format("the units row says '{}', the layout's angle_unit is '{}'; accepted: one unit (the "
                            "angle_unit left out, the units row gives it)",
                            u, options_.angle_quantum > 0 ? "counts" : options_.angle_unit_stated));
    options_.angle_scale = *size;
  }
  if (output_ && !units[*output_].empty()) {
    const std::string& u = units[*output_];
    if (pulses_ && !pulse_unit(u))
      refuse(*output_, fmt::format("'{}' is no count; accepted: counts, pulses, 1 or nothing", u));
    if (!pulses_ && !options_.output_unit.empty() && u != options_.output_unit) {
      bool same = false;
      try {
        const Quantity a = parse_unit(u), b = parse_unit(options_.output_unit);
        same = a.dim == b.dim && same_size(a.value_si, b.value_si);
      } catch (const UnitError&) {
      }
      if (!same)
        refuse(*output_, fmt::format("the units row says '{}', the instrument's output is read in {}; accepted: "
                                     "the output in {}",
                                     u, options_.output_unit, options_.output_unit));
    }
  }
}

void LogReducer::defer_count(int line, double value, std::string problem) {
  defer(Problem::counter_wrap, cell_error(*output_, line, fmt::format("{} {}", value, problem)));
}

// A counter of `bits` wraps at 2^bits: each step is taken modulo 2^bits into [−2^(bits−1), 2^(bits−1)), so
// that it may count down too. Without a declared width, a step against the count's direction over the log and
// more than ten times its mean step is no pulse count (a PIGA's count per sample is steady to a few per cent):
// a counter that wraps, refused where it does.
void LogReducer::count_sample(double value, int line, double step_time) {
  const int bits = options_.columns.counter_bits;
  if (bits > 0 && !(value >= 0 && value < std::ldexp(1.0, bits) && value == std::floor(value))) {
    defer_count(line, value, fmt::format("is not a count of a {}-bit counter; accepted: a whole number from 0 to "
                                         "2^{} − 1 (columns.counter_bits of the manifest)",
                                         bits, bits));
    return;
  }
  if (rows_ == 0) {
    output_first_ = output_previous_ = count_raw_ = value;
    return;
  }
  double step = value - count_raw_;
  count_raw_ = value;
  if (bits > 0) {
    const double range = std::ldexp(1.0, bits), half = std::ldexp(1.0, bits - 1);
    step -= range * std::floor((step - bridge_count_ + half) / range);
  } else if (count_steps_ >= 10) {
    check_count_step(step, value, line);
  }
  count_travel_ += std::abs(step);
  ++count_steps_;
  if (step_time > 0) spread_.add(step / step_time, line, 10 / step_time);
  output_previous_ += step;
}

void LogReducer::defer_spacing(const Encoder& e, int line, double step_time) {
  // With max_gap declared, a step within it that is not bridged is no gap: no shorter step came before it (a
  // gap at the log's start, or a log sampled too sparsely throughout).
  defer(e.spacing,
        cell_error(e.column, line,
                   fmt::format("samples {:.6g} s apart turn the joint by {:.3g} rad at the planned "
                               "rate; accepted: less than 0.75π rad between encoder samples, {}",
                               step_time, std::abs(planned_rate_) * step_time,
                               options_.max_gap > 0
                                   ? "and max_gap bridges a gap only after shorter steps (not at the log's "
                                     "start: the log from after the gap)"
                                   : "or a gap in the log declared by max_gap in the [format] table (bridged "
                                     "at the encoder's mean rate)")));
}

void LogReducer::note_wild(Encoder& e, int line, double departure, double limit) {
  if (e.wild++ > 0) return;
  e.first_wild.emplace(cell_error(
      e.column, line,
      fmt::format("the reading departs by {:.3g} rad from the line through the two readings before it; "
                  "accepted: within {:.3g} rad of it (a wild reading: a glitch, a lost digit, a cell edited by hand)",
                  departure, limit)));
}

// One wild reading is refused where it is; many are no turning joint read in the unit the log is taken in.
void LogReducer::throw_wild(const Encoder& e) const {
  if (e.wild == 0) return;
  if (e.wild <= std::max<std::size_t>(3, rows_ / 100)) throw *e.first_wild;
  // The likely cause by the unit read: radians (the default), counts, or another angle unit.
  const std::string cause =
      options_.angle_quantum > 0
          ? "counts_per_revolution other than the encoder's"
      : options_.angle_scale == 1
          ? "angles in degrees read as radians (angle_unit = deg, in the manifest or as an option), or counts "
            "without their counts_per_revolution"
          : fmt::format("angles in another unit than the one read ({:.6g} rad; the manifest's or layout's "
                        "angle_unit, or the angle_unit option)",
                        options_.angle_scale);
  throw CsvError(source_, header_line_, int(e.column + 1), header_[e.column],
                 fmt::format("{} of {} readings depart from the line through the two before them by more than "
                             "{:.3g} rad: no joint turning steadily in the unit read; likely cause: {}",
                             e.wild, rows_, std::max(kEncoderJumpLimit, 4 * options_.angle_quantum), cause));
}

// A declared gap (max_gap): the angle across it is the one nearest to where the joint's mean rate so far brings
// it (the step between raw readings, plus whole turns, keeps their digits). False when the reading is left out
// (refused: a gap after the first reading, or a wild reading).
bool LogReducer::bridge_gap(Encoder& e, double a, double tau, int line) {
  if (e.seen < 2 || !(e.tau > e.first_tau)) {
    defer(e.spacing, cell_error(e.column, line,
                                "a gap after the encoder's first reading: its rate is not known to bridge it; "
                                "accepted: at least two readings before a gap"));
    return false;
  }
  const double rate = (e.unwrapped - e.first_unwrapped) / (e.tau - e.first_tau);
  const double predicted = e.unwrapped + rate * (tau - e.tau);
  const double base = e.unwrapped + (a - e.raw);
  const double angle = base + kTwoPi * std::nearbyint((predicted - base) / kTwoPi);
  const double limit = std::max(kEncoderJumpLimit, 4 * options_.angle_quantum);
  if (!(std::abs(angle - predicted) <= limit)) {
    note_wild(e, line, std::abs(angle - predicted), limit);
    return false;
  }
  e.earlier_unwrapped = e.unwrapped;
  e.earlier_tau = e.tau;
  e.unwrapped = angle;
  return true;
}

// One encoder sample: unwrapped (each step mapped to (−π, π]) and added to the fit. The samples must be less
// than half a revolution apart at the planned rate (with a 1/4 margin for a rate error), or the unwrapping
// would alias.
template <class Cells>
void LogReducer::encoder_sample(Encoder& e, const Cells& cells, int line, bool time_ok, double t) {
  const std::optional<double> raw = cells(e.column, e.cell, line);
  if (time_ok && rows_ > 0 && have_previous_time_) {
    const double step_time = t - t_previous_;
    if (std::abs(planned_rate_) * step_time > 0.75 * std::numbers::pi) defer_spacing(e, line, step_time);
  }
  if (!raw || !time_ok || pending_kind_) return;  // the log will be refused: nothing more to fit
  const double a = *raw * options_.angle_scale;
  const double tau = t - t_first_;
  if (e.seen == 0) {
    e.unwrapped = e.first_unwrapped = a;
    e.first_tau = tau;
  } else {
    // The step from the previous reading, mapped to (−π, π] (remainder(x, 2π) is x itself for |x| < π, so
    // the usual step needs no division); taken between raw readings, it keeps their digits.
    double step = a - e.raw;
    if (!(step > -std::numbers::pi && step <= std::numbers::pi)) step = std::remainder(step, kTwoPi);
    if (step == -std::numbers::pi) step = std::numbers::pi;
    const double angle = e.unwrapped + step;
    // A wild reading: the joint's angle departs from the straight line through the two samples before it by
    // more than kEncoderJumpLimit (or four counts of a coarse encoder), which a drive's rate ripple or an
    // encoder's cyclic error never comes near (1e-5 rad) and a glitch always passes (up to π once unwrapped).
    // Compared without a division: |α − α1|·(τ1 − τ0) against |α1 − α0|·(τ − τ1) at the limit × (τ1 − τ0).
    if (e.seen >= 2) {
      const double span = e.tau - e.earlier_tau;
      const double departure = (angle - e.unwrapped) * span - (e.unwrapped - e.earlier_unwrapped) * (tau - e.tau);
      const double limit = std::max(kEncoderJumpLimit, 4 * options_.angle_quantum);
      if (!(std::abs(departure) <= limit * span)) {
        note_wild(e, line, std::abs(departure) / span, limit);
        return;  // left out: the next reading is unwrapped and checked against the line before it
      }
    }
    e.earlier_unwrapped = e.unwrapped;
    e.earlier_tau = e.tau;
    e.unwrapped = angle;
  }
  e.seen = std::min(e.seen + 1, 2);
  e.raw = a;
  e.tau = tau;
  e.fit.add(tau, e.unwrapped, a);
}

// The encoders' samples of the row after a declared gap (bridge_gap), off the rows' path.
template <class Cells>
void LogReducer::bridge_encoders(const Cells& cells, int line, double t) {
  for (std::optional<Encoder>* slot : {&theta1_, &gamma_}) {
    if (!slot->has_value()) continue;
    Encoder& e = **slot;
    const std::optional<double> raw = cells(e.column, e.cell, line);
    if (!raw || pending_kind_) continue;
    const double a = *raw * options_.angle_scale;
    const double tau = t - t_first_;
    if (!bridge_gap(e, a, tau, line)) continue;
    e.seen = std::min(e.seen + 1, 2);
    e.raw = a;
    e.tau = tau;
    e.fit.add(tau, e.unwrapped, a);
  }
}

void LogReducer::row(const std::string_view* fields, int line) {
  reduce_batch();  // the rows before it first
  if (options_.columns.iso_time) {
    reduce_row(
        [&](std::size_t column, Problem kind, int at) {
          return kind == Problem::time_cell ? iso_time_cell(fields[column], at) : cell(fields, column, kind, at);
        },
        line);
    return;
  }
  reduce_row([&](std::size_t column, Problem kind, int at) { return cell(fields, column, kind, at); }, line);
}

bool LogReducer::row_line(std::string_view line, int line_no) {
  // (A row of timestamps is declined by the plain decimals' reader: "2026-11-30T…" is none; row() reads it.)
  const std::size_t columns = header_.size();
  if (!row_reader_.read(line, std::span(batch_values_.data() + batch_rows_ * columns, columns))) return false;
  batch_lines_[batch_rows_] = line_no;
  if (++batch_rows_ == kRowBatch) reduce_batch();
  return true;
}

void LogReducer::reduce_batch() {
  const std::size_t columns = header_.size();
  for (std::size_t k = 0; k < batch_rows_; ++k) {
    const double* values = batch_values_.data() + k * columns;
    reduce_row([values](std::size_t column, Problem, int) { return std::optional<double>(values[column]); },
               batch_lines_[k]);
  }
  batch_rows_ = 0;
}

template <class Cells>
void LogReducer::reduce_row(const Cells& cells, int line) {
  last_line_ = line;
  if (pending_kind_ == Problem::no_time) return;
  std::optional<double> t = cells(time_, Problem::time_cell, line);
  if (t) *t *= options_.columns.time_scale;  // to s
  if (t && have_previous_time_ && !(*t > t_previous_)) defer_time_order(line, *t);
  if (t && rows_ == 0) t_first_ = *t;
  // A gap: a step of more than 1.5 times the shortest before it (the first step is none); a declared one
  // (max_gap) is bridged: the encoders across it at their mean rate, the sampled output not integrated over it.
  // One comparison a row: gap_threshold_ is 1.5 times the shortest step so far, or max_gap if that is less.
  bool bridge = false;
  if (t && have_previous_time_) {
    const double step = *t - t_previous_;
    if (!(step <= gap_threshold_ && step >= min_step_)) bridge = unusual_step(step, line);
  }
  if (output_) {
    if (const std::optional<double> v = cells(*output_, Problem::output_cell, line); v && t) {
      if (pulses_) {
        if (bridge && options_.columns.counter_bits > 0 && count_steps_ > 0 && *t > t_first_) {
          bridge_count_ = (output_previous_ - output_first_) / (t_previous_ - t_first_) * (*t - t_previous_);
          count_sample(*v, line, *t - t_previous_);
          bridge_count_ = 0;
        } else {
          count_sample(*v, line, have_previous_time_ ? *t - t_previous_ : 0.0);
        }
      } else {
        const double y = *v * options_.output_scale;
        if (rows_ > 0 && !bridge) integral_ += 0.5 * (y + output_previous_) * (*t - t_previous_);
        if (rows_ > 0 && y != output_previous_)
          output_resolution_ = std::min(output_resolution_, std::abs(y - output_previous_));
        spread_.add(y, line, 0);
        output_previous_ = y;
      }
    }
  }
  if (bridge) {
    bridge_encoders(cells, line, *t);
  } else {
    if (theta1_) encoder_sample(*theta1_, cells, line, t.has_value(), t.value_or(0));
    if (gamma_) encoder_sample(*gamma_, cells, line, t.has_value(), t.value_or(0));
  }
  if (t) {
    t_previous_ = *t;
    have_previous_time_ = true;
  } else {
    have_previous_time_ = false;
  }
  ++rows_;
}

ReducedLog LogReducer::finish() {
  reduce_batch();
  settle_count_wrap(std::nullopt);
  ReducedLog r;
  r.source = source_;
  r.samples = rows_;
  throw_pending_before(Problem::time_cell);
  if (rows_ < 2)
    throw CsvError(source_, header_line_, int(time_ + 1), options_.columns.time,
                   fmt::format("{} sample(s); accepted: at least two, the first and last of the run", rows_));
  throw_pending_before(Problem::gap);
  r.duration = t_previous_ - t_first_;
  // A gap at the log's start (its first step more than 1.5 times the shortest after it) is reported as one;
  // not bridged, it was read as any step (the encoders' spacing check passed it).
  const bool gap_first = rows_ > 2 && first_step_ > 1.5 * min_step_;
  r.gaps = gaps_ + (gap_first ? 1 : 0);
  r.longest_gap = gap_first ? std::max(longest_gap_, first_step_) : longest_gap_;
  r.missing = r.gaps > 0 ? std::max(0.0, gap_time_ + (gap_first ? first_step_ : 0.0) - double(r.gaps) * min_step_)
                         : 0.0;
  if (!std::isfinite(r.duration))
    throw CsvError(source_, last_line_, int(time_ + 1), options_.columns.time,
                   fmt::format("the span {} s to {} s overflows; accepted: times of a run, in s", t_first_,
                               t_previous_));
  throw_pending_before(Problem::output_cell);
  r.pulses = pulses_;
  // A sampled output's mean is over the time its samples cover: declared gaps are not integrated over.
  const double covered = options_.max_gap > 0 ? r.duration - gap_time_ : r.duration;
  r.mean_output = pulses_ ? (output_previous_ - output_first_) * options_.pulse_weight / r.duration
                          : integral_ / covered;
  // The fit squares the means: beyond 1e150 (SI) its sums overflow, and the failure would surface far from
  // the log.
  if (!(std::abs(r.mean_output) <= 1e150))
    throw CsvError(source_, header_line_, int(*output_ + 1), header_[*output_],
                   fmt::format("the mean output over the log, {:.6g} (SI), overflows the fit; accepted: the "
                               "instrument's output in its output unit, or a pulse count, below 1e150",
                               r.mean_output));
  throw_pending_before(Problem::mean_overflow);  // a counter that wraps is said so, before its step is wild
  throw_wild_output();
  throw_pending_before(Problem::gamma_spacing);
  if (theta1_) throw_wild(*theta1_);
  if (gamma_) throw_wild(*gamma_);
  if (theta1_) add_theta1_fit(theta1_->fit.result(), options_.angle_offset, r);
  if (gamma_) add_gamma_fit(gamma_->fit.result(), options_.angle_offset, r);
  return r;
}

}  // namespace ccal::detail
