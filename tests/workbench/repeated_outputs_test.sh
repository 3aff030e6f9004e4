#!/bin/sh
# Every output option of the mc1 commands given twice (--stats a --stats b,
# ...): refused with exit 2 and a message naming the option and both files,
# before anything runs, and no file written (the last would otherwise
# silently replace the first); but --profile, repeatable, writes every file
# (p.md and p.json from one run), and refuses one file twice.
#   repeated_outputs_test.sh MC1 SCENE WORK_DIR
set -u
mc1=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fails=0 cases=0
# twice COMMAND OPTION EXT [ARGS...]: COMMAND ARGS OPTION dir/a.EXT OPTION dir/b.EXT
twice() {
  cmd=$1 opt=$2 ext=$3
  shift 3
  cases=$((cases + 1))
  "$mc1" "$cmd" "$@" "$opt" "$dir/a.$ext" "$opt" "$dir/b.$ext" >"$dir/out" 2>"$dir/err"
  rc=$?
  if [ "$rc" -ne 2 ] || ! grep -q -- "$opt is given 2 times ($dir/a.$ext, $dir/b.$ext)" "$dir/err" ||
    [ -e "$dir/a.$ext" ] || [ -e "$dir/b.$ext" ] || [ -s "$dir/out" ]; then
    echo "repeated_outputs_test: mc1 $cmd $opt twice: exit $rc: $(cat "$dir/err")" >&2
    fails=$((fails + 1))
  fi
}
small="--size 16x16 --nodes 2"
for opt in --out:png --stats:json --gantt:svg --vcd:vcd --trace:fst --diff:png; do
  twice render "${opt%%:*}" "${opt#*:}" "$scene" $small --ref
done
# --profile is the one repeatable output: p.md (the tables) and p.json (the
# stall profile) from one run, each file by its name's ending.
cases=$((cases + 1))
"$mc1" render "$scene" $small --quiet --profile "$dir/p.md" --profile "$dir/p.json" --profile "$dir/q.json" \
  >"$dir/out" 2>"$dir/err"
rc=$?
if [ "$rc" -ne 0 ] || ! grep -q "^| step | APU cycles" "$dir/p.md" || ! grep -q '"schema": "apu-profile/2"' "$dir/p.json" ||
  ! cmp -s "$dir/p.json" "$dir/q.json"; then
  echo "repeated_outputs_test: mc1 render --profile p.md --profile p.json --profile q.json: exit $rc: $(cat "$dir/err")" >&2
  fails=$((fails + 1))
fi
rm -f "$dir/p.md" "$dir/p.json" "$dir/q.json"
cases=$((cases + 1))
"$mc1" render "$scene" $small --profile "$dir/p.md" --profile "$dir/p.md" >"$dir/out" 2>"$dir/err"
rc=$?
if [ "$rc" -ne 2 ] || ! grep -q -- "--profile and --profile name one file: $dir/p.md" "$dir/err" || [ -e "$dir/p.md" ]; then
  echo "repeated_outputs_test: mc1 render --profile p.md twice: exit $rc: $(cat "$dir/err")" >&2
  fails=$((fails + 1))
fi
for opt in --out:png --stats:json --gantt:svg --vcd:vcd; do
  twice diag "${opt%%:*}" "${opt#*:}" $small
done
mkdir -p "$dir/pts"
for opt in --json:json --csv:csv --plot:svg; do
  twice sweep "${opt%%:*}" "${opt#*:}" --scene "$scene" --size 16x16 --nodes 1 --out-dir "$dir/pts"
done
[ -z "$(ls "$dir/pts")" ] || { echo "repeated_outputs_test: a refused sweep wrote $(ls "$dir/pts")" >&2; fails=$((fails + 1)); }
twice bench-render --json json --scene "$scene" --size 16x16
echo "repeated_outputs_test: $cases cases, $fails failed"
[ "$fails" -eq 0 ]
