#pragma once
// The kept values of a Monte Carlo run (verbs::MonteCarloOptions::keep_samples) as a file, for
// `ccal montecarlo --samples-out FILE`: one row per trial in trial order, one column per coefficient, each
// value in its coefficient's display unit (that of the JSON and text outputs).
//   CSV: a header row `K0 [deg/s],K2 [deg/s/g^2],…`, then the values with 17 significant digits (they read
//        back to the same doubles).
//   NPY: NumPy's format 1.0 (numpy.lib.format): little-endian float64, shape (M, n_coefficients), C order;
//        numpy.load gives the array.
// The file is produced in blocks of kSampleBlockRows rows handed to a sink, so that its text is never all in
// memory: beyond the kept values (8 bytes per trial and coefficient) it needs at most one block, about
// kSampleBlockRows · 26 bytes per coefficient.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "ccal/verbs/montecarlo.hpp"

namespace ccal::render {

inline constexpr std::size_t kSampleBlockRows = 4096;

enum class SampleFileFormat { csv, npy };

// By the path's extension: `.npy` (any case) is NPY, anything else CSV.
SampleFileFormat sample_file_format(std::string_view path);

// Receives the file block by block; returns false when a write failed (the writer then stops).
using ChunkSink = std::function<bool(std::string_view)>;

// Writes the file through `sink`; false if the sink failed. Throws InputError when the result kept no
// samples.
bool write_samples(const verbs::MonteCarloResult& result, SampleFileFormat format, const ChunkSink& sink);

}  // namespace ccal::render
