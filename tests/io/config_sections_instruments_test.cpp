// [[instruments]]: a test of several instruments on the platform (docs/config.md), each a configuration of its
// own with its place and azimuth; the bad entries refused where they are written.
#include "config_test_support.hpp"
#include "test_paths.hpp"

namespace ccal {
namespace {

using namespace config_test;

const std::string kTwo = kBase + R"(
[[instruments]]
id = "A"
terms = { K0 = "0.06 deg/s", K1 = "505 deg/s/g", K2 = "0.02 deg/s/g^2", K3 = "0.003 deg/s/g^3" }
[[instruments]]
id = "B"
position = ["0 m", "120 mm"]
azimuth = "90 deg"
terms = { K0 = "0.05 deg/s", K1 = "504 deg/s/g", K2 = "0.015 deg/s/g^2", K3 = "0.002 deg/s/g^3" }
)";

TEST(Instruments, EachIsAConfigurationOfItsOwnAtItsPlace) {
  const Config c = parse_config(kTwo, "two.toml");
  ASSERT_EQ(c.instruments.size(), 2u);
  EXPECT_EQ(c.instrument_id, "A");  // the configuration itself is the first's
  const Config& a = c.instruments[0];
  const Config& b = c.instruments[1];
  EXPECT_EQ(a.instrument_id, "A");
  EXPECT_EQ(b.instrument_id, "B");
  EXPECT_TRUE(a.instruments.empty() && b.instruments.empty());
  EXPECT_NEAR(*a.instrument.coefficient("K0"), 0.06 * kDeg, 1e-18);
  EXPECT_NEAR(*b.instrument.coefficient("K0"), 0.05 * kDeg, 1e-18);
  EXPECT_EQ(a.centrifuge.geometry.x5, 0.0);
  EXPECT_EQ(a.centrifuge.geometry.azimuth5, 0.0);
  EXPECT_EQ(b.centrifuge.geometry.x5, 0.0);
  EXPECT_NEAR(b.centrifuge.geometry.y5, 0.12, 1e-17);
  EXPECT_NEAR(b.centrifuge.geometry.azimuth5, std::numbers::pi / 2, 1e-16);
  // Shared: the plan, the machine, the identification; the fingerprints of the numbers are each its own.
  EXPECT_EQ(a.plan.runs.size(), b.plan.runs.size());
  EXPECT_EQ(a.setup_sha256, b.setup_sha256);
  EXPECT_NE(a.numbers_sha256, b.numbers_sha256);
  EXPECT_EQ(c.numbers_sha256, a.numbers_sha256);
  EXPECT_EQ(a.identification.free_terms, b.identification.free_terms);
}

// The example job: the lab's machine with two PIGAs, the set-up's [instrument] replaced by the job's two.
TEST(Instruments, TheExampleJobReplacesItsSetUpsInstrument) {
  const Config c = load_config(std::string(CCAL_SOURCE_DIR) + "/examples/two_instruments.toml");
  ASSERT_EQ(c.instruments.size(), 2u);
  EXPECT_EQ(c.instruments[1].instrument_id, "B");
  EXPECT_FALSE(c.tolerances.empty());  // the set-up's
  EXPECT_EQ(c.plan.runs.size(), 6u);
  // A with one [instrument] is as before: no list.
  EXPECT_TRUE(load_config(std::string(CCAL_SOURCE_DIR) + "/examples/lab.toml").instruments.empty());
}

TEST(Instruments, BadEntriesAreRefusedWhereTheyAreWritten) {
  const std::string both = kBase + "\n[instrument]\nmodel = \"piga\"\n[[instruments]]\nid = \"A\"";
  expect_error(both, last_line(both) - 1, "instruments", {"both [instrument] and [[instruments]]"});
  const std::string no_id = kBase + "\n[[instruments]]\nmodel = \"piga\"";  // at the entry's header
  expect_error(no_id, last_line(no_id) - 1, "instruments[1].id", {"missing", "id = \"A\""});
  expect_appended_error("[[instruments]]\nid = \"A\"\n[[instruments]]\nid = \"A\"", "instruments[2].id",
                        {"'A' names an earlier instrument too"});
  expect_appended_error("[[instruments]]\nid = \"A B\"", "instruments[1].id", {"'A B' is not an id", "letters"});
  expect_appended_error("[[instruments]]\nid = \"A\"\nposition = [\"1 m\"]", "instruments[1].position",
                        {"two lengths", "an array of 1"});
  expect_appended_error("[[instruments]]\nid = \"A\"\nposition = [\"1 m\", \"2 deg\"]",
                        "instruments[1].position[1]", {"deg"});
  expect_appended_error("[[instruments]]\nid = \"A\"\nposition = [\"1 m\", \"11 m\"]",
                        "instruments[1].position[1]", {"more than 10 m"});
  expect_appended_error("[[instruments]]\nid = \"A\"\nazimuth = \"3 m\"", "instruments[1].azimuth", {"angle"});
  expect_appended_error("[[instruments]]\nid = \"A\"\npositon = [\"0 m\", \"0 m\"]", "instruments[1].positon",
                        {"did you mean 'position'?"});
  // The [instrument] keys of an entry are named by the entry.
  expect_appended_error("[[instruments]]\nid = \"A\"\noutput_unit = \"furlong\"", "instruments[1].output_unit",
                        {"furlong"});
  expect_appended_error("[[instruments]]\nid = \"A\"\n[instruments.terms]\nK0x = \"1 deg/s\"",
                        "instruments[1].terms.K0x", {"not a term id", "did you mean 'K0'?"});
  expect_error("instruments = 3\n" + kBase, 1, "instruments", {"one [[instruments]] table per instrument"});
}

// The paper's first-order rules assume the instrument on the platform axis and not turned.
TEST(Instruments, PaperModeIsRefusedForAnInstrumentOffTheAxis) {
  const std::string text = kBase + "\n[identification]\nmode = \"paper\"\n[[instruments]]\nid = \"A\"\n"
                                   "[[instruments]]\nid = \"B\"\nazimuth = \"90 deg\"";
  expect_error(text, last_line(text) - 2, "instruments[2]", {"instrument 'B'", "mode = \"exact\""});
  EXPECT_NO_THROW(parse_config(kBase + "\n[identification]\nmode = \"paper\"\n[[instruments]]\nid = \"A\"", "x"));
}

}  // namespace
}  // namespace ccal

namespace ccal {
namespace {

using namespace config_test;

const std::string kCertificate = "\n[certificate]\nlaboratory = \"Lab\"\nserial_number = \"SN 1\"\n";

// Each instrument's serial number is its certificate's: the [certificate] table is the test's, the serial each
// entry's own (the certificate and the history name an instrument by it).
TEST(Instruments, EachSerialNumberIsItsOwnCertificates) {
  const std::string text = kBase + kCertificate +
                           "[[instruments]]\nid = \"A\"\nserial_number = \"SN 10\"\n"
                           "[[instruments]]\nid = \"B\"\nserial_number = \"SN 11\"\n";
  const Config c = parse_config(text, "two.toml");
  ASSERT_EQ(c.instruments.size(), 2u);
  EXPECT_EQ(c.instruments[0].certificate->serial_number, "SN 10");
  EXPECT_EQ(c.instruments[1].certificate->serial_number, "SN 11");
  EXPECT_EQ(c.instruments[1].certificate->laboratory, "Lab");
  // The serial is no number of the test: the fingerprints are those of the same test without serials.
  const Config plain = parse_config(kBase + "\n[[instruments]]\nid = \"A\"\n[[instruments]]\nid = \"B\"\n", "p.toml");
  EXPECT_EQ(c.instruments[0].numbers_sha256, plain.instruments[0].numbers_sha256);
  EXPECT_EQ(c.instruments[1].numbers_sha256, plain.instruments[1].numbers_sha256);
  // One entry of a [certificate]: its serial is the table's.
  const Config one = parse_config(kBase + kCertificate + "[[instruments]]\nid = \"A\"\n", "one.toml");
  EXPECT_EQ(one.instruments[0].certificate->serial_number, "SN 1");
  // The example job: the set-up's [certificate], each PIGA its serial.
  const Config two = load_config(std::string(CCAL_SOURCE_DIR) + "/examples/two_instruments.toml");
  EXPECT_EQ(two.instruments[0].certificate->serial_number, "SN 0815");
  EXPECT_EQ(two.instruments[1].certificate->serial_number, "SN 0816");
}

TEST(Instruments, SerialNumbersThatCannotNameEachInstrumentAreRefused) {
  // A [certificate] for two instruments without a serial of each would give both one history.
  const std::string none = kBase + kCertificate + "[[instruments]]\nid = \"A\"\nserial_number = \"SN 10\"\n"
                                                  "[[instruments]]\nid = \"B\"";
  expect_error(none, last_line(none) - 1, "instruments[2]",
               {"instrument 'B' has no serial_number", "each of the 2 instruments", "each its own"});
  const std::string same = kBase + kCertificate + "[[instruments]]\nid = \"A\"\nserial_number = \"SN 10\"\n"
                                                  "[[instruments]]\nid = \"B\"\nserial_number = \"SN 10\"";
  expect_error(same, last_line(same), "instruments[2].serial_number",
               {"'SN 10' is also the serial number of instrument 'A'"});
  expect_appended_error("[[instruments]]\nid = \"A\"\nserial_number = \"SN 10\"", "instruments[1].serial_number",
                        {"no [certificate] table", "accepted: a [certificate] table, or no serial_number"});
  expect_appended_error(kCertificate + "[[instruments]]\nid = \"A\"\nserial_number = \" \"",
                        "instruments[1].serial_number", {"is empty"});
  expect_appended_error(kCertificate + "[[instruments]]\nid = \"A\"\nserial_number = 42",
                        "instruments[1].serial_number", {"string"});
  // A control character (a NUL written as \u0000) went into the certificate and the history refused it later.
  expect_appended_error(kCertificate + "[[instruments]]\nid = \"A\"\nserial_number = \"SN\\u0000 10\"",
                        "instruments[1].serial_number",
                        {"'SN\\x00 10' holds a control character; accepted: the instrument's serial number"});
}

// One instrument chosen from a test (`--instrument ID`): its configuration as a test of it alone, the others named.
TEST(Instruments, OneInstrumentIsChosenByItsId) {
  const Config c = parse_config(kTwo, "two.toml");
  const Config b = select_instrument(c, "B");
  EXPECT_EQ(b.instrument_id, "B");
  ASSERT_EQ(b.instruments.size(), 1u);
  EXPECT_EQ(b.instruments[0].instrument_id, "B");
  ASSERT_EQ(b.other_instruments.size(), 1u);
  EXPECT_EQ(b.other_instruments[0].id, "A");
  EXPECT_EQ(b.other_instruments[0].numbers_sha256, c.instruments[0].numbers_sha256);
  EXPECT_EQ(b.numbers_sha256, c.instruments[1].numbers_sha256);
  EXPECT_NEAR(b.centrifuge.geometry.y5, 0.12, 1e-17);
  EXPECT_NO_THROW(require_one_instrument(b, "budget"));
  EXPECT_EQ(select_instrument(c, "").instruments.size(), 2u);  // none chosen: the whole test
  try {
    select_instrument(c, "C");
    FAIL() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "instrument");
    EXPECT_EQ(std::string(e.what()), "instrument: C is no instrument of two.toml; accepted: A, B");
  }
  try {
    select_instrument(parse_config(kBase, "one.toml"), "A");
    FAIL() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_NE(std::string(e.what()).find("one.toml has one [instrument] and no ids"), std::string::npos) << e.what();
  }
  // A verb of one instrument asks for one, naming them.
  try {
    require_one_instrument(c, "force");
    FAIL() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "instrument");
    EXPECT_NE(std::string(e.what()).find("two.toml holds a test of 2 instruments (A, B), and force answers for one "
                                         "at a time; accepted: one of A, B"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ccal
