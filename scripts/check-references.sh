#!/usr/bin/env bash
# Everything a user needs is in the repository: fails if the README, docs/ or any source, test,
# script or manifest points at something outside it (the team's working notes, numbered
# issues, lecture notes), or if docs/extremes.md names a test that no longer exists.
set -euo pipefail
cd "$(dirname "$0")/.."
fail=0

# Tracked text files, this script excepted.
files="$(git ls-files -- '*.rs' '*.md' '*.sh' '*.toml' '*.txt' '*.py' '.ci/*' | grep -v '^scripts/check-references.sh$')"
pattern='\.\./shared|GUIDE( §|\.md)|EXTREMES\b|[Ii]ssue [0-9]+\b|[Ss]eed [0-9]{3}\b|the seeds|seeds'"'"'|lecture notes?'
if hits="$(echo "$files" | xargs grep -nE "$pattern")"; then
  echo "check-references: references to things outside the repository:" >&2
  echo "$hits" >&2
  fail=1
else
  echo "check-references: no reference outside the repository"
fi

# Every test docs/extremes.md names exists.
tests="$(grep -hoE 'fn e[0-9]{2}_[a-z0-9_]+' crates/zrow/tests/*.rs | sed 's/^fn //' | sort -u)"
for t in $(grep -oE '`e[0-9]{2}_[a-z0-9_]+`' docs/extremes.md | tr -d '`' | sort -u); do
  if ! grep -qx "$t" <<<"$tests"; then
    echo "check-references: docs/extremes.md names $t, which no test defines" >&2
    fail=1
  fi
done
echo "check-references: $(grep -oE '`e[0-9]{2}_[a-z0-9_]+`' docs/extremes.md | sort -u | wc -l) tests named in docs/extremes.md"
exit "$fail"
