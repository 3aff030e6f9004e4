#!/bin/sh
# tools/slurm/sweep-array.sh's site options without SLURM: a stand-in
# `sbatch` first on PATH records its arguments. --partition, --time,
# --account, --mem, --qos and --sbatch OPT reach every sbatch (each array
# of shards and the merge); SLURM's output of each task goes to
# OUTDIR/shard-%a.slurm.log (shard-OFFSET+%a past the first MAX_ARRAY) and
# OUTDIR/merge.slurm.log, never /dev/null; bad options are usage errors
# (exit 2) before anything is submitted; mc1-sweep.sh wants --scene.
#   slurm_options_test.sh SOURCE_DIR MC1
set -u
src=$1 mc1=$2
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
fail() { echo "slurm_options_test: $*" >&2; exit 1; }
mkdir "$dir/bin"
cat >"$dir/bin/sbatch" <<'FAKE'
#!/bin/sh
echo "$*" >>"$SBATCH_CALLS"
n=$(wc -l <"$SBATCH_CALLS")
echo "10$n"
FAKE
chmod +x "$dir/bin/sbatch"
export PATH="$dir/bin:$PATH" SBATCH_CALLS="$dir/calls"

: >"$dir/calls"
MAX_ARRAY=2 sh "$src/tools/slurm/mc1-sweep.sh" --partition long --time 2:00:00 --account proj1 --mem 4G --qos low \
  --sbatch --constraint=avx2 3 "$dir/out" "$mc1" --scene /shared/whitted.json --nodes 1,4,16 >"$dir/stdout" ||
  fail "mc1-sweep.sh exit $?"
[ "$(wc -l <"$dir/calls")" -eq 3 ] || fail "$(wc -l <"$dir/calls") sbatch calls, not 3 (2 arrays and the merge): $(cat "$dir/calls")"
while read -r call; do
  for opt in --partition=long --time=2:00:00 --account=proj1 --mem=4G --qos=low --constraint=avx2; do
    case " $call " in *" $opt "*) ;; *) fail "an sbatch without $opt: $call" ;; esac
  done
  case $call in *dev/null*) fail "an sbatch discards SLURM's output: $call" ;; esac
done <"$dir/calls"
sed -n 1p "$dir/calls" | grep -q -- "--array=1-2 .*--output=$dir/out/shard-%a.slurm.log .*mc1-sweep-shard.sbatch $dir/out $mc1 3 0 --scene" ||
  fail "the first array: $(sed -n 1p "$dir/calls")"
sed -n 2p "$dir/calls" | grep -q -- "--array=1-1 .*--output=$dir/out/shard-2+%a.slurm.log .* 3 2 --scene" ||
  fail "the second array: $(sed -n 2p "$dir/calls")"
sed -n 3p "$dir/calls" | grep -q -- "--dependency=afterok:101:102 --output=$dir/out/merge.slurm.log .*mc1-sweep-merge.sbatch" ||
  fail "the merge: $(sed -n 3p "$dir/calls")"
grep -q "^103$" "$dir/stdout" || fail "the merge job's id not printed: $(cat "$dir/stdout")"

# Usage errors: nothing submitted, exit 2.
: >"$dir/calls"
bad() {
  sh "$src/tools/slurm/$@" >/dev/null 2>"$dir/err"
  rc=$?
  [ "$rc" -eq 2 ] || fail "$* exit $rc, not 2"
  [ ! -s "$dir/calls" ] || fail "$*: submitted $(cat "$dir/calls")"
}
bad mc1-sweep.sh 2 "$dir/out" "$mc1" --nodes 1
grep -q "name the scene with --scene" "$dir/err" || fail "no --scene: $(cat "$dir/err")"
bad mc1-sweep.sh --sbatch constraint=avx2 2 "$dir/out" "$mc1" --scene s.json
bad mc1-sweep.sh --sbatch "--constraint avx2" 2 "$dir/out" "$mc1" --scene s.json
bad mc1-sweep.sh --partition 2 "$dir/out" "$mc1" --scene s.json
bad fp24-sweep.sh --nodelist n1 2 "$dir/out" "$mc1"
grep -q "unknown option '--nodelist'" "$dir/err" || fail "an unknown option: $(cat "$dir/err")"
echo "slurm_options_test: site options reach every sbatch; SLURM's logs per task; bad options refused"
