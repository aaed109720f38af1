// Thrust against measured rpm: fitted on a bench log's rpm column, carried by the model file.
#include <gtest/gtest.h>

#include <cmath>

#include "bench_sweep_fixture.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/fitting/rpm_thrust_fit.h"
#include "propulsion_estimator/model/model_yaml.h"

namespace pe = propulsion_estimator;

TEST(RpmThrustFit, RecoversThePropellersSpeedToThrustLaw) {
  // SmoothChain: 9e-6 g per rpm^2, noise 4 g on the thrust and 30 rpm on the speed.
  const SweepSet sweeps = syntheticSweeps();
  const pe::RpmThrust fit = pe::fitRpmThrust(sweeps.logs, 1.2);
  const double truth = 9.0e-6 * pe::kStandardGravity / 1000.0;
  for (double rpm : {4000.0, 6000.0, 8000.0}) {
    EXPECT_NEAR(fit.thrustN(rpm), truth * rpm * rpm, 0.01 * truth * rpm * rpm) << rpm;
  }
  EXPECT_GT(fit.rows, 500);
  EXPECT_LT(fit.rms_n, 0.1);
  // Denser air, more thrust at the same speed; NaN is the bench's air.
  EXPECT_NEAR(fit.thrustN(6000.0, 1.32) / fit.thrustN(6000.0), 1.1, 1e-12);
  EXPECT_EQ(fit.thrustN(6000.0, pe::kNaN), fit.thrustN(6000.0));
  EXPECT_EQ(fit.thrustN(0.0), 0.0);
}

TEST(RpmThrustFit, RefusesLogsWithoutRpm) {
  SweepSet sweeps = syntheticSweeps();
  for (pe::BenchLog& log : sweeps.logs) log.column(pe::BenchColumn::kRpm).clear();
  try {
    pe::fitRpmThrust(sweeps.logs, 1.2);
    FAIL() << "no rpm column accepted";
  } catch (const pe::DataError& e) {
    EXPECT_EQ(std::string(e.what()), "sweep_0.csv: no rpm column: thrust from rpm cannot be fitted");
  }
}

TEST(RpmThrustFit, RefusesRowsAllAtOneSpeed) {
  SweepSet sweeps = syntheticSweeps();
  for (pe::BenchLog& log : sweeps.logs) {
    for (double& rpm : log.column(pe::BenchColumn::kRpm)) rpm = 5000.0;
  }
  try {
    pe::fitRpmThrust(sweeps.logs, 1.2);
    FAIL() << "one speed accepted";
  } catch (const pe::DataError& e) {
    EXPECT_EQ(std::string(e.what()),
              "sweep_0.csv: the rows with rpm and thrust are all at one speed: thrust from rpm cannot be fitted");
  }
}

TEST(RpmThrustFit, TheModelFileCarriesItAndReadsItBack) {
  const std::string thesis = pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  pe::PropulsionModel model = pe::parseModelYaml(thesis, "thesis");
  EXPECT_FALSE(model.rpmThrust());
  pe::RpmThrust fit;
  fit.n_per_rpm2 = 8.8e-8;
  fit.n_per_rpm = -1.5e-5;
  fit.rms_n = 0.05;
  fit.rows = 1200;
  model.setRpmThrust(fit);
  const pe::PropulsionModel read = pe::parseModelYaml(pe::modelToYaml(model), "written");
  ASSERT_TRUE(read.rpmThrust());
  EXPECT_EQ(read.rpmThrust()->n_per_rpm2, 8.8e-8);
  EXPECT_EQ(read.rpmThrust()->n_per_rpm, -1.5e-5);
  EXPECT_EQ(read.rpmThrust()->rms_n, 0.05);
  EXPECT_EQ(read.rpmThrust()->rows, 1200);
  EXPECT_EQ(read.rpmThrust()->bench_air_density_kg_m3, read.metadata().benchAirDensity());
  EXPECT_EQ(pe::modelToYaml(read), pe::modelToYaml(model));
  try {
    pe::parseModelYaml(thesis + "thrust_from_rpm: {n_per_rpm2: -1.0e-8, n_per_rpm: 0, rms_n: 0.1, rows: 10}\n", "bad");
    FAIL() << "a negative coefficient accepted";
  } catch (const pe::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("thrust_from_rpm.n_per_rpm2: -1e-08 is not positive"), std::string::npos)
        << e.what();
  }
}
