#!/usr/bin/env bash
# Installs the dependencies, builds panelrad (Release, with the Python module for Debian's
# /usr/bin/python3) and runs the whole test suite with ctest (the C++ tests and pytest);
# then runs the suite a second time under AddressSanitizer + UndefinedBehaviorSanitizer and fuzzes
# the mesh reader for a bounded time. Fails when any step fails.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage's wall time, said when it ends (the whole run must stay well inside CI's limit).
stage_start=$SECONDS
stage() {
  echo "run-tests: $1 took $((SECONDS - stage_start)) s (total $SECONDS s)"
  stage_start=$SECONDS
}
bash cmake/install-deps.sh
stage "installing the dependencies"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPANELRAD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build build -j "$(nproc)"
stage "the Release build"
ctest --test-dir build --output-on-failure -j "$(nproc)"
stage "the Release tests"

# The MPI tests (label mpi): the same Release build with -DPANELRAD_MPI=ON, which adds the MPI
# communicator (panelrad_mpi), makes the program an MPI program and adds the tests run under
# mpirun with 1, 2 and 3 ranks; the library itself is the same, so only the program and those
# tests are built again. One at a time (each runs up to 3 ranks on this machine's cores). Then
# build/ is made MPI-free again, as run-main.sh expects it.
cmake -S . -B build -DPANELRAD_MPI=ON
cmake --build build -j "$(nproc)" --target panelrad_cli test_mpi_solves
ctest --test-dir build --output-on-failure -L mpi
cmake -S . -B build -DPANELRAD_MPI=OFF
cmake --build build -j "$(nproc)" --target panelrad_cli
stage "the MPI build and tests"

# Second build with -fsanitize=address,undefined (PANELRAD_SANITIZE): -O1 with line tables (-g1: a
# report names file and line; full debug information would double the objects and slow every link)
# and with assertions (no NDEBUG: Eigen's and CGAL's own checks are on too). Examples and benchmarks are
# not needed by the tests and are left out. Excluded from this run:
#  - package_consumer: installs the instrumented static libraries and links an outside project
#    without -fsanitize (undefined __asan_* symbols); a packaging test, run by the Release build;
#  - StressNumerics.LargestLevelInSeconds: a size test (cube level 6, n = 49,152, 1.4 GB in
#    Release) that takes minutes under the sanitizers; its code paths run at smaller n in the
#    other stress and fast-operator tests;
#  - the tests labelled "slow" (the paper's tables at n = 3072 and 12288, dense setup of a
#    12288 x 12288 matrix): the same code runs at n <= 768 in the other tests.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
  -DPANELRAD_SANITIZE=ON -DPANELRAD_BUILD_EXAMPLES=OFF -DPANELRAD_BUILD_BENCH=OFF
cmake --build build-asan -j "$(nproc)"
stage "the sanitizer build"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE slow \
  -E '^(package_consumer|StressNumerics\.LargestLevelInSeconds)$'
stage "the sanitizer tests"

# The mesh reader under libFuzzer (clang, with ASan + UBSan) for 60 s, seeded with the shipped
# meshes: fails on any crash, sanitizer report, hang or exception other than MeshError.
bash fuzz/run-fuzz.sh 60 build-fuzz
stage "the fuzzer's build and run"
