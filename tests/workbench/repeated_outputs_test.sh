#!/bin/sh
# Every output option of the mc1 commands given twice (--profile p.md
# --profile p.json, --stats a --stats b, ...): refused with exit 2 and a
# message naming the option and both files, before anything runs, and no
# file written (the last would otherwise silently replace the first).
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
# The two kinds of --profile (a table, a stall profile): still one file per run.
cases=$((cases + 1))
"$mc1" render "$scene" $small --profile "$dir/p.md" --profile "$dir/p.json" >"$dir/out" 2>"$dir/err"
rc=$?
if [ "$rc" -ne 2 ] || ! grep -q -- "--profile is given 2 times ($dir/p.md, $dir/p.json)" "$dir/err" ||
  [ -e "$dir/p.md" ] || [ -e "$dir/p.json" ]; then
  echo "repeated_outputs_test: mc1 render --profile p.md --profile p.json: exit $rc: $(cat "$dir/err")" >&2
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
