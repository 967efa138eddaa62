// A calibration job and its machine set-up (docs/config.md, "Job files"), and the fingerprints of a
// configuration's tables.
#include <sstream>

#include "ccal/core/sha256.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

namespace {

// The keys of [certificate] that belong to the machine's set-up: the traceability of its standards.
constexpr const char* kSetupTraceabilityKeys[] = {"radius_standard", "rate_standard", "traceability"};

// The set-up's path: as written if absolute, else relative to the job file's folder.
std::filesystem::path setup_path(const std::string& job_source, const std::string& written) {
  const std::filesystem::path path(written);
  if (path.is_absolute()) return path;
  return std::filesystem::path(job_source).parent_path() / path;
}

}  // namespace

toml::table with_setup(const Reader& job_reader, toml::table job, std::string& setup_source) {
  const toml::node* named = job.get("setup");
  if (named == nullptr) return job;
  const auto* written = named->as_string();
  if (written == nullptr || written->get().empty())
    job_reader.fail(*named, "setup",
                    fmt::format("expected the set-up file's path as a string, got {}; accepted: e.g. "
                                "setup = \"lab_setup.toml\" (relative to this file's folder)",
                                written ? "an empty string" : type_name(*named)));
  const std::filesystem::path path = setup_path(job_reader.source(), written->get());
  std::string text;
  try {
    text = read_file_text(path);
  } catch (const ConfigError&) {
    job_reader.fail(*named, "setup",
                    fmt::format("cannot read the set-up file '{}'; accepted: a readable TOML file, its path "
                                "relative to this file's folder",
                                path.string()));
  }
  setup_source = path.string();
  const Reader setup_reader{setup_source};
  toml::table setup = parse_toml(setup_reader, text, setup_source);
  if (const toml::node* nested = setup.get("setup"))
    setup_reader.fail(*nested, "setup",
                      "a set-up cannot name another set-up; accepted: the machine's and the lab's tables "
                      "([site], [centrifuge], [errors], [tolerances], …), the job file names its set-up");
  // The traceability of the machine's standards is the set-up's: a job's [certificate] that states none keeps
  // the set-up's radius_standard, rate_standard and [certificate.traceability], each where it is written.
  toml::table* job_certificate = job["certificate"].as_table();
  // (moved, not copied: a copied node forgets where it was written)
  if (toml::table* setup_certificate = setup["certificate"].as_table(); job_certificate && setup_certificate)
    for (const char* key : kSetupTraceabilityKeys)
      if (!job_certificate->contains(key))
        if (toml::node* node = setup_certificate->get(key)) job_certificate->insert(key, std::move(*node));
  // A new root (it has no place of its own: a message about it names the job), its tables moved in with the
  // places they were written at.
  // The item calibrated is one [instrument] or several [[instruments]]: a job that gives either replaces both.
  if (job.contains("instrument") || job.contains("instruments")) {
    setup.erase("instrument");
    setup.erase("instruments");
  }
  toml::table merged;
  for (auto&& [key, node] : setup) merged.insert_or_assign(key, std::move(node));
  for (auto&& [key, node] : job)
    if (key.str() != "setup") merged.insert_or_assign(key, std::move(node));
  return merged;
}

std::string tables_sha256(const toml::table& root, const Keys& keys, KeySelection selection) {
  toml::table chosen;
  for (const auto& [key, node] : root) {
    const bool listed = std::find(keys.begin(), keys.end(), key.str()) != keys.end();
    if (key.str() != "setup" && listed == (selection == KeySelection::include)) chosen.insert(key, node);
  }
  // An instrument's serial number is its certificate's (wording, as [certificate]): not a number of the test.
  if (toml::array* instruments = chosen["instruments"].as_array())
    for (toml::node& entry : *instruments)
      if (toml::table* t = entry.as_table()) t->erase("serial_number");
  // toml::table is ordered by key: the text is the same for the same values whatever the file's order,
  // comments or layout. Floats are written with the digits that read back the same double.
  std::ostringstream text;
  text << toml::toml_formatter(chosen, toml::format_flags::none);
  return sha256_hex(text.str());
}

}  // namespace ccal::config_reading
