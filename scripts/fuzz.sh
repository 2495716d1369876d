#!/usr/bin/env bash
# Builds prt's libFuzzer targets (tests/fuzz) with clang 14, AddressSanitizer and
# UndefinedBehaviorSanitizer in build-fuzz/, and runs them.
# Usage: scripts/fuzz.sh [--ci] [--runs N] [--time SECONDS] [--jobs J] [TARGET...]
#   (no option)   run each target for 10 minutes (long runs by hand; stop with Ctrl-C)
#   --ci          run each target for its fixed number of executions (2-12 s each, the counts
#                 below), seed 1: the fuzz step of .ci/run
#   --runs N      N executions per target;  --time S  S seconds per target
#   --build-only  build the targets and stop
#   --coverage    no fuzzing: replay build-fuzz/corpus/<target> once with -print_coverage=1 and print,
#                 per prt source file the target reaches, the instrumented edges its corpus covers
#   --line-coverage  no fuzzing: build the targets with clang's source-based coverage (no sanitizers) in
#                 build-fuzz-cov/, replay build-fuzz/corpus/<target> (else the seed corpus) once and print
#                 llvm-cov's line, function and region coverage of each prt source file the target runs
#   TARGET        ply obj gltf image prt cprt brdf light probes points (default: all)
# The committed seed corpus tests/fuzz/corpus/<target> is copied to build-fuzz/corpus/<target>, which
# collects the new inputs; crashes go to build-fuzz/artifacts/. Exits non-zero on any crash, sanitizer
# report, leak, timeout (10 s per input) or out-of-memory (2 GiB), printing the reproducer's path.
# Environment: PRT_FUZZ_BUILD_DIR (default build-fuzz).
set -euo pipefail
cd "$(dirname "$0")/.."

all=(ply obj gltf image prt cprt brdf light probes points)
# Executions per target for --ci: about 12 s each at the rates measured on the shared (heavily
# loaded) AMD EPYC development machine, so less on an idle CI machine (tests/fuzz/README.md).
declare -A ci_runs=([ply]=12400 [obj]=8400 [gltf]=10400 [image]=8000 [prt]=28800 [cprt]=28800 [brdf]=6000 [light]=10400 [probes]=26800 [points]=12800)
mode=time; seconds=600; runs=0; build_only=0; targets=()
while (($#)); do
  case "$1" in
    --ci) mode=ci ;;
    --runs) mode=runs; runs="$2"; shift ;;
    --time) mode=time; seconds="$2"; shift ;;
    --build-only) build_only=1 ;;
    --coverage) mode=coverage ;;
    --line-coverage) mode=line-coverage ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    *) targets+=("$1") ;;
  esac
  shift
done
((${#targets[@]})) || targets=("${all[@]}")

build_dir="${PRT_FUZZ_BUILD_DIR:-build-fuzz}"
command -v clang++-14 >/dev/null || { echo "fuzz: clang++-14 is missing (scripts/setup.sh --fuzz installs it)" >&2; exit 1; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
if [ "$mode" = line-coverage ]; then
  cov_dir="${build_dir}-cov"
  command -v llvm-cov-14 >/dev/null || { echo "fuzz: llvm-cov-14 is missing (scripts/setup.sh --tests installs llvm-14)" >&2; exit 1; }
  if [ ! -f "$cov_dir/build.ninja" ]; then
    CC=clang-14 CXX=clang++-14 cmake -S . -B "$cov_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DPRT_BUILD_FUZZ=ON -DPRT_COVERAGE=ON -DPRT_BUILD_TESTS=OFF -DPRT_BUILD_BENCH=OFF -DPRT_BUILD_GL=OFF \
      -DPRT_ARCH= "${launcher[@]}" 2>&1 | grep -v -e PyImath -e '^$' >&2 || true
  fi
  cmake --build "$cov_dir" --target $(printf 'fuzz_%s ' "${targets[@]}")
  for t in "${targets[@]}"; do
    corpus="$build_dir/corpus/$t"
    [ -d "$corpus" ] && [ -n "$(ls -A "$corpus")" ] || corpus="tests/fuzz/corpus/$t"
    rm -f "$cov_dir/$t"-*.profraw
    # %m: one profile per instrumented binary (the image target's dlopen'd backend module writes its own).
    LLVM_PROFILE_FILE="$cov_dir/$t-%p-%m.profraw" "$cov_dir/tests/fuzz/fuzz_$t" -runs=0 -artifact_prefix="$cov_dir/$t-" "$corpus" \
      > "$cov_dir/replay_$t.log" 2>&1 || { echo "fuzz: $t: replay failed ($cov_dir/replay_$t.log)" >&2; exit 1; }
    llvm-profdata-14 merge -sparse "$cov_dir/$t"-*.profraw -o "$cov_dir/$t.profdata"
    echo "fuzz: $t: $(ls "$corpus" | wc -l) inputs from $corpus; line coverage per prt source file it runs:"
    # llvm-cov's columns (paths under src/): regions, missed, cover, functions, missed, executed, lines,
    # missed, cover, ...; files the target never enters are left out.
    objects=()
    [ "$t" = image ] && objects=(-object "$cov_dir/src/image/libprt_image_oiio.so")
    llvm-cov-14 report "$cov_dir/tests/fuzz/fuzz_$t" "${objects[@]}" -instr-profile="$cov_dir/$t.profdata" \
      -ignore-filename-regex='^/usr/|tests/fuzz/' |
      awk '$1 != "Filename" && $1 !~ /^-/ && NF >= 10 {
        if ($7 == "0.00%" && $1 != "TOTAL") next
        printf "  %-34s lines %7s of %5d  functions %7s  regions %7s\n", $1, $10, $8, $7, $4 }'
  done
  exit 0
fi
# The build is also .ci/run's sanitizer build of the tests (configured with them; only test_core and
# test_sh are built there). -O1 with line tables: what AddressSanitizer's documentation suggests, and
# about 15% less compile time than -O2 -g; reports still name file and line.
if [ ! -f "$build_dir/build.ninja" ] || ! grep -q '^PRT_BUILD_TESTS:BOOL=ON' "$build_dir/CMakeCache.txt"; then
  CC=clang-14 CXX=clang++-14 cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
    -DPRT_SANITIZE=address,undefined -DPRT_BUILD_FUZZ=ON -DPRT_BUILD_TESTS=ON -DPRT_BUILD_BENCH=OFF \
    -DPRT_BUILD_GL=OFF -DPRT_ARCH= "${launcher[@]}" 2>&1 | grep -v -e PyImath -e '^$' >&2 || true
fi
cmake --build "$build_dir" --target $(printf 'fuzz_%s ' "${targets[@]}")
((build_only)) && exit 0

mkdir -p "$build_dir/artifacts"
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=0:abort_on_error=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
failed=()
for t in "${targets[@]}"; do
  corpus="$build_dir/corpus/$t"
  [ "$mode" = ci ] && rm -rf "$corpus"  # CI starts from the seed corpus: the same inputs every run
  mkdir -p "$corpus"
  cp -n tests/fuzz/corpus/"$t"/* "$corpus"/ 2>/dev/null || true
  if [ "$mode" = coverage ]; then
    "$build_dir/tests/fuzz/fuzz_$t" -runs=0 -print_coverage=1 "$corpus" 2>&1 |
      awk -v t="$t" -v root="$PWD/src/" '
        /^(COVERED|UNCOVERED)_FUNC: / {
          split($5, e, "/"); file = $NF; sub(/:[0-9]+$/, "", file); gsub(/\/[^\/]+\/\.\.\//, "/", file)
          if (index(file, root) != 1) next
          sub(root, "", file); covered[file] += e[1]; total[file] += e[2]
        }
        END {
          for (f in total) { printf "%s %s %d/%d edges (%.0f%%)\n", t, f, covered[f], total[f], 100 * covered[f] / total[f]; c += covered[f]; n += total[f] }
          if (n) printf "%s TOTAL %d/%d edges (%.0f%%)\n", t, c, n, 100 * c / n
        }' | sort
    continue
  fi
  args=(-artifact_prefix="$build_dir/artifacts/$t-" -timeout=10 -rss_limit_mb=2048 -max_len=65536
        -print_final_stats=1)
  [ -f "tests/fuzz/dict/$t.dict" ] && args+=(-dict="tests/fuzz/dict/$t.dict")
  # The image reader points stderr at a capture file while a codec runs (oiio_backend.cpp): with
  # -close_fd_mask=2, libFuzzer and the sanitizers report on a copy of the real stderr instead, so a
  # report made inside a codec is not swallowed (the codecs' own text is then discarded).
  [ "$t" = image ] && args+=(-close_fd_mask=2)
  case "$mode" in
    ci) args+=(-runs="${ci_runs[$t]}" -seed=1) ;;
    runs) args+=(-runs="$runs") ;;
    time) args+=(-max_total_time="$seconds") ;;
  esac
  echo "fuzz: $t (${args[*]: -2})" >&2
  start=$(date +%s)
  if "$build_dir/tests/fuzz/fuzz_$t" "${args[@]}" "$corpus" > "$build_dir/fuzz_$t.log" 2>&1; then
    echo "fuzz: $t ok in $(( $(date +%s) - start )) s: $(grep -E 'stat::number_of_executed_units|stat::average_exec_per_sec' "$build_dir/fuzz_$t.log" | tr -s ' ' | tr '\n' ' ')" >&2
  else
    echo "fuzz: $t FAILED; log $build_dir/fuzz_$t.log:" >&2
    grep -E 'ERROR|SUMMARY|Test unit written|runtime error|terminate' "$build_dir/fuzz_$t.log" | head -8 >&2
    failed+=("$t")
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
