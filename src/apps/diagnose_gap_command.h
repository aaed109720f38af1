#pragma once

namespace propulsion_estimator {

// `diagnose_gap --model MODEL.yaml --manifest FLIGHTS.yaml --out DIR [options]`: reads the
// manifest's flight bags (in parallel with --jobs) and diagnoses where the model and the weighed
// flights part. A flight that cannot be used (its bag missing or unreadable, without a required
// topic, a segment outside the bag, a value the manifest refuses) is refused with one line on
// stderr and the others are diagnosed. Returns the process exit status: 0 every flight used,
// 1 a refused input or at least one refused flight (the last line says how many), 2 usage error.
int runDiagnoseGap(int argc, char** argv);

}  // namespace propulsion_estimator
