// The integrators: one row each. Names are parsed and printed from here only.

#include <stdexcept>

#include "integrator.h"

namespace dynamics {
namespace internal {
namespace {

constexpr IntegratorInfo kTable[] = {
    {Integrator::kImplicitMidpoint, "implicit-midpoint", StepImplicitMidpoint, true},
    {Integrator::kSplitting, "splitting", StepSplitting, true},
    {Integrator::kRK4, "rk4", StepRK4, false},
    {Integrator::kExplicitEuler, "explicit-euler", StepExplicitEuler, false},
    {Integrator::kQuaternionEuler, "quaternion-euler", StepQuaternionEuler, false},
    {Integrator::kSymplecticEuler, "symplectic-euler", StepSymplecticEuler, false},
    {Integrator::kImplicitGyroscopic, "implicit-gyroscopic", StepImplicitGyroscopic, false},
    {Integrator::kExactSplitting, "exact-splitting", StepExactSplitting, true},
};
static_assert(std::size(kTable) == std::size(kAllIntegrators), "one row per integrator");

}  // namespace

const IntegratorInfo& Info(Integrator integrator) {
  for (const IntegratorInfo& row : kTable) {
    if (row.id == integrator) return row;
  }
  throw std::invalid_argument("unknown integrator");
}

}  // namespace internal

const char* IntegratorName(Integrator integrator) { return internal::Info(integrator).name; }

std::string IntegratorNames() {
  std::string s;
  for (const auto& row : internal::kTable) s += (s.empty() ? "" : ", ") + std::string(row.name);
  return s;
}

Integrator ParseIntegrator(const std::string& name) {
  for (const auto& row : internal::kTable) {
    if (name == row.name) return row.id;
  }
  throw std::invalid_argument("unknown integrator '" + name + "' (" + IntegratorNames() + ")");
}

}  // namespace dynamics
