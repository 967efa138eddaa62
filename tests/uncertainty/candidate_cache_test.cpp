// The cache file of the design's candidate rows (uncertainty/candidate_cache.hpp): rows read back bit for bit, every
// kind of mismatch a miss, keys that change with every input, the folder kept small, a folder that cannot be
// written harmless; and through `design`: the second design reads the rows and gives the same plan.
#include "ccal/uncertainty/candidate_cache.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/verbs/design.hpp"

namespace ccal {
namespace {

namespace fs = std::filesystem;

// A fresh folder of its own for each test.
class CandidateCache : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ =
        fs::temp_directory_path() /
        ("ccal-cache-test-" + std::to_string(::getpid()) + "-" +  // apart from another checkout's run
         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

// Rows of every kind of double the cache must keep: random values over many decades, −0, a subnormal, the
// largest and the smallest normal.
CandidateRows random_rows(Eigen::Index runs, Eigen::Index terms, Eigen::Index leaks, unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-300, 300);
  auto fill = [&](Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols) {
    m.resize(rows, cols);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = std::ldexp(mantissa(random), exponent(random));
  };
  CandidateRows r;
  fill(r.regressors, runs, terms);
  fill(r.leaks, runs, leaks);
  fill(r.natural, runs, terms);
  Eigen::MatrixXd column;
  fill(column, runs, 1);
  r.scatter = column;
  fill(column, runs, 1);
  r.noise = column;
  fill(column, runs, 1);
  r.duration = column;
  r.leaks(0, 0) = -0.0;
  r.leaks(1, 0) = std::numeric_limits<double>::denorm_min();
  r.noise[0] = std::numeric_limits<double>::max();
  r.scatter[0] = std::numeric_limits<double>::min();
  return r;
}

bool same_bits(const CandidateRows& a, const CandidateRows& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.rows() == y.rows() && x.cols() == y.cols() &&
           std::memcmp(x.data(), y.data(), sizeof(double) * std::size_t(x.size())) == 0;
  };
  return same(a.regressors, b.regressors) && same(a.leaks, b.leaks) && same(a.scatter, b.scatter) &&
         same(a.noise, b.noise) && same(a.natural, b.natural) && same(a.duration, b.duration);
}

const std::string kKey(64, 'a');

TEST_F(CandidateCache, RowsReadBackBitForBit) {
  const CandidateRows rows = random_rows(37, 3, 52, 1);
  ASSERT_TRUE(write_candidate_cache(folder_, kKey, rows));
  const std::optional<CandidateRows> back = read_candidate_cache(folder_, kKey, 37, 3);
  ASSERT_TRUE(back.has_value());
  EXPECT_TRUE(same_bits(*back, rows));
  EXPECT_TRUE(std::signbit(back->leaks(0, 0)));
}

TEST_F(CandidateCache, EveryMismatchIsAMiss) {
  const CandidateRows rows = random_rows(20, 3, 5, 2);
  ASSERT_TRUE(write_candidate_cache(folder_, kKey, rows));
  const fs::path file = candidate_cache_file(folder_, kKey);
  EXPECT_FALSE(read_candidate_cache(folder_, std::string(64, 'b'), 20, 3));  // no file of that key
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 21, 3));                  // other candidates
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 20, 4));                  // other free terms
  EXPECT_FALSE(read_candidate_cache(folder_, "short", 20, 3));
  EXPECT_FALSE(read_candidate_cache(fs::path(), kKey, 20, 3));
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  auto rewrite = [&file](const std::string& content) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << content;
  };
  // One bit of one number flipped: the digest of the numbers no longer matches.
  std::string flipped = bytes;
  flipped[bytes.size() / 2] = char(flipped[bytes.size() / 2] ^ 1);
  rewrite(flipped);
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 20, 3));
  rewrite(bytes.substr(0, bytes.size() - 1));  // truncated
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 20, 3));
  rewrite(bytes + "x");  // a byte too many
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 20, 3));
  rewrite("");
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 20, 3));
  rewrite(bytes);  // the check itself: the file as written is read
  EXPECT_TRUE(read_candidate_cache(folder_, kKey, 20, 3));
}

TEST_F(CandidateCache, KeysChangeWithEveryInput) {
  Config config = bundled_example();
  ASSERT_FALSE(config.numbers_sha256.empty());
  std::vector<DesignRun> runs(3);
  for (int k = 0; k < 3; ++k) runs[std::size_t(k)].g_level = 5.0 * (k + 1);
  const std::string key = candidate_cache_key(config, runs);
  ASSERT_EQ(key.size(), 64u);
  EXPECT_EQ(candidate_cache_key(config, runs), key);  // deterministic
  std::vector<DesignRun> moved = runs;
  moved[1].phase = std::nextafter(moved[1].phase, 1.0);  // one ulp of one variable
  EXPECT_NE(candidate_cache_key(config, moved), key);
  moved = runs;
  moved[2].platform = PlatformMode::fixed;
  EXPECT_NE(candidate_cache_key(config, moved), key);
  EXPECT_NE(candidate_cache_key(config, {runs[0], runs[1]}), key);
  // A comment or a [certificate] leaves the numbers, so the rows, as they are; the arm's radius does not.
  const std::string text(bundled_example_text());
  const Config worded = parse_config(text + "\n# another file\n[certificate]\noperator = \"A. Engineer\"\n", "w.toml");
  EXPECT_EQ(candidate_cache_key(worded, runs), key);
  std::string radius = text;
  radius.replace(radius.find("radius = \"2.5 m\""), 16, "radius = \"2.6 m\"");
  const Config other = parse_config(radius, "other.toml");
  EXPECT_NE(candidate_cache_key(other, runs), key);
  clear_fingerprints(config);  // changed in code: describes no file, never cached
  EXPECT_EQ(candidate_cache_key(config, runs), "");
}

TEST_F(CandidateCache, TheFolderKeepsTheNewestFiles) {
  const CandidateRows rows = random_rows(4, 3, 2, 3);
  std::vector<std::string> keys;
  for (int k = 0; k < kMaxCandidateCacheFiles + 3; ++k) {
    keys.push_back(std::string(63, 'c') + char('a' + k));
    ASSERT_TRUE(write_candidate_cache(folder_, keys.back(), rows));
    // Modification times a second apart and in the past (the file being written is the newest), so that the
    // order does not depend on the file system's resolution.
    fs::last_write_time(candidate_cache_file(folder_, keys.back()),
                        fs::file_time_type::clock::now() - std::chrono::seconds(100 - k));
  }
  ASSERT_TRUE(write_candidate_cache(folder_, keys.back(), rows));  // evicts once more
  int kept = 0;
  for (const auto& e : fs::directory_iterator(folder_)) kept += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(kept, kMaxCandidateCacheFiles);
  for (std::size_t k = 0; k < keys.size(); ++k)
    EXPECT_EQ(fs::exists(candidate_cache_file(folder_, keys[k])), k >= 3) << k;
}

TEST_F(CandidateCache, AFolderThatCannotBeWrittenIsNoCache) {
  std::ofstream(folder_) << "a file where the folder would be\n";
  const CandidateRows rows = random_rows(4, 3, 2, 4);
  EXPECT_FALSE(write_candidate_cache(folder_, kKey, rows));
  EXPECT_FALSE(read_candidate_cache(folder_, kKey, 4, 3));
  fs::remove(folder_);
}

// Through the verb: the first design computes and stores the rows, the second reads them and designs the same
// plan, bit for bit; fresh_candidates computes them again, to the same plan. A small design space (192
// candidates) keeps it short.
TEST_F(CandidateCache, ASecondDesignReadsTheRows) {
  const Config config =
      parse_config(std::string(bundled_example_text()) +
                       "\n[design]\ng_step = \"5 g\"\nturn_fractions = 4\nphase_step = \"90 "
                       "deg\"\nazimuth_step = \"180 deg\"\nstarts = 2\n",
                   "design_cache_test.toml");
  verbs::DesignOptions options;
  options.cache_folder = folder_;
  const verbs::DesignResult first = verbs::design(config, options);
  EXPECT_FALSE(first.candidates_from_cache);
  const verbs::DesignResult second = verbs::design(config, options);
  EXPECT_TRUE(second.candidates_from_cache);
  options.fresh_candidates = true;
  const verbs::DesignResult fresh = verbs::design(config, options);
  EXPECT_FALSE(fresh.candidates_from_cache);
  for (const verbs::DesignResult* r : {&second, &fresh}) {
    EXPECT_EQ(r->designed_objective, first.designed_objective);
    ASSERT_EQ(r->designed.plan.runs.size(), first.designed.plan.runs.size());
    for (std::size_t j = 0; j < first.designed.plan.runs.size(); ++j) {
      EXPECT_EQ(r->designed.plan.runs[j].g_level, first.designed.plan.runs[j].g_level);
      EXPECT_EQ(r->designed.plan.runs[j].duration, first.designed.plan.runs[j].duration);
    }
    EXPECT_EQ(r->after.budget.expanded_uncertainty, first.after.budget.expanded_uncertainty);
  }
}

}  // namespace
}  // namespace ccal
