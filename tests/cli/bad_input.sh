#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# One case of the bad-input suite: a run of a broken scenario must stop with exit code 1 and a
# message matching REGEX, and create or replace no output.
# usage: bad_input.sh ROIFEM WORK REGEX TEMPLATE MESH [--out DIR] [OLD NEW]...
#   TEMPLATE's @MESH@ becomes MESH, then each OLD (which must occur) becomes NEW, both read with
#   printf's %b escapes (\n, \xHH), which CMake arguments cannot carry. The run goes
#   twice: into a directory holding a good result from an earlier run (which must stay as it
#   was, with nothing added) and into a directory that does not exist (which must not appear).
#   --out DIR: one run into DIR instead (an unwritable place), which must not appear.
set -uo pipefail
roifem=$1 work=$2 regex=$3 template=$4 mesh=$5
shift 5
out=""
if [ "${1:-}" = --out ]; then
  out=$2
  shift 2
fi
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work"
mkdir -p "$work"
text=$(cat "$template")
text=${text//@MESH@/$mesh}
while [ $# -ge 2 ]; do
  old=$(printf '%b' "$1") new=$(printf '%b' "$2")
  [[ $text == *"$old"* ]] || fail "'$old' does not occur in $template"
  text=${text//"$old"/"$new"}
  shift 2
done
[ $# -eq 0 ] || fail "'$1' has no replacement (CMake drops empty arguments: replace by a comment)"
printf '%s\n' "$text" > "$work/case.toml"

# Runs the case into $1; checks the exit code and the message.
refused() {
  local status=0
  "$roifem" run "$work/case.toml" --out "$1" > "$work/stdout.txt" 2> "$work/stderr.txt" || status=$?
  message=$(cat "$work/stderr.txt")
  [ "$status" -eq 1 ] || fail "exit code $status, expected 1; stderr: $message"
  grep -qE -- "$regex" <<<"$message" || fail "stderr does not match '$regex': $message"
}
snapshot() { (cd "$1" && ls -A && md5sum -- *); }

if [ -n "$out" ]; then
  refused "$out"
  [ ! -e "$out" ] || fail "$out was created"
else
  kept="$work/kept"
  mkdir "$kept"
  echo "a good result from an earlier run" > "$kept/results.h5"
  echo "its XDMF" > "$kept/results.xdmf"
  before=$(snapshot "$kept")
  refused "$kept"
  [ "$(snapshot "$kept")" = "$before" ] || fail "the earlier result in $kept was changed: $(ls -A "$kept")"
  refused "$work/fresh"
  [ ! -e "$work/fresh" ] || fail "$work/fresh was created: $(ls -A "$work/fresh")"
fi
echo "ok: refused with exit 1: $message"
