#!/usr/bin/env bash
# ./cdlab's build is quiet (issue 43 §3): nothing on stderr when nothing compiles, one line when
# something does, the compiler's message and "build failed" (exit 2) when it fails — run with a
# stand-in `cmake` that prints what make or ninja prints in each case, and a stand-in program; run under
# CDLAB_WERROR=1 as well as without (.ci/run sets it, and the script then reconfigures first).
# Usage: quiet_build_test.sh REPO_ROOT
set -eu
root="$1"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL ($generator, CDLAB_WERROR=$werror) $*"; echo "--- stderr:"; cat "$tmp/err"; exit 1; }
mkdir -p "$tmp/path" "$tmp/build/bin"
touch "$tmp/build/CMakeCache.txt" "$tmp/build/.cdlab-configured"  # configured, after every CMakeLists.txt
cat > "$tmp/path/cmake" <<'FAKE'
#!/usr/bin/env bash
# A configure (CI's CDLAB_WERROR=1 reconfigures first) talks and succeeds: the script must keep it quiet.
if [ "${1:-}" != "--build" ]; then echo "-- Configuring done"; exit 0; fi
if grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$2/CMakeCache.txt"; then
    # ninja takes no make options (the script must not pass --no-print-directory) and prints its own lines
    for a in "$@"; do [ "$a" != "--no-print-directory" ] || { echo "ninja: unknown option"; exit 1; }; done
    case "$FAKE_BUILD" in
        uptodate) printf '%s\n' "ninja: no work to do." ;;
        compiles) printf '%s\n' "[0/2] Re-checking globbed directories..." "[1/3] Building CXX object app/x.cpp.o" \
                                "[2/3] Linking CXX static library app/libcdlab_app.a" "[3/3] Linking CXX executable bin/cdlab" ;;
        fails) printf '%s\n' "[1/3] Building CXX object app/x.cpp.o" "FAILED: app/x.cpp.o" \
                              "app/x.cpp:3:1: error: expected ';' before '}' token" "ninja: build stopped: subcommand failed."; exit 1 ;;
    esac
    exit 0
fi
case "$FAKE_BUILD" in
    uptodate) printf '%s\n' "[ 20%] Built target cdlab_core" "[ 60%] Built target cdlab_app" "[100%] Built target cdlab" ;;
    compiles) printf '%s\n' "[ 20%] Built target cdlab_core" "[ 40%] Building CXX object app/x.cpp.o" \
                            "[ 60%] Linking CXX executable ../bin/cdlab" "[100%] Built target cdlab" ;;
    fails) printf '%s\n' "[ 40%] Building CXX object app/x.cpp.o" "app/x.cpp:3:1: error: expected ';' before '}' token"; exit 2 ;;
esac
FAKE
printf '#!/bin/sh\necho "ran $*"\n' > "$tmp/build/bin/cdlab-figures"
chmod +x "$tmp/path/cmake" "$tmp/build/bin/cdlab-figures"
run() { FAKE_BUILD="$1" PATH="$tmp/path:$PATH" CDLAB_BUILD_DIR="$tmp/build" "$root/cdlab" render --template drop > "$tmp/out" 2> "$tmp/err"; }

for generator in make ninja; do
if [ "$generator" = ninja ]; then echo "CMAKE_GENERATOR:INTERNAL=Ninja" > "$tmp/build/CMakeCache.txt"; fi
for werror in 0 1; do
export CDLAB_WERROR=$werror
run uptodate || fail "up to date: exit $?"
[ ! -s "$tmp/err" ] || fail "up to date: the build printed on stderr"
grep -qx "ran render --template drop" "$tmp/out" || fail "up to date: the program did not run"
run compiles || fail "compiles: exit $?"
[ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "compiles: more than one line on stderr"
grep -q "^cdlab: building cdlab_figures" "$tmp/err" || fail "compiles: no progress line"
set +e; run fails; status=$?; set -e
[ "$status" -eq 2 ] || fail "fails: exit $status, not 2"
grep -qF "app/x.cpp:3:1: error: expected ';'" "$tmp/err" || fail "fails: the compiler's message is not shown"
grep -q "build failed" "$tmp/err" || fail "fails: no \"build failed\""
! grep -q "ran" "$tmp/out" || fail "fails: the program ran after a failed build"
done
done
echo "quiet build (make and ninja): silent when up to date, one line when compiling, the error and exit 2 when failing"
