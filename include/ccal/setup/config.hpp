#pragma once
// The whole set-up of a calibration test as one value: site, centrifuge (geometry and known errors),
// instrument, test plan, tolerances, what is identified and how runs are reduced. Read from a file by
// io/config_file.hpp; every verb takes one (verbs/).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"
#include "ccal/setup/certificate.hpp"
#include "ccal/setup/design_space.hpp"
#include "ccal/setup/experiment.hpp"
#include "ccal/setup/tolerance.hpp"

namespace ccal {

struct Config {
  std::string source;  // file name (or the name given to parse_config), as used in messages
  // A job file's machine set-up (`setup = "…toml"`), as read; "" for a file that names none.
  std::string setup_source;
  // Fingerprints (SHA-256), each empty for a configuration built or changed in code (it then describes no
  // file; clear_fingerprints). text_sha256: of the file's own bytes (the job's, not its set-up's), for
  // provenance. numbers_sha256: of the canonical text of every table but [certificate] and [design], the job
  // and its set-up merged: what changes the numbers, the fingerprint that binds an observations file to its
  // configuration. setup_sha256: of the machine's and the lab's tables alone ([site], [centrifuge], [errors],
  // [tolerances], [[correlations]], [[inputs]]), the same for every job on one set-up (docs/config.md).
  std::string text_sha256;
  std::string numbers_sha256;
  std::string setup_sha256;
  Site site;
  CentrifugeModel centrifuge;  // geometry and the known/actual values of the [errors] section
  InstrumentModel instrument;
  // The instrument's id in a test of several ([[instruments]] id); "" for the one [instrument].
  std::string instrument_id;
  // A test of several instruments on the platform ([[instruments]], docs/config.md): each as a configuration
  // of its own, in the file's order — its instrument that entry's, its place and azimuth in
  // centrifuge.geometry (x5, y5, azimuth5), its fingerprint numbers_sha256 its own, every other table shared.
  // This configuration is then the first's, with the list. Empty for a configuration of one [instrument].
  std::vector<Config> instruments;
  // The test's other instruments, when this configuration is one instrument chosen from a test of several
  // (select_instrument): their ids (their columns in the test's logs are not this instrument's) and the
  // fingerprints of their numbers (an observations file of one of them is named as theirs).
  struct OtherInstrument {
    std::string id, numbers_sha256;
  };
  std::vector<OtherInstrument> other_instruments;
  TestPlan plan;
  std::vector<Tolerance> tolerances;  // in catalogue (ErrorLayout) order, then the measuring chain's inputs
  std::vector<Correlation> correlations;  // pairs of tolerances partly correlated ([[correlations]])
  // The measuring chain: [[inputs]] declared by the lab, and (set by a test's reduction) what it measured.
  MeasuringChain chain;
  // What is identified ([identification]; default: K0, K2, K3 free and K1 held at the instrument's value, as
  // in the paper). Fixed terms hold the instrument's configured coefficients (SI).
  IdentificationSpec identification;
  // How runs are reduced ([identification] mode): the exact chain (default) or the paper's first-order rules.
  ModelMode mode = ModelMode::exact;
  // The design space of `ccal design` ([design]; every field optional, defaults from the plan).
  DesignSpace design;
  // The certificate's administrative fields ([certificate]; unset without the table): what `ccal report`
  // prints at the head of the certificate page with the statement of --observations.
  std::optional<Certificate> certificate;

  // The experiment (geometry, layout, site, plan, instrument) of this configuration.
  Experiment experiment() const;
};

// Refuses a configuration of several instruments (two or more [[instruments]]) for a verb that handles one: an
// OptionError of the field "instrument" naming the verb and the instruments, which accepts one of them (chosen by
// select_instrument); it must not answer for the first alone.
void require_one_instrument(const Config& config, std::string_view verb);

// One instrument of a test of several, by its [[instruments]] id: its configuration, at its place on the platform,
// as a test of that one instrument (instruments = {it}), with the others' ids in other_instruments. An empty id
// gives the configuration unchanged. OptionError of the field "instrument" for an id the test does not have, or for
// a configuration of one [instrument] (which has no ids), naming what is accepted.
Config select_instrument(const Config& config, std::string_view id);
// The words refusing an instrument id given empty (an unset shell variable, an empty string), which would
// otherwise mean every instrument silently; each front end names its option (`--instrument`, instrument()).
inline constexpr std::string_view kEmptyInstrumentId =
    "the id is empty; accepted: an instrument's id of the configuration's [[instruments]], e.g. A";

// The configuration no longer describes its file (changed in code): its fingerprints emptied.
void clear_fingerprints(Config& config);

// Index of a run chosen by the user: a run name, or else a 1-based index ("3"). Throws InputError listing the
// runs if there is no such run; option_name (e.g. "--run") starts the message.
std::size_t select_run(const TestPlan& plan, std::string_view name_or_index, std::string_view option_name);

}  // namespace ccal
