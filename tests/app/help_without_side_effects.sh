#!/usr/bin/env bash
# `--help` / `-h` on every command of ./cdlab and of the built program prints that command's usage and
# exits 0 without installing, configuring or building: the wrapper is pointed at a build folder that
# does not exist and at a PATH where apt-get, cmake and sudo fail loudly; the folder must stay absent.
# Usage: help_without_side_effects.sh REPO_ROOT BUILT_CDLAB
set -u
root="$1"; program="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/bin"
for tool in apt-get cmake sudo dpkg-query ctest make ninja; do
    printf '#!/bin/sh\necho "%s was called" >&2\nexit 99\n' "$tool" > "$tmp/bin/$tool"; chmod +x "$tmp/bin/$tool"
done
fail=0
for cmd in figures render test golden query check bench stress fuzz demos; do
    for flag in --help -h; do
        out="$(CDLAB_BUILD_DIR="$tmp/build" PATH="$tmp/bin:$PATH" "$root/cdlab" "$cmd" "$flag" 2>"$tmp/err")"; rc=$?
        if [ $rc -ne 0 ] || [ -s "$tmp/err" ] || ! grep -q "^usage: ./cdlab $cmd" <<<"$out" || ! grep -q "^  $cmd " <<<"$out"; then
            echo "FAIL ./cdlab $cmd $flag: rc $rc, stderr: $(cat "$tmp/err"), stdout: $out"; fail=1
        fi
        if [ -e "$tmp/build" ]; then echo "FAIL ./cdlab $cmd $flag created the build folder"; fail=1; fi
    done
    case "$cmd" in test|fuzz) continue ;; esac  # wrapper-only commands
    out="$("$program" "$cmd" --help 2>"$tmp/err")"; rc=$?
    if [ $rc -ne 0 ] || ! grep -q "^  $cmd " <<<"$out"; then echo "FAIL cdlab $cmd --help: rc $rc: $out"; fail=1; fi
done
# The wrapper's full usage and the program's are the same text.
if ! diff <("$root/cdlab" --help) <("$program" --help) >/dev/null; then echo "FAIL the two usage texts differ"; fail=1; fi
[ $fail -eq 0 ] && echo "help: every command answers --help and -h with its usage, nothing installed or built"
exit $fail
