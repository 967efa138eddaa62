// Job files (docs/config.md, "Job files"): a job names its machine set-up, the job's tables replace the
// set-up's of the same name, every message points at the file and line of its key, and the fingerprints cover
// what changes the numbers: a [certificate] edit keeps them, a tolerance, the plan or the instrument does not.
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "config_test_support.hpp"

namespace ccal {
namespace {

namespace fs = std::filesystem;
using namespace config_test;

// The machine and the lab of kBase, with a tolerance; no plan.
const std::string kSetup = R"([site]
latitude = "45.75 deg"
g = "9.8 m/s^2"
[centrifuge]
radius = "2.5 m"
[tolerances]
dR_s = "25 um"
)";

// The job's plan and certificate, after its `setup` line.
const std::string kJobTables = R"(
[plan]
duration = "450 s"
terminal_phase = "180 deg"
[[plan.runs]]
name = "a"
g_level = "5 g"
[certificate]
operator = "A. Engineer"
)";

class JobFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt::format("ccal_job_{}_{}", ::getpid(), info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "jobs");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  // A set-up machine.toml and a job in jobs/ naming it; the job's path.
  std::string job(const std::string& setup_text, const std::string& job_tables) const {
    write("machine.toml", setup_text);
    return write("jobs/job.toml", "setup = \"../machine.toml\"\n" + job_tables);
  }
  ConfigError error_of_job(const std::string& setup_text, const std::string& job_tables) const {
    const std::string path = job(setup_text, job_tables);
    try {
      load_config(path);
    } catch (const ConfigError& e) {
      return e;
    }
    ADD_FAILURE() << "accepted: " << path;
    return ConfigError("", 0, 0, "", "");
  }

  fs::path dir_;
};

TEST_F(JobFile, TheJobsTablesOnItsSetUp) {
  const Config c = load_config(job(kSetup, kJobTables));
  EXPECT_EQ(c.source, (dir_ / "jobs/job.toml").string());
  EXPECT_EQ(fs::weakly_canonical(c.setup_source), fs::weakly_canonical(dir_ / "machine.toml"));
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.R0, 2.5);  // the set-up's
  ASSERT_EQ(c.plan.runs.size(), 1u);                 // the job's
  ASSERT_TRUE(c.certificate.has_value());
  EXPECT_EQ(c.certificate->operator_name, "A. Engineer");
  // The same tables in one file read to the same configuration and the same fingerprint of the numbers.
  const Config single = parse_config(kSetup + kJobTables, "single.toml");
  EXPECT_EQ(single.setup_source, "");
  EXPECT_EQ(c.numbers_sha256, single.numbers_sha256);
  EXPECT_EQ(c.setup_sha256, single.setup_sha256);
  EXPECT_NE(c.text_sha256, single.text_sha256);  // the job file's own bytes
}

TEST_F(JobFile, ATableTheJobGivesReplacesTheSetUpsWhole) {
  // The set-up's [plan] has two runs and a platform default; the job's, one run and none: the job's alone.
  const std::string setup = kSetup + R"([plan]
duration = "450 s"
terminal_phase = "180 deg"
platform = "fixed"
[[plan.runs]]
name = "x"
g_level = "5 g"
[[plan.runs]]
name = "y"
g_level = "10 g"
)";
  const Config c = load_config(job(setup, kJobTables));
  ASSERT_EQ(c.plan.runs.size(), 1u);
  EXPECT_EQ(c.plan.runs[0].name, "a");
  EXPECT_EQ(c.plan.runs[0].mode, PlatformMode::counter_rotating);  // not the set-up's "fixed"
  // A table the job does not give is the set-up's: a job without [plan] runs the set-up's.
  EXPECT_EQ(load_config(job(setup, "")).plan.runs.size(), 2u);
}

TEST_F(JobFile, TheSetUpsTraceabilityHoldsForItsJobs) {
  // The machine's standards are the set-up's: a job's [certificate] that states none keeps them; one that
  // states its own has its own. The rest of the set-up's [certificate] is replaced whole, as any table.
  const std::string setup = kSetup + R"([certificate]
laboratory = "Lab"
radius_standard = "laser tracker, LT-1"
[certificate.traceability]
g = "gravimeter, G-3"
angle = "autocollimator, AC-2"
)";
  Config c = load_config(job(setup, kJobTables));
  ASSERT_TRUE(c.certificate.has_value());
  EXPECT_EQ(c.certificate->operator_name, "A. Engineer");
  EXPECT_EQ(c.certificate->laboratory, "");  // the job's [certificate] says no laboratory
  EXPECT_EQ(c.certificate->radius_standard, "laser tracker, LT-1");
  const std::vector<std::pair<std::string, std::string>> machine{{"g", "gravimeter, G-3"},
                                                                  {"angle", "autocollimator, AC-2"}};
  EXPECT_EQ(c.certificate->traceability, machine);
  c = load_config(job(setup, kJobTables + "radius_standard = \"CMM, C-9\"\n[certificate.traceability]\ng = "
                                          "\"gravimeter, G-4\"\n"));
  EXPECT_EQ(c.certificate->radius_standard, "CMM, C-9");
  const std::vector<std::pair<std::string, std::string>> own{{"g", "gravimeter, G-4"}};
  EXPECT_EQ(c.certificate->traceability, own);
  // A bad line of the set-up's traceability is refused at the set-up's file and line.
  std::string bad = setup;
  bad.replace(bad.find("\"gravimeter, G-3\""), 17, "9.8");
  const ConfigError e = error_of_job(bad, kJobTables);
  EXPECT_EQ(fs::path(e.source()).filename(), "machine.toml") << e.what();
  EXPECT_EQ(e.line(), 12) << e.what();
}

TEST_F(JobFile, MessagesPointAtTheFileAndLineOfTheirKey) {
  // In the set-up: its file and line (the tolerance is on line 7 of kSetup).
  std::string setup = kSetup;
  setup.replace(setup.find("\"25 um\""), 7, "\"25 s\"");
  ConfigError e = error_of_job(setup, kJobTables);
  EXPECT_EQ(fs::path(e.source()).filename(), "machine.toml") << e.what();
  EXPECT_EQ(e.line(), 7) << e.what();
  EXPECT_EQ(e.key(), "tolerances.dR_s") << e.what();
  // In the job: its file and line (g_level on line 8 of the job).
  std::string tables = kJobTables;
  tables.replace(tables.find("\"5 g\""), 5, "\"5 m\"");
  e = error_of_job(kSetup, tables);
  EXPECT_EQ(fs::path(e.source()).filename(), "job.toml") << e.what();
  EXPECT_EQ(e.line(), 8) << e.what();
  EXPECT_EQ(e.key(), "plan.runs[1].g_level") << e.what();
  // An unknown table of the job: the job's line of it.
  e = error_of_job(kSetup, kJobTables + "[sitee]\n");
  EXPECT_EQ(fs::path(e.source()).filename(), "job.toml") << e.what();
  EXPECT_EQ(e.line(), 11) << e.what();
  EXPECT_NE(std::string(e.what()).find("did you mean 'site'?"), std::string::npos) << e.what();
}

TEST_F(JobFile, AMissingOrNestedSetUpIsRefusedWhereItIsNamed) {
  const std::string path = write("jobs/lost.toml", "# a job\nsetup = \"nowhere.toml\"\n" + kJobTables);
  try {
    load_config(path);
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.source(), path);
    EXPECT_EQ(e.line(), 2) << what;
    EXPECT_EQ(e.key(), "setup") << what;
    EXPECT_NE(what.find("cannot read the set-up file"), std::string::npos) << what;
    EXPECT_NE(what.find("nowhere.toml"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  ConfigError e = error_of_job("setup = \"other.toml\"\n" + kSetup, kJobTables);
  EXPECT_EQ(fs::path(e.source()).filename(), "machine.toml") << e.what();
  EXPECT_EQ(e.line(), 1) << e.what();
  EXPECT_NE(std::string(e.what()).find("a set-up cannot name another set-up"), std::string::npos) << e.what();
  for (const char* bad : {"setup = 3", "setup = \"\""}) {
    write("jobs/bad.toml", std::string(bad) + "\n" + kJobTables);
    try {
      load_config(dir_ / "jobs/bad.toml");
      ADD_FAILURE() << bad;
    } catch (const ConfigError& x) {
      EXPECT_EQ(x.line(), 1) << x.what();
      EXPECT_NE(std::string(x.what()).find("accepted: e.g. setup = \"lab_setup.toml\""), std::string::npos)
          << x.what();
    }
  }
}

// What each edit does to the three fingerprints of a job (text, numbers, set-up): true where it changes one.
struct Edit {
  const char* what;
  std::string setup, job;
  bool text, numbers, setup_part;
};

TEST_F(JobFile, FingerprintsCoverWhatChangesTheNumbers) {
  const Config before = load_config(job(kSetup, kJobTables));
  const auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  const Edit edits[] = {
      {"the operator's name", kSetup, replaced(kJobTables, "A. Engineer", "B. Engineer"), true, false, false},
      {"a comment and the key order", "# the machine\n" + replaced(kSetup, "latitude = \"45.75 deg\"\ng = \"9.8 m/s^2\"",
                                                                   "g = \"9.8 m/s^2\"  # measured\nlatitude = \"45.75 deg\""),
       kJobTables, false, false, false},
      {"a [design] table", kSetup, kJobTables + "[design]\nruns = 4\n", true, false, false},
      {"a tolerance", replaced(kSetup, "25 um", "26 um"), kJobTables, false, true, true},
      {"the plan", kSetup, replaced(kJobTables, "450 s", "451 s"), true, true, false},
      {"the instrument", kSetup, kJobTables + "[instrument]\nnoise_density = \"0.0005 deg/s/rtHz\"\n", true, true,
       false},
      {"the identification", kSetup, kJobTables + "[identification]\nmode = \"paper\"\n", true, true, false},
  };
  for (const Edit& e : edits) {
    SCOPED_TRACE(e.what);
    const Config after = load_config(job(e.setup, e.job));
    EXPECT_EQ(after.text_sha256 != before.text_sha256, e.text);
    EXPECT_EQ(after.numbers_sha256 != before.numbers_sha256, e.numbers);
    EXPECT_EQ(after.setup_sha256 != before.setup_sha256, e.setup_part);
    EXPECT_EQ(after.numbers_sha256.size(), 64u);
    EXPECT_EQ(after.setup_sha256.size(), 64u);
  }
  // A float is written with every digit it needs: one part in 10¹⁶ is another fingerprint.
  const Config tenth = parse_config(kBase + "\n[instrument]\nrate_gain = 0.1\n", "a.toml");
  const Config next = parse_config(kBase + "\n[instrument]\nrate_gain = 0.10000000000000002\n", "a.toml");
  EXPECT_NE(tenth.numbers_sha256, next.numbers_sha256);
}

}  // namespace
}  // namespace ccal
