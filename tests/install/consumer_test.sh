#!/usr/bin/env bash
# The core as a library (issue 19 §3): `cmake --install` of this build into a temporary prefix, then
# a consumer project built against it with find_package(cdlab) that must print the right distance;
# the same consumer compiled with add_subdirectory(path/to/cdlab/core) from the source tree; and a
# core-only configure of the repository that looks for nothing but Eigen. Usage: consumer_test.sh REPO_ROOT BUILD_DIR
set -eu
root="$1"; build="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
test -f "$tmp/prefix/include/cdlab/core/gjk_epa/gjk.h"
test -f "$tmp/prefix/include/cdlab/core/cdlab.h"
test -f "$tmp/prefix/lib/cmake/cdlab/cdlabConfig.cmake"
# A core built with ASan + UBSan (./cdlab test --sanitize) needs the sanitizer runtimes in whatever
# links it: the consumer of that installed library links them too.
link_flags=""
grep -q '^CDLAB_SANITIZE:BOOL=ON$' "$build/CMakeCache.txt" && link_flags="-fsanitize=address,undefined"
cmake -S "$root/tests/install/consumer" -B "$tmp/installed" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
      -DCMAKE_EXE_LINKER_FLAGS="$link_flags" >/dev/null
cmake --build "$tmp/installed" -j 2 >/dev/null
"$tmp/installed/consumer"
# The installed core answers the same pairs as `cdlab query`, double for double.
"$tmp/installed/consumer" lines > "$tmp/pairs.jsonl"
"$build/bin/cdlab" query < "$tmp/pairs.jsonl" > "$tmp/answers.jsonl"
"$tmp/installed/consumer" compare < "$tmp/answers.jsonl"
# examples/engine, the README's engine example, against the same fresh install: it builds and its
# three answers (distance, manifold, ray) are the ones its comments state (exit 0).
cmake -S "$root/examples/engine" -B "$tmp/engine" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
      -DCMAKE_EXE_LINKER_FLAGS="$link_flags" >/dev/null
cmake --build "$tmp/engine" -j 2 >/dev/null
"$tmp/engine/engine_example" >/dev/null || { echo "FAIL examples/engine answered wrong:"; "$tmp/engine/engine_example"; exit 1; }
# add_subdirectory(core): configure, and compile the consumer's source against the core target's
# include directory and flags (linking it would rebuild all of core: the installed variant links).
cmake -S "$root/tests/install/consumer" -B "$tmp/subdir" -DCDLAB_CORE_DIR="$root/core" >/dev/null
make -C "$tmp/subdir" --no-print-directory main.cpp.o >/dev/null
# A core-only configure of the repository (demos and tests off) asks for Eigen alone.
cmake -S "$root" -B "$tmp/core-only" -DCDLAB_BUILD_DEMOS=OFF -DCDLAB_BUILD_TESTS=OFF >"$tmp/core-only.log"
if grep -E -i "EGL|GIF|nlohmann|doctest|PNG|OpenGL" "$tmp/core-only.log"; then
    echo "FAIL the core-only configure looked for more than Eigen"; exit 1
fi
echo "install: the find_package(cdlab) consumer builds, runs and answers as cdlab query does; examples/engine builds and answers right; add_subdirectory(core) compiles; core-only configure needs Eigen alone"
