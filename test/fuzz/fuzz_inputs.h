#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace propulsion_estimator {
namespace fuzz {

/// One reader under fuzzing: `feed` hands it the bytes of one input (a file's text, or for
/// rcout a serialized message) and returns true when the input was accepted, false when it was
/// refused with InputError (or its subclasses: the documented refusal, a one-line message).
/// Anything else escapes it: another exception, or a broken invariant of an accepted input
/// (std::logic_error), which the fuzzer and the corpus replay test report as a finding.
struct FuzzInput {
  const char* name;  // the corpus folder test/fuzz/corpus/<name>/ and the executable fuzz_<name>
  bool (*feed)(const std::uint8_t* data, std::size_t size);
};

/// Every fuzzed reader: model_yaml, bench_csv, tyto_csv, flight_manifest, flight_profile,
/// vehicle_urdf, rcout, tare_file, pack_file, ulog, dataflash, flight_bag.
const std::vector<FuzzInput>& fuzzInputs();
/// The reader called `name`; std::invalid_argument listing the names when there is none.
const FuzzInput& fuzzInput(const std::string& name);

}  // namespace fuzz
}  // namespace propulsion_estimator
