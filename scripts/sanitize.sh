#!/usr/bin/env bash
# Sanitizer builds of parts of the suite (docs/reliability.md, "Sanitizers and
# warnings"), each in its own build folder, built and run:
#   scripts/sanitize.sh address   AddressSanitizer + UndefinedBehaviorSanitizer:
#                                 the unit tests (build-asan/)
#   scripts/sanitize.sh thread    ThreadSanitizer: the transport and session
#                                 tests, whose heartbeat threads write the run
#                                 control topic beside the main loop (build-tsan/)
# Any report fails the test that made it (halt_on_error). .ci/run runs both.
set -euo pipefail
cd "$(dirname "$0")/.."
MODE=${1:?"scripts/sanitize.sh address|thread"}
case $MODE in
  address)
    DIR=build-asan FLAGS=address,undefined
    # The unit and small validation tests (under 20 s each in Release); the
    # runs of whole programs (tyre rolling, coupled runs, restarts) are left to
    # the Release suite: under ASan they would take hours.
    TESTS=(test_facet_tag test_schema_defaults test_participant test_checkpoint test_signal test_ramp
           test_result_references test_surface_exchange test_vtk test_plot test_process test_penalty_contact
           test_quad_facet test_mdpc test_kernels test_neighbours test_particle_outputs test_water_eos
           test_scene_validation test_stability test_run_outputs test_sph_surface_contact test_sph_substeps
           test_sph_active_domain test_sph_drain test_sph_tensile test_cylinder_contact test_rut test_axisym_fe
           test_tyre_elements test_tyre_hex8_batch test_tyre_materials test_tyre_lame test_tyre_geometry
           test_tyre_tread_block test_hydroplaning test_coupler_forces test_coupler_friction test_coupler_wire
           test_transport_options)
    export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
    export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    ;;
  thread)
    DIR=build-tsan FLAGS=thread
    TESTS=(test_session test_transport_roundtrip test_transport_lockstep)
    # Races inside the DDS libraries (not built with TSan, so their atomics are
    # invisible to it) are theirs; any race with a frame of ours is reported.
    export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/tests/support/tsan.supp"
    ;;
  *) echo "scripts/sanitize.sh: give address or thread" >&2; exit 2 ;;
esac
cmake -S . -B "$DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCOSIM_SANITIZE="$FLAGS" -DCOSIM_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$DIR" -j "${JOBS:-$(nproc)}" --target "${TESTS[@]}"
regex=$(IFS='|'; echo "^(${TESTS[*]})\$")
ctest --test-dir "$DIR" -R "$regex" --output-on-failure -j "${JOBS:-2}"
