#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Usage: tools/check_apidocs.sh BUILD_DIR
#
# Proves that the API reference's check (docs/Doxyfile.in, warnings as
# errors) catches what it is meant to. Runs BUILD_DIR/docs/Doxyfile (the
# configured one of the docs target) on copies of the public headers:
#   1. unchanged: doxygen must pass without a message;
#   2. without the doc comment of ladrc_axis_init: doxygen must fail and
#      name ladrc_axis_init as undocumented;
#   3. without the @param line of angle_rad of ladrc_axis_step: doxygen must
#      fail and name that parameter of ladrc_axis_step;
#   4. with a @ref to a name that does not exist: doxygen must fail and name
#      the reference.
set -euo pipefail

if [[ $# -ne 1 || $1 == -h || $1 == --help ]]; then
  sed -n '2,14s/^# \{0,1\}//p' "$0"
  [[ $# -eq 1 ]] && exit 0
  exit 2
fi
cd "$(dirname "${BASH_SOURCE[0]}")/.."
doxyfile=$1/docs/Doxyfile
version_h=$1/include/ladrc/version.h
for f in "$doxyfile" "$version_h"; do
  [[ -f $f ]] || { echo "check_apidocs: no $f (configure $1 with Doxygen found first)" >&2; exit 2; }
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

# Copies the headers into $tmp/<case> as the docs target reads them.
copy_headers() { # case
  local dir=$tmp/$1
  mkdir -p "$dir/include" "$dir/analysis/include" "$dir/gen/ladrc"
  cp -R include/ladrc "$dir/include/"
  cp -R analysis/include/ladrc "$dir/analysis/include/"
  cp "$version_h" "$dir/gen/ladrc/"
}

# Runs the configured Doxyfile on the copy (later settings override earlier
# ones); the messages land in $tmp/<case>.log, the status is doxygen's.
run_doxygen() { # case
  local dir=$tmp/$1
  {
    cat "$doxyfile"
    echo "INPUT = \"$dir/include/ladrc\" \"$dir/analysis/include/ladrc\" \"$dir/gen/ladrc/version.h\""
    echo "STRIP_FROM_PATH = \"$dir/include\" \"$dir/analysis/include\" \"$dir/gen\""
    echo "STRIP_FROM_INC_PATH = \"$dir/include\" \"$dir/analysis/include\" \"$dir/gen\""
    echo "OUTPUT_DIRECTORY = \"$dir/out\""
  } >"$dir/Doxyfile"
  (cd "$dir" && doxygen Doxyfile) >"$tmp/$1.log" 2>&1
}

# Edits one header of the copy with a perl substitution that must change it.
alter() { # case header perl-substitution
  local file=$tmp/$1/$2
  cp "$file" "$file.orig"
  perl -0777 -pi -e "$3" "$file"
  if cmp -s "$file" "$file.orig"; then
    echo "check_apidocs: $1: the edit of $2 changed nothing (the header moved on?)" >&2
    exit 1
  fi
  rm "$file.orig"
}

# The case must fail and its messages match the pattern (grep -E).
expect_failure() { # case pattern what
  if run_doxygen "$1"; then
    echo "FAIL: $1: doxygen passed with $3" >&2
    failures=$((failures + 1))
  elif ! grep -Eq "$2" "$tmp/$1.log"; then
    echo "FAIL: $1: doxygen failed but no message matches '$2':" >&2
    sed 's/^/  /' "$tmp/$1.log" >&2
    failures=$((failures + 1))
  else
    echo "ok: $1: doxygen failed on $3: $(grep -Em1 "$2" "$tmp/$1.log")"
  fi
}

copy_headers clean
if run_doxygen clean && [[ ! -s $tmp/clean.log ]]; then
  echo "ok: clean: the unchanged headers pass without a message"
else
  echo "FAIL: clean: the unchanged headers do not pass cleanly:" >&2
  sed 's/^/  /' "$tmp/clean.log" >&2
  failures=$((failures + 1))
fi

# The doc comment right before the declaration (no */ inside it).
copy_headers no_doc
alter no_doc include/ladrc/axis.h 's{/\*\*(?:(?!\*/).)*\*/\n(?=ladrc_status_t ladrc_axis_init\()}{}s'
expect_failure no_doc 'ladrc_axis_init\(.*is not documented' "ladrc_axis_init undocumented"

# One @param line inside the comment of ladrc_axis_step.
copy_headers no_param
alter no_param include/ladrc/axis.h \
  's{^ \*\s*\@param(?:\[\w+\])?\s+angle_rad\b[^\n]*\n(?=(?:(?!\*/).)*\*/\nladrc_fault_t ladrc_axis_step\()}{}ms'
expect_failure no_param "parameter 'angle_rad'" "the @param of angle_rad missing"
grep -q 'ladrc_axis_step' "$tmp/no_param.log" || {
  echo "FAIL: no_param: the message does not name ladrc_axis_step" >&2
  failures=$((failures + 1))
}

copy_headers bad_ref
alter bad_ref include/ladrc/axis.h 's{^( \* \@file axis\.h\n)}{$1 * See \@ref ladrc_no_such_symbol.\n}m'
expect_failure bad_ref "ladrc_no_such_symbol" "a @ref to a name that does not exist"

if [[ $failures -ne 0 ]]; then
  echo "check_apidocs: $failures case(s) failed" >&2
  exit 1
fi
echo "check_apidocs: the reference's check catches a missing doc comment, @param and @ref"
