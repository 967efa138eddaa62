#include "ccal/uncertainty/candidate_cache.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string_view>

#include "ccal/core/sha256.hpp"
#include "ccal/version.hpp"

namespace ccal {

namespace {

namespace fs = std::filesystem;

// The file: this header line, the key (64 hex digits), the three sizes (int64), the numbers (double, in the
// order of numbers_of), and the SHA-256 of the numbers' bytes (64 hex digits). The machine's byte order: a
// file from a machine of the other order fails its check and is a miss.
constexpr std::string_view kMagic = "ccal candidate rows 1\n";
constexpr std::string_view kPrefix = "candidates-";
constexpr std::string_view kSuffix = ".bin";
constexpr std::size_t kDigest = 64;

std::string bytes_of(const void* data, std::size_t size) {
  return std::string(static_cast<const char*>(data), size);
}

// The blocks of numbers of a set of rows, in the file's order, sized for runs × terms with `leaks` columns.
std::array<Eigen::Map<Eigen::MatrixXd>, 6> blocks_of(CandidateRows& rows, Eigen::Index runs,
                                                     Eigen::Index terms, Eigen::Index leaks) {
  rows.regressors.resize(runs, terms);
  rows.leaks.resize(runs, leaks);
  rows.scatter.resize(runs);
  rows.noise.resize(runs);
  rows.natural.resize(runs, terms);
  rows.duration.resize(runs);
  using Map = Eigen::Map<Eigen::MatrixXd>;
  return {Map(rows.regressors.data(), runs, terms), Map(rows.leaks.data(), runs, leaks),
          Map(rows.scatter.data(), runs, 1),        Map(rows.noise.data(), runs, 1),
          Map(rows.natural.data(), runs, terms),    Map(rows.duration.data(), runs, 1)};
}

// The numbers of a set of rows as bytes, in the order of blocks_of.
std::string numbers_of(const CandidateRows& rows) {
  std::string out;
  auto add = [&out](const auto& m) { out += bytes_of(m.data(), sizeof(double) * std::size_t(m.size())); };
  add(rows.regressors);
  add(rows.leaks);
  add(rows.scatter);
  add(rows.noise);
  add(rows.natural);
  add(rows.duration);
  return out;
}

bool is_cache_file(const fs::path& p) {
  const std::string name = p.filename().string();
  return name.size() == kPrefix.size() + kDigest + kSuffix.size() && name.starts_with(kPrefix) &&
         name.ends_with(kSuffix);
}

// Keeps the newest kMaxCandidateCacheFiles cache files of the folder (by modification time).
void evict_old_files(const fs::path& folder) {
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    if (!is_cache_file(e.path()) || !e.is_regular_file(ec)) continue;
    files.emplace_back(e.last_write_time(ec), e.path());
  }
  if (files.size() <= std::size_t(kMaxCandidateCacheFiles)) return;
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t k = std::size_t(kMaxCandidateCacheFiles); k < files.size(); ++k)
    fs::remove(files[k].second, ec);
}

// The SHA-256 of the file this code was loaded from (the program, or the Python module), once per process:
// a rebuild of ccal from changed sources, committed or not, gets keys of its own. Empty when it cannot be
// read.
const std::string& build_fingerprint() {
  static const std::string fingerprint = [] {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&default_cache_folder), &info) == 0 || info.dli_fname == nullptr)
      return std::string();
    std::ifstream in(info.dli_fname, std::ios::binary);
    if (!in) return std::string();
    Sha256 hash;
    std::string block(std::size_t(1) << 20, '\0');
    while (in) {
      in.read(block.data(), std::streamsize(block.size()));
      hash.update(std::string_view(block.data(), std::size_t(in.gcount())));
    }
    return in.eof() ? hash.hex() : std::string();
  }();
  return fingerprint;
}

}  // namespace

fs::path default_cache_folder() {
  if (const char* cache = std::getenv("XDG_CACHE_HOME"); cache && *cache) return fs::path(cache) / "ccal";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "ccal";
  return {};
}

std::string candidate_cache_key(const Config& config, const std::vector<DesignRun>& runs) {
  if (config.numbers_sha256.empty() || build_fingerprint().empty()) return {};
  Sha256 key;
  key.update(kMagic).update(version()).update("\n").update(build_fingerprint()).update("\n");
  key.update(config.numbers_sha256);
  // The rows are scaled by the tolerances as the Config holds them, which need not be the text's (the design
  // credits what declared encoders will measure): their bounds, laws and groups are part of the key.
  for (const Tolerance& t : config.tolerances) {
    key.update(t.id).update("\n").update(t.group).update("\n");
    const int law = int(t.distribution);
    key.update(bytes_of(&t.bound, sizeof t.bound)).update(bytes_of(&law, sizeof law));
  }
  for (const Correlation& c : config.correlations)
    key.update(c.first).update("\n").update(c.second).update("\n").update(bytes_of(&c.r, sizeof c.r));
  for (const DesignRun& r : runs) {
    for (double v : {r.g_level, r.duration, r.phase, r.arm_azimuth}) key.update(bytes_of(&v, sizeof v));
    for (int v : {int(r.phase_kind), int(r.mounting), int(r.platform)}) key.update(bytes_of(&v, sizeof v));
  }
  return key.hex();
}

fs::path candidate_cache_file(const fs::path& folder, const std::string& key) {
  return folder / (std::string(kPrefix) + key + std::string(kSuffix));
}

std::optional<CandidateRows> read_candidate_cache(const fs::path& folder, const std::string& key,
                                                  Eigen::Index runs, Eigen::Index terms) {
  if (key.size() != kDigest || folder.empty()) return std::nullopt;
  std::ifstream in(candidate_cache_file(folder, key), std::ios::binary);
  if (!in) return std::nullopt;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t at = 0;
  auto take = [&](std::size_t n) -> std::string_view {
    if (text.size() - at < n) return {};
    const std::string_view piece(text.data() + at, n);
    at += n;
    return piece;
  };
  if (take(kMagic.size()) != kMagic || take(kDigest) != key) return std::nullopt;
  std::int64_t sizes[3];
  const std::string_view size_bytes = take(sizeof sizes);
  if (size_bytes.size() != sizeof sizes) return std::nullopt;
  std::memcpy(sizes, size_bytes.data(), sizeof sizes);
  if (sizes[0] != runs || sizes[1] != terms || sizes[2] < 0 || sizes[2] > 100000) return std::nullopt;
  const auto leaks = Eigen::Index(sizes[2]);
  const std::size_t count = std::size_t(runs) * std::size_t(2 * terms + leaks + 3);
  const std::string_view numbers = take(sizeof(double) * count);
  const std::string_view digest = take(kDigest);
  if (digest.size() != kDigest || at != text.size() || sha256_hex(numbers) != digest) return std::nullopt;
  CandidateRows rows;
  std::size_t offset = 0;
  for (Eigen::Map<Eigen::MatrixXd>& block : blocks_of(rows, runs, terms, leaks)) {
    const std::size_t n = sizeof(double) * std::size_t(block.size());
    std::memcpy(block.data(), numbers.data() + offset, n);
    offset += n;
  }
  return rows;
}

bool write_candidate_cache(const fs::path& folder, const std::string& key,
                           const CandidateRows& rows) noexcept {
  if (key.size() != kDigest || folder.empty()) return false;
  fs::path temporary;
  try {
    std::error_code ec;
    fs::create_directories(folder, ec);
    const fs::path file = candidate_cache_file(folder, key);
    temporary = file;
    temporary += ".tmp-" + std::to_string(::getpid());
    const std::string numbers = numbers_of(rows);
    const std::int64_t sizes[3] = {rows.regressors.rows(), rows.regressors.cols(), rows.leaks.cols()};
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      out << kMagic << key;
      out.write(reinterpret_cast<const char*>(sizes), sizeof sizes);
      out << numbers << sha256_hex(numbers);
      out.close();
      if (!out) throw std::runtime_error("not written");
    }
    fs::rename(temporary, file);  // atomic: a reader sees the old file or the whole new one
    evict_old_files(folder);
    return true;
  } catch (...) {
    std::error_code ec;
    if (!temporary.empty()) fs::remove(temporary, ec);
    return false;
  }
}

}  // namespace ccal
