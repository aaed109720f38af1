#pragma once

/// The registry of effects: one line per effect, X(enumerator, describer), in the order of
/// effects::Kind, of reports and of model files. `describer` is the function an effect's own file
/// in src/model/effects/ defines, returning its EffectDescription (effect_description.h). Adding
/// an effect is that file, its test and one line here (docs/contributing.md, "Adding an effect").
#define PE_EFFECT_LIST(X)                         \
  X(kSupplyResistance, supplyResistanceEffect)    \
  X(kAirDensity, airDensityEffect)                \
  X(kGroundEffect, groundEffectEffect)            \
  X(kThrustLoss, thrustLossEffect)                \
  X(kMotorTemperature, motorTemperatureEffect)    \
  X(kClimbInflow, climbInflowEffect)              \
  X(kEscOffset, escOffsetEffect)                  \
  X(kTranslationalLift, translationalLiftEffect)
