// Per-message cost of the ROS layer's part: decoding a 16-channel RCOut from a ShapeShifter.
#include <string>

#include <benchmark/benchmark.h>

#include "propulsion_estimator/codecs/rcout_codec.h"

namespace pe = propulsion_estimator;

namespace {

void BM_RcOutDecode(benchmark::State& state) {
  pe::RcOutMessage message;
  message.channels.assign(16, 1690);
  const topic_tools::ShapeShifter shifter = pe::encodeRcOut(message);
  pe::RcOutDecoder decoder;
  pe::RcOutMessage decoded;
  std::string error;
  for (auto _ : state) benchmark::DoNotOptimize(decoder.decode(shifter, &decoded, &error));
}
BENCHMARK(BM_RcOutDecode);

}  // namespace

BENCHMARK_MAIN();
