// A serial's history exported as JSON and imported into another store (history/history_exchange.hpp): the same
// records, values bit for bit, the same statements (so the same SHA-256), the supersession mapped to the new
// ids; importing twice adds nothing; a file that is no export is refused before anything is added.
#include "ccal/history/history_exchange.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "ccal/core/errors.hpp"

namespace ccal {
namespace {

namespace fs = std::filesystem;

std::string exchanged_statement(double k2) {
  return fmt::format(R"({{"coverage_probability": 0.95, "coefficients": {{"K2": {{"unit": "deg/s/g^2",
      "corrected_estimate": {}, "expanded_uncertainty": 3.2e-4, "coverage_factor": 1.96, "effective_dof": 44.5}}}}}})",
                     k2);
}

TEST(HistoryExchange, ExportedAndImportedTheSame) {
  const fs::path folder = fs::temp_directory_path() / fmt::format("ccal_history_exchange_{}", ::getpid());
  fs::remove_all(folder);
  HistoryStore from = HistoryStore::open((folder / "from.sqlite").string(), HistoryStore::Access::create);
  from.add(history_entry(exchanged_statement(0.0200001), "a", "SN 1", "2024-11-30"));  // ids 1, 2, 3 here
  const std::int64_t second = from.add(history_entry(exchanged_statement(0.0202), "b", "SN 1", "2025-11-30"));
  const std::int64_t third = from.add(history_entry(exchanged_statement(0.0204), "c", "SN 1", "2026-11-30"));
  from.supersede(second, third, "repeated");
  const std::string text = export_history(from, "SN 1");

  HistoryStore to = HistoryStore::open((folder / "to.sqlite").string(), HistoryStore::Access::create);
  to.add(history_entry(exchanged_statement(9.0), "z", "SN 9", "2020-01-01"));  // so that the new ids differ
  const HistoryImport first = import_history(to, text, "sn1.json");
  EXPECT_EQ(first.added, 3u);
  EXPECT_EQ(first.superseded, 1u);
  const std::vector<HistoryRecord> a = from.records("SN 1"), b = to.records("SN 1");
  ASSERT_EQ(b.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(b[i].date, a[i].date);
    EXPECT_EQ(b[i].statement_sha256, a[i].statement_sha256);
    EXPECT_EQ(b[i].coefficients.at(0).value, a[i].coefficients.at(0).value);
    EXPECT_EQ(b[i].coefficients.at(0).expanded, a[i].coefficients.at(0).expanded);
    EXPECT_EQ(b[i].coefficients.at(0).effective_dof, a[i].coefficients.at(0).effective_dof);
  }
  EXPECT_EQ(b[1].superseded_reason, "repeated");
  EXPECT_EQ(b[1].superseded_by, b[2].id);  // the new store's id of the third
  EXPECT_NE(b[2].id, third);
  // Twice: nothing more.
  const HistoryImport again = import_history(to, text, "sn1.json");
  EXPECT_EQ(again.added, 0u);
  EXPECT_EQ(again.present, 3u);
  EXPECT_EQ(to.records("SN 1").size(), 3u);
  // Not an export, or one with a bad entry: refused, nothing added.
  EXPECT_THROW(import_history(to, R"({"format": "other"})", "x.json"), InputError);
  const std::string bad =
      R"({"format": "ccal calibration history", "schema": 1, "serial": "SN 5", "calibrations": [
      {"id": 1, "date": "2026-01-01", "statement": )" +
      exchanged_statement(0.01) + R"(},
      {"id": 2, "date": "2026-13-01", "statement": )" +
      exchanged_statement(0.02) + "}]}";
  EXPECT_THROW(import_history(to, bad, "bad.json"), InputError);
  EXPECT_TRUE(to.records("SN 5").empty());
  EXPECT_THROW(export_history(to, "SN 404"), InputError);
  fs::remove_all(folder);
}

// The supersessions of a file: a "by" that names no calibration of the file is refused (it would be dropped,
// leaving the record superseded by nothing), as are supersessions in a circle; a chain (1 by 2, 2 by 3) is
// recorded whatever the order of the file, since a record is superseded only by one in force.
TEST(HistoryExchange, SupersessionsAreRecordedInOrderOrRefused) {
  const fs::path folder = fs::temp_directory_path() / fmt::format("ccal_history_chain_{}", ::getpid());
  fs::remove_all(folder);
  const auto file = [](const std::string& sup1, const std::string& sup2) {
    return R"({"format": "ccal calibration history", "schema": 1, "serial": "SN 3", "calibrations": [
      {"id": 3, "date": "2026-01-03", "statement": )" +
           exchanged_statement(0.03) + R"(},
      {"id": 2, "date": "2026-01-02", "statement": )" +
           exchanged_statement(0.02) + R"(, "superseded": )" + sup2 + R"(},
      {"id": 1, "date": "2026-01-01", "statement": )" +
           exchanged_statement(0.01) + R"(, "superseded": )" + sup1 + "}]}";
  };
  HistoryStore to = HistoryStore::open((folder / "to.sqlite").string(), HistoryStore::Access::create);
  const auto refused = [&](const std::string& text, const std::string& says) {
    try {
      import_history(to, text, "sn3.json");
      ADD_FAILURE() << "not refused: " << says;
    } catch (const InputError& x) {
      EXPECT_NE(std::string(x.what()).find(says), std::string::npos) << x.what();
    }
    EXPECT_TRUE(to.records("SN 3").empty());  // refused before anything is added
  };
  refused(file(R"({"by": 999, "reason": "r"})", R"({"by": 3, "reason": "r"})"),
          "sn3.json: calibrations[2] (id 1) is superseded by 999, which names no calibration in the file; "
          "accepted: the \"id\" of another calibration in the file, or null");
  refused(file(R"({"by": 2, "reason": "r"})", R"({"by": 1, "reason": "r"})"), "go round in a circle");
  refused(file(R"({"by": 1, "reason": "r"})", "null"), "is superseded by 1, itself");
  // 2 by 3 comes first in the file; 1 by 2 must be recorded before it.
  const HistoryImport r =
      import_history(to, file(R"({"by": 2, "reason": "a"})", R"({"by": 3, "reason": "b"})"), "sn3.json");
  EXPECT_EQ(r.superseded, 2u);
  const std::vector<HistoryRecord> b = to.records("SN 3");
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].superseded_by, b[1].id);
  EXPECT_EQ(b[1].superseded_by, b[2].id);
  EXPECT_TRUE(b[2].superseded_reason.empty());
  fs::remove_all(folder);
}

}  // namespace
}  // namespace ccal
