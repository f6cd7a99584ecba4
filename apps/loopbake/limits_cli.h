// loopbake's resource-limit options and memory report (lt::Limits, looptess/tools/baker.h).
// Part of the loopbake tool, not of the library.
#pragma once

#include "looptess/tools/baker.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace lt::cli {

// The help text of the limit options, with their defaults (from Limits{}).
std::string limitsUsage();

// When `opt` is a limit option (--max-faces, --max-vertices, --max-valence,
// --max-input-bytes, --max-output-bytes, --max-memory-mb): parses `value` into
// `limits` (a Usage status when it is not an integer in the option's range) and
// returns true. Returns false, touching nothing, for any other option.
bool applyLimitOption(const std::string& opt, const std::string& value, Limits& limits, Status& st);

// Whether `opt` is one of the options above.
bool isLimitOption(const std::string& opt);

// Checks the size of file `path` against limits.maxInputBytes before it is read
// (a file that cannot be examined passes: reading it reports why).
Status checkInputFile(const std::string& path, const Limits& limits);

// The process's peak resident set so far, in bytes (getrusage ru_maxrss), or 0.
uint64_t peakRssBytes();

// -v: one line "memory: estimated ... (limit ...), refined faces ..., peak resident ...".
void printMemory(const MemoryStats& memory, const Limits& limits);

// --json: the limits in effect, and the memory figures (peak resident set only when
// `verbose`: it varies from run to run, and reports are byte-stable without -v).
nlohmann::ordered_json limitsJson(const Limits& limits);
nlohmann::ordered_json memoryJson(const MemoryStats& memory, bool verbose);

}  // namespace lt::cli
