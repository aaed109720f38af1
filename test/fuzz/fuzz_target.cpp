// One libFuzzer executable per reader: PE_FUZZ_INPUT names it (fuzz_inputs.h). The reader's
// documented refusal (InputError) is a normal outcome; anything else escaping feed() aborts the
// process, and libFuzzer keeps the input as a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const propulsion_estimator::fuzz::FuzzInput& input = propulsion_estimator::fuzz::fuzzInput(PE_FUZZ_INPUT);
  input.feed(data, size);
  return 0;
}
