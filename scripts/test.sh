#!/usr/bin/env bash
# Quick start (2): install dependencies, build, and run the whole test suite through ctest.
# MASSPROPS_SANITIZE=ON runs it under AddressSanitizer + UndefinedBehaviorSanitizer instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=$(bash "$root/scripts/build.sh" | tail -n 1)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/tests/lsan.supp:print_suppressions=0}
# Long simulations run once, in the Release run: under the sanitizers their code runs through the
# shorter tests of the same steps (a box resting, a ball rolling, one drop), not for minutes. The
# golden files (the same bits under the sanitizers: their code paths run in the unit, CLI and
# hostile tests there) and the browser's page tests (JavaScript) run once too.
exclude=()
if [ "${MASSPROPS_SANITIZE:-OFF}" = ON ]; then
  exclude=(-E '^(MeshContact\.StackOfTenMeshBoxesStands|Contact\.StackOfTenBoxesStands|Drops\.BoxLandsOnItsLargeFacesAndRestitutionMatters|Drops\.CubeAndTetrahedronLandOnEveryFaceAlike|Drops\.FourTimesTheDropsHalveTheInterval|Simulation\.ContactExamples|MeshContact\.RingSlidesDownAPegThatItsHullCannotPass|Scene\.PileInABinSettlesInsideIt|Friction\.BoxesAtRestOnInclinesBelowStaticFrictionStayPut|Joints\.MeshPendulumPeriodAtLargeAmplitude|Joints\.DoublePendulumEnergyHasNoSecularDrift|Joints\.LagrangeTopNutatesBetweenTheRootsAtThePeriodByQuadrature|Joints\.LongChainsOnTheRecursionAgreeWithTheDenseFactor|peers|golden|rbsim_page|rbsim_viewer_bundle)$')
fi
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" "${exclude[@]}"
