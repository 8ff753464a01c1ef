#pragma once
// Load and speed ramps: a value rising from 0 at t = 0 to its full value at
// t = ramp_time with zero rate at both ends, and held there afterwards. Two
// curves, named, because scenes were tuned with each:
//   RampCurve::smoothstep    3u^2 - 2u^3           (zero slope at both ends;
//                                                    the tyre's load, speed and torque)
//   RampCurve::smootherstep  10u^3 - 15u^4 + 6u^5  (zero slope and curvature at
//                                                    both ends; Abaqus's SMOOTH STEP
//                                                    amplitude; the SPH bodies' load)
// with u = t / ramp_time. A ramp time <= 0 means the full value at once. t < 0
// is not clamped (callers start their ramps at t = 0).
namespace cosim {

enum class RampCurve { smoothstep, smootherstep };

// `full` times the ramp's fraction at time t. Each curve multiplies in the
// order its callers always used, so that results did not change when the two
// copies became this one.
inline double ramp(RampCurve curve, double t, double ramp_time, double full = 1.0) {
  if (ramp_time <= 0.0 || t >= ramp_time) return full;
  const double u = t / ramp_time;
  if (curve == RampCurve::smoothstep) return full * (u * u * (3.0 - 2.0 * u));
  return full * u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
}

}  // namespace cosim
