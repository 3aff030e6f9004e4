#!/bin/sh
# A host thread that cannot be created ends a run cleanly (issue 39): run
# as an unprivileged user under a process limit (RLIMIT_NPROC, which root
# ignores), `mc1 render --threads 8` and `fp24-regress --threads 8` must
# exit 1 naming the thread, not hang (ApuPool) or abort (std::system_error);
# fp24-regress's RTL units start no threads of their own; and mc1 render on
# a terminal renders without its progress bar's thread when it cannot start.
# Needs root (to become nobody) and setpriv/prlimit; skipped (77) without.
#   thread_limit_test.sh MC1 FP24_REGRESS SCENE
set -u
mc1=$1 regress=$2 scene=$3
[ "$(id -u)" -eq 0 ] || { echo "thread_limit_test: not root: skipped"; exit 77; }
command -v setpriv >/dev/null && command -v prlimit >/dev/null || { echo "thread_limit_test: no setpriv/prlimit: skipped"; exit 77; }
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
chmod 777 "$dir"
cp "$scene" "$dir/scene.json" && chmod 644 "$dir/scene.json"
fail() { echo "thread_limit_test: $*" >&2; exit 1; }

# as nobody, at most 3 processes and threads: the fourth thread fails.
limited() { timeout 120 setpriv --reuid=65534 --regid=65534 --clear-groups prlimit --nproc=3 "$@"; }

limited "$mc1" render "$dir/scene.json" --threads 8 --out "$dir/x.png" >"$dir/out" 2>&1
rc=$?
[ "$rc" -ne 124 ] || fail "mc1 render hung when a thread could not start"
[ "$rc" -eq 1 ] || fail "mc1 render: exit $rc, wanted 1: $(cat "$dir/out")"
grep -q "cannot start host thread [0-9]* of 8" "$dir/out" || fail "mc1 render: no message naming the thread: $(cat "$dir/out")"
[ ! -e "$dir/x.png" ] || fail "mc1 render: a frame was written"

limited "$regress" --ops float --no-oracle --threads 8 >"$dir/out" 2>&1
rc=$?
[ "$rc" -ne 124 ] || fail "fp24-regress hung when a thread could not start"
[ "$rc" -eq 1 ] || fail "fp24-regress: exit $rc, wanted 1: $(cat "$dir/out")"
grep -q "the host started [0-9]* threads and no more" "$dir/out" || fail "fp24-regress: no message naming the threads: $(cat "$dir/out")"

# On a terminal mc1 render draws a progress bar, redrawn each second by a
# thread of its own: with no thread to spare (--threads 1, a limit of 1)
# the frame is rendered without that thread. script(1) gives the terminal
# (where the host has a pseudo-terminal to give).
if command -v script >/dev/null && script -qec true /dev/null >/dev/null 2>&1; then
  timeout 120 script -qec "setpriv --reuid=65534 --regid=65534 --clear-groups prlimit --nproc=1 \
    '$mc1' render '$dir/scene.json' --threads 1 --out '$dir/tty.png'" /dev/null >"$dir/out" 2>&1
  rc=$?
  [ "$rc" -eq 0 ] || fail "mc1 render on a terminal, --threads 1, a limit of 1: exit $rc, wanted 0: $(cat "$dir/out")"
  grep -q "blocks" "$dir/out" || fail "mc1 render on a terminal: no progress bar: $(cat "$dir/out")"
  [ -s "$dir/tty.png" ] || fail "mc1 render on a terminal: no frame written"
fi

# Two workers and the main thread are all the threads fp24-regress needs:
# a verilated model makes no threads of its own (apu_rtl/verilated_context.hpp;
# Verilator 5 would give each RTL unit's context hardware_concurrency() - 1).
limited "$regress" --ops float --no-oracle --threads 2 >"$dir/out" 2>&1
rc=$?
[ "$rc" -eq 0 ] || fail "fp24-regress --threads 2 under a limit of 3: exit $rc, wanted 0: $(cat "$dir/out")"
grep -q "engines model rtl" "$dir/out" || fail "fp24-regress --threads 2: the RTL did not run: $(cat "$dir/out")"
echo "thread_limit_test: mc1 render and fp24-regress end cleanly when a thread cannot start; RTL models start none; the progress bar's thread is optional"
