#!/usr/bin/env bash
# Builds the mesh-reader fuzzer with clang (-fsanitize=fuzzer,address,undefined) and runs it for a
# bounded time, seeded with the shipped meshes (examples/meshes) and the regression inputs
# (tests/data/fuzz). Exits non-zero when the fuzzer finds a crash, a sanitizer report, an
# uncaught exception other than MeshError, a timeout or excessive memory; the input is then in
# $BUILD/artifacts/ (turn it into a test in tests/geometry/test_fuzz_regressions.cpp).
# Usage: fuzz/run-fuzz.sh [SECONDS (default 60)] [BUILD_DIR (default build-fuzz)]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
build="${2:-build-fuzz}"

cmake -S fuzz -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)"

# A working corpus outside the source tree (the fuzzer adds the inputs it finds interesting).
corpus="$build/corpus"
mkdir -p "$corpus" "$build/artifacts"
seeds=(examples/meshes)
[ -d tests/data/fuzz ] && seeds+=(tests/data/fuzz)

# -timeout: one input may take at most 10 s (a hang is a bug); -rss_limit_mb / -malloc_limit_mb:
# a small file must not make the reader allocate gigabytes (a header count is not a licence to
# allocate); -max_len: large enough for the shipped meshes (1.3 kB) with room to grow.
echo "run-fuzz: fuzzing the mesh reader for ${seconds} s (log: $build/fuzz.log)"
status=0
"$build/fuzz_mesh_reader" "$corpus" "${seeds[@]}" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=8192 \
  -print_final_stats=1 -artifact_prefix="$build/artifacts/" >"$build/fuzz.log" 2>&1 || status=$?
if [ "$status" -ne 0 ]; then
  # The report: from the sanitizer's or libFuzzer's first error line on.
  sed -n '/==ERROR\|ERROR: libFuzzer\|deadly signal\|runtime error\|terminate called/,$p' "$build/fuzz.log" | head -n 80 >&2
  echo "run-fuzz: the fuzzer found a failing input (exit $status); see $build/artifacts/" >&2
  exit "$status"
fi
grep -E '^(Done|stat::)' "$build/fuzz.log" || true
echo "run-fuzz: no crash in ${seconds} s"
