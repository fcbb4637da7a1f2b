#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# expect_failure.sh REGEX COMMAND...: passes when COMMAND exits non-zero and its stderr matches REGEX.
regex=$1
shift
err=$("$@" 2>&1 >/dev/null)
status=$?
if [ "$status" -eq 0 ]; then
  echo "expected a non-zero exit from: $*" >&2
  exit 1
fi
if ! grep -qE -- "$regex" <<<"$err"; then
  echo "stderr of '$*' does not match '$regex':" >&2
  echo "$err" >&2
  exit 1
fi
echo "exit $status: $err"
