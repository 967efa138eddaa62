#pragma once
// The cached rows of `ccal design`'s candidate runs (uncertainty/design_search.hpp, CandidateRows) kept in a
// file, so that designing again from the same configuration skips their computation, most of a design's time
// (docs/model.md §15.1).
//
// A file holds the rows of one set of candidate runs under one configuration and one build of ccal. Its name
// is its key: the SHA-256 of what changes the configuration's numbers (Config::numbers_sha256: not its
// [certificate] or [design], which leave the rows as they are), of ccal's version, of the file
// ccal's code was loaded from (the program or the Python module: any rebuild gets keys of its own) and of
// every candidate run's variables, bit for bit. A configuration changed in code (no text fingerprint) has no
// key and is never cached. A file is read back only when its header, key, sizes and the SHA-256 of its
// numbers all match; anything else (a truncated, foreign or damaged file) is a miss, and the rows are
// computed and the file written again. The numbers are stored as their bytes: rows read back equal the rows
// computed, bit for bit.
//
// Writing is atomic (a temporary file renamed over the name) and never an error: a folder that cannot be
// written only means no cache. The folder keeps the kMaxCandidateCacheFiles most recently written files.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/design_search.hpp"

namespace ccal {

inline constexpr int kMaxCandidateCacheFiles = 8;

// $XDG_CACHE_HOME/ccal, else $HOME/.cache/ccal; empty when neither variable is set.
std::filesystem::path default_cache_folder();

// The key of these candidate runs under this configuration (64 hex digits), or empty when they cannot be
// cached.
std::string candidate_cache_key(const Config& config, const std::vector<DesignRun>& runs);

// The file of a key in a folder.
std::filesystem::path candidate_cache_file(const std::filesystem::path& folder, const std::string& key);

// The rows stored under `key` for `runs` candidate runs and `terms` free terms, or nothing (no such file, or
// one that does not match in every respect).
std::optional<CandidateRows> read_candidate_cache(const std::filesystem::path& folder, const std::string& key,
                                                  Eigen::Index runs, Eigen::Index terms);

// Stores the rows under `key` (creating the folder), then removes all but the newest kMaxCandidateCacheFiles
// cache files of the folder. Returns whether the file was written.
bool write_candidate_cache(const std::filesystem::path& folder, const std::string& key,
                           const CandidateRows& rows) noexcept;

}  // namespace ccal
